"""The kernel's reader of ``dpp-profile/1`` and ``dpp-ngoal-profile/1`` (``docs/formats.md``
§2, §2b): each type's mixture over walks and the Defender as a table (proofs/KERNEL.md K.0) or
the guarantee rule.

A document without its format tag is bad input; a document of the right format that is not a
well-formed profile of the instance is refuted (``docs/formats.md``, "One verdict"), with the
first defect named.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from dppverify.kernel.reading import Instance, number, parse
from dppverify.kernel.verdict import BadInput, Refuted

__all__ = ["Guarantee", "Profile", "Table", "read_profile", "walk"]

Walk = tuple[int, ...]


@dataclass(frozen=True)
class Table:
    """A table Defender: ``entries`` (prefix -> distribution over the goals, document order)
    and a ``default``: a distribution, ``"progress"`` towards goal index ``goal``, or None."""

    entries: dict[Walk, tuple[Fraction, ...]]
    default: tuple[Fraction, ...] | str | None
    goal: int = 0


@dataclass(frozen=True)
class Guarantee:
    """The guarantee rule: ``h`` and its normals (the 0/1 vectors first, then the extras)."""

    h: tuple[Fraction, ...]
    normals: tuple[tuple[int, ...], ...]


@dataclass(frozen=True)
class Profile:
    """Each type's mixture (instance goal order) as ``(walk, probability)`` pairs, and the rule."""

    mixtures: tuple[tuple[tuple[Walk, Fraction], ...], ...]
    rule: Table | Guarantee


def walk(inst: Instance, raw: Any, where: str, complete: bool) -> Walk:
    """A walk of the game from ``s0`` (``complete``: ending at its first goal; else a prefix of
    at least one step that does not continue past a goal), or refuted naming ``where``.

    Examples
    --------
    >>> from dppverify.kernel.reading import read_instance
    >>> inst = read_instance(b'''{"graph": {"nodes": [{"id": "s"}, {"id": "a"}],
    ...   "edges": [{"source": "s", "target": "a"}]}, "start": "s", "goals": ["s", "a"],
    ...   "prior": ["1/2", "1/2"]}''', None)
    >>> walk(inst, ["s"], "path", True)
    (0,)
    >>> walk(inst, ["s", "a"], "path", True)
    Traceback (most recent call last):
    dppverify.kernel.verdict.Refuted: profile: path: continues past the goal "s" at step 0
    """
    nodes = [inst.lookup(x) for x in raw] if type(raw) is list else [None]
    if not nodes or None in nodes:
        raise Refuted(f"profile: {where}: not a list of node ids of the instance")
    if nodes[0] != inst.start:
        raise Refuted(f"profile: {where}: does not start at the start {inst.show(inst.start)}")
    for t in range(1, len(nodes)):
        if inst.is_goal[nodes[t - 1]]:
            raise Refuted(f"profile: {where}: continues past the goal "
                          f"{inst.show(nodes[t - 1])} at step {t - 1}")
        if inst.graph.weight(nodes[t - 1], nodes[t]) is None:  # type: ignore[arg-type]
            raise Refuted(f"profile: {where}: no edge {inst.show(nodes[t - 1])} -> "  # type: ignore[arg-type]
                          f"{inst.show(nodes[t])} at step {t}")  # type: ignore[arg-type]
    if complete and not inst.is_goal[nodes[-1]]:  # type: ignore[index]
        raise Refuted(f"profile: {where}: ends at {inst.show(nodes[-1])}, not a goal")  # type: ignore[arg-type]
    if not complete and len(nodes) < 2:
        raise Refuted(f"profile: {where}: a table entry needs at least one step")
    return tuple(nodes)  # type: ignore[arg-type]


def _mixture(inst: Instance, raw: Any, where: str, key: str) -> tuple[tuple[Walk, Fraction], ...]:
    if type(raw) is not list or not raw:
        raise Refuted(f"profile: {where}: must be a non-empty list of walks")
    out: dict[Walk, Fraction] = {}
    for k, e in enumerate(raw):
        p = number(e.get("probability")) if type(e) is dict else None
        if p is None or p < 0:
            raise Refuted(f"profile: {where}[{k}].probability: must be a number >= 0")
        w = walk(inst, e.get(key), f"{where}[{k}].{key}", True)
        if w in out:
            raise Refuted(f"profile: {where}[{k}]: the same walk is listed twice")
        out[w] = p
    if sum(out.values()) != 1:
        raise Refuted(f"profile: {where}: probabilities sum to {sum(out.values())}, not 1")
    return tuple(out.items())


def _distribution(raw: Any, n: int, where: str) -> tuple[Fraction, ...]:
    q = [number(x) for x in raw] if type(raw) is list and len(raw) == n else [None]
    if None in q or not all(0 <= x <= 1 for x in q) or sum(q) != 1:  # type: ignore[arg-type, operator]
        raise Refuted(f"profile: {where}: must be {n} probabilities summing to 1")
    return tuple(q)  # type: ignore[arg-type]


def _two(p: Any, i: int, j: int, where: str) -> tuple[Fraction, ...]:
    x = number(p)
    if x is None or not 0 <= x <= 1:
        raise Refuted(f"profile: {where}: must be a probability")
    return (x, 1 - x) if i < j else (1 - x, x)


def read_profile(data: bytes, inst: Instance) -> Profile:
    """The profile of a document of either format, read against ``inst``.

    Examples
    --------
    >>> from dppverify.kernel.reading import read_instance
    >>> inst = read_instance(b'''{"graph": {"nodes": [{"id": "s"}, {"id": "a"}, {"id": "b"}],
    ...   "edges": [{"source": "s", "target": "a"}, {"source": "s", "target": "b"}]},
    ...   "start": "s", "goals": ["a", "b"], "prior": ["1/2", "1/2"]}''', None)
    >>> p = read_profile(b'''{"format": "dpp-profile/1", "goals": {"primary": "a",
    ...   "secondary": "b"}, "defender": {"rule": "progress", "goal": "a"},
    ...   "attacker": {"primary": [{"path": ["s", "a"], "probability": 1}],
    ...                "secondary": [{"path": ["s", "b"], "probability": 1}]}}''', inst)
    >>> p.mixtures[1], p.rule
    ((((0, 2), Fraction(1, 1)),), Table(entries={}, default='progress', goal=0))
    """
    doc = parse(data, "profile")
    fmt = doc.get("format") if type(doc) is dict else None
    n = len(inst.goals)
    if fmt == "dpp-ngoal-profile/1":
        if "goals" in doc and [inst.lookup(g) for g in doc["goals"] or [None]] != list(inst.goals):
            raise Refuted("profile: goals: must list the instance's goals in its order")
        att = doc.get("attacker")
        if type(att) is not list or len(att) != n:
            raise Refuted(f"profile: attacker: must be a list of {n} mixed strategies")
        mixtures = tuple(_mixture(inst, m, f"attacker[{t}]", "path") for t, m in enumerate(att))
        d = doc.get("defender")
        if type(d) is dict and d.get("rule") == "guarantee":
            return Profile(mixtures, _guarantee(d, n))
        if type(d) is not dict or d.get("rule") != "table" or type(d.get("entries", [])) \
                is not list:
            raise Refuted("profile: defender: must be a table or the guarantee rule")
        entries: dict[Walk, tuple[Fraction, ...]] = {}
        for k, e in enumerate(d.get("entries", [])):
            at = f"defender.entries[{k}]"
            w = walk(inst, e.get("walk") if type(e) is dict else None, f"{at}.walk", False)
            if w in entries:
                raise Refuted(f"profile: {at}: the same walk is listed twice")
            entries[w] = _distribution(e.get("probabilities"), n, f"{at}.probabilities")
        default = d.get("default")
        return Profile(mixtures, Table(entries, None if default is None else
                                       _distribution(default, n, "defender.default")))
    if fmt != "dpp-profile/1" or n != 2:
        also = ' or "dpp-profile/1"' if n == 2 else ""
        raise BadInput(f'profile: "format" must be "dpp-ngoal-profile/1"{also} for this instance')
    goals = doc.get("goals")
    pg = [inst.lookup(goals.get(k)) for k in ("primary", "secondary")] if type(goals) is dict \
        else []
    if sorted(pg, key=str) != sorted(inst.goals, key=str):
        raise Refuted("profile: goals: must name the instance's two goals")
    first = inst.goals.index(pg[0])  # type: ignore[arg-type]
    if inst.prior[first] < inst.prior[1 - first]:
        raise Refuted("profile: goals.primary: is not the instance's primary goal (larger prior)")
    att = doc.get("attacker")
    att = att if type(att) is dict else {}
    mix = [_mixture(inst, att.get(k), f"attacker.{k}", "path") for k in ("primary", "secondary")]
    d = doc.get("defender")
    g = inst.lookup(d.get("goal")) if type(d) is dict else None
    if g not in inst.goals or d.get("rule") not in ("progress", "table"):  # type: ignore[union-attr]
        raise Refuted("profile: defender: must be {\"rule\": \"progress\" or \"table\", "
                      "\"goal\": one of the instance's goals}")
    j = inst.goals.index(g)  # type: ignore[arg-type]
    mixtures = tuple(mix if first == 0 else mix[::-1])
    if d["rule"] == "progress":  # type: ignore[index]
        return Profile(mixtures, Table({}, "progress", j))
    entries = {}
    for k, e in enumerate(d.get("entries", []) if type(d.get("entries", [])) is list else [1]):  # type: ignore[union-attr]
        at = f"defender.entries[{k}]"
        w = walk(inst, e.get("walk") if type(e) is dict else None, f"{at}.walk", False)
        if w in entries:
            raise Refuted(f"profile: {at}: the same walk is listed twice")
        entries[w] = _two(e.get("probability"), j, 1 - j, f"{at}.probability")
    default = d.get("default")  # type: ignore[union-attr]
    return Profile(mixtures, Table(entries, default if default in (None, "progress") else
                                   _two(default, j, 1 - j, "defender.default"), j))


def _guarantee(d: dict[str, Any], n: int) -> Guarantee:
    h = [number(x) for x in d.get("h")] if type(d.get("h")) is list else []
    if len(h) != n or None in h:
        raise Refuted(f"profile: defender.h: must be {n} numbers")
    extras = d.get("normals", [])
    ok = type(extras) is list and len(extras) <= 64 and all(
        type(a) is list and len(a) == n and all(type(x) is int and 0 <= x <= 16 for x in a)
        and any(x > 1 for x in a) for a in extras) and len(set(map(tuple, extras))) == len(extras)
    if not ok or set(d) - {"rule", "h", "normals"}:
        raise BadInput("profile: defender.normals: must be distinct lists of N integers in "
                       "0..16, not all 0 or 1")
    units = [tuple(m >> i & 1 for i in range(n)) for m in range(1, 1 << n)]
    return Guarantee(tuple(h), tuple(units) + tuple(map(tuple, extras)))  # type: ignore[arg-type]
