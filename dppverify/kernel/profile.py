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
from itertools import pairwise
from typing import Any

from dppverify.kernel.reading import Instance, common_denominator, number, parse
from dppverify.kernel.verdict import BadInput, Refuted

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
    nodes: Any = [inst.lookup(x) for x in raw] if type(raw) is list else [None]
    bad = ("not a list of node ids of the instance" if not nodes or None in nodes else
           f"does not start at the start {inst.show(inst.start)}" if nodes[0] != inst.start
           else next((f"continues past the goal {inst.show(v)} at step {t}" if inst.is_goal[v]
                      else f"no edge {inst.show(v)} -> {inst.show(u)} at step {t + 1}"
                      for t, (v, u) in enumerate(pairwise(nodes))
                      if inst.is_goal[v] or inst.graph.weight(v, u) is None), None))
    if bad is None and complete and not inst.is_goal[nodes[-1]]:
        bad = f"ends at {inst.show(nodes[-1])}, not a goal"
    if bad is None and not complete and len(nodes) < 2:
        bad = "a table entry needs at least one step"
    if bad is not None:
        raise Refuted(f"profile: {where}: {bad}")
    return tuple(nodes)


def _mixture(inst: Instance, raw: Any, where: str) -> tuple[tuple[Walk, Fraction], ...]:
    if type(raw) is not list or not raw:
        raise Refuted(f"profile: {where}: must be a non-empty list of walks")
    out: dict[Walk, Fraction] = {}
    for k, e in enumerate(raw):
        p = number(e.get("probability")) if type(e) is dict else None
        if p is None or p < 0:
            raise Refuted(f"profile: {where}[{k}].probability: must be a number >= 0")
        w = walk(inst, e.get("path"), f"{where}[{k}].path", True)
        if w in out:
            raise Refuted(f"profile: {where}[{k}]: the same walk is listed twice")
        out[w] = p
    common_denominator((p.denominator for p in out.values()), f"profile: {where}", 1000)
    if sum(out.values()) != 1:
        raise Refuted(f"profile: {where}: probabilities sum to {sum(out.values())}, not 1")
    return tuple(out.items())


def _dist(raw: Any, n: int, where: str, goal: int | None) -> tuple[Fraction, ...]:
    """A distribution over the ``n`` goals; with ``goal``, a probability on that goal (two
    goals: the rest on the other)."""
    q = [number(raw)] if goal is not None else [number(x) for x in raw] if type(raw) is list \
        and len(raw) == n else [None]
    if None in q or not all(0 <= x <= 1 for x in q) or (goal is None and sum(q) != 1):  # type: ignore[operator, arg-type]
        what = "a probability" if goal is not None else f"{n} probabilities summing to 1"
        raise Refuted(f"profile: {where}: must be {what}")
    return tuple(q) if goal is None else (q[0], 1 - q[0]) if goal == 0 else (1 - q[0], q[0])  # type: ignore[return-value, operator, arg-type]


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
    fmt, n = doc.get("format") if type(doc) is dict else None, len(inst.goals)
    two = fmt == "dpp-profile/1" and n == 2
    if fmt != "dpp-ngoal-profile/1" and not two:
        also = ' or "dpp-profile/1"' if n == 2 else ""
        raise BadInput(f'profile: "format" must be "dpp-ngoal-profile/1"{also} for this instance')
    d, att, goals = (doc.get(k) for k in ("defender", "attacker", "goals"))
    d = d if type(d) is dict else {}
    j: int | None = None
    if two:
        pg = [inst.lookup(goals.get(k)) for k in ("primary", "secondary")] \
            if type(goals) is dict else []
        if sorted(pg, key=str) != sorted(inst.goals, key=str):
            raise Refuted("profile: goals: must name the instance's two goals")
        first = inst.goals.index(pg[0])
        if inst.prior[first] < inst.prior[1 - first]:
            raise Refuted("profile: goals.primary: is not the instance's primary goal")
        att = att if type(att) is dict else {}
        att = [att.get(k) for k in (("primary", "secondary") if first == 0 else
                                    ("secondary", "primary"))]
        g = inst.lookup(d.get("goal"))
        if g not in inst.goals:
            raise Refuted("profile: defender.goal: must be one of the instance's goals")
        j = inst.goals.index(g)
    elif goals is not None and (type(goals) is not list or
                                [inst.lookup(x) for x in goals] != list(inst.goals)):
        raise Refuted("profile: goals: must list the instance's goals in its order")
    if type(att) is not list or len(att) != n:
        raise Refuted(f"profile: attacker: must hold {n} mixed strategies, one per goal")
    names = ("primary", "secondary") if two and first == 0 else ("secondary", "primary")
    mixtures = tuple(_mixture(inst, m, f"attacker.{names[t]}" if two else f"attacker[{t}]")
                     for t, m in enumerate(att))
    rule = d.get("rule")
    if rule == "guarantee" and not two:
        return Profile(mixtures, _guarantee(d, n))
    if rule not in (("progress", "table") if two else ("table",)) or \
            type(d.get("entries", [])) is not list:
        raise Refuted("profile: defender: not a rule of this profile format")
    if rule == "progress":
        return Profile(mixtures, Table({}, "progress", j))  # type: ignore[arg-type]
    entries: dict[Walk, tuple[Fraction, ...]] = {}
    key = "probability" if two else "probabilities"
    for k, e in enumerate(d.get("entries", [])):
        at = f"defender.entries[{k}]"
        w = walk(inst, e.get("walk") if type(e) is dict else None, f"{at}.walk", False)
        if w in entries:
            raise Refuted(f"profile: {at}: the same walk is listed twice")
        entries[w] = _dist(e.get(key), n, f"{at}.{key}", j)
    q = d.get("default")
    return Profile(mixtures, Table(entries, q if q is None or (two and q == "progress") else
                                   _dist(q, n, "defender.default", j), j or 0))


def _guarantee(d: dict[str, Any], n: int) -> Guarantee:
    h = [number(x) for x in d["h"]] if type(d.get("h")) is list else []
    extras = d.get("normals", [])
    if len(h) != n or None in h:
        raise Refuted(f"profile: defender.h: must be {n} numbers")
    ok = type(extras) is list and len(extras) <= 64 and all(
        type(a) is list and len(a) == n and all(type(x) is int and 0 <= x <= 16 for x in a)
        and any(x > 1 for x in a) for a in extras) and len(set(map(tuple, extras))) == len(extras)
    if not ok or set(d) - {"rule", "h", "normals"}:
        raise BadInput("profile: defender.normals: must be distinct lists of N integers in "
                       "0..16, not all 0 or 1")
    units = (tuple(m >> i & 1 for i in range(n)) for m in range(1, 1 << n))
    return Guarantee(tuple(h), (*units, *map(tuple, extras)))  # type: ignore[arg-type]
