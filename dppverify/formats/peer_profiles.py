"""Behaviour profiles written by the peers, Gambit and OpenSpiel, of a game ``dpp export-efg``
wrote: read them, and turn their floats into exact rationals with a stated tolerance.

Three forms are read (``dpp import-profile``; ``docs/formats.md`` §2c):

- **Gambit, a profile line** as ``gambit-lp``, ``gambit-lcp`` and ``gambit-logit`` print it:
  ``NE,p1,p2,...``, one probability per action of every information set, players in order
  (the Attacker, then the Defender), each player's information sets by number, each one's
  actions in file order (pygambit's order too: ``[profile[a] for a in game.actions]`` when the
  game has no chance actions among them, else per player, infoset, action);
- **Gambit or any tool, by name**: a JSON object ``{infoset label: {action label:
  probability}}`` (from pygambit: ``{i.label: {a.label: str(profile[a]) for a in i.actions}
  for p in game.players for i in p.infosets}``);
- **OpenSpiel, a tabular policy**: ``json.dump(policy.to_dict(), f)`` for a
  ``TabularPolicy`` (CFR's ``average_policy()``, the sequence-form LP's policies): a JSON
  object ``{information state string: [[action id, probability], ...]}``; the string is
  OpenSpiel's ``"<player>-<player>-<infoset>-<label>"`` for an ``.efg`` game, the ids its
  global action ids (action names by first appearance in the file).

A probability is exact when it is an integer or a ``p/q`` string, a float otherwise (JSON
numbers with a fraction or exponent, decimal strings). :func:`rationalise` makes every
distribution exact: each float becomes the simplest rational within ``tolerance`` of it
(:func:`simplest_within`; with tolerance 0 its exact binary value), and a distribution that
then does not sum to exactly 1 is scaled to; the largest change is reported.

Examples
--------
>>> prof = parse_peer_profile('NE,1/2,1/2,0.25,0.75', "p.csv")
>>> prof.source, prof.flat
('gambit', (Fraction(1, 2), Fraction(1, 2), 0.25, 0.75))
>>> sets = [Infoset(1, 1, "T1 p0", ("go a", "go b")),
...         Infoset(2, 1, "D p1 h-", ("alloc a", "alloc b"))]
>>> beh = prof.behaviour(sets, ["go a", "go b", "alloc a", "alloc b"])
>>> exact, report = rationalise(beh, 1e-9)
>>> exact["D p1 h-"], report.floats, report.max_change
({'alloc a': Fraction(1, 4), 'alloc b': Fraction(3, 4)}, 2, 0.0)
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from dppio.inputs import read_input
from dppio.limits import check_json_depth, check_numeral
from dppio.text import count, decimal
from dppverify.errors import ProfileError

Number = Fraction | float
Behaviour = dict[str, dict[str, Number]]
"""Information set label -> action label -> probability."""

_EXACT = re.compile(r"\s*-?\d+\s*(/\s*\d+\s*)?")
_OPENSPIEL_KEY = re.compile(r"-?\d+-\d+-\d+-(.*)", re.S)
SUM_SLACK = 1e-6
"""A float distribution whose sum is off 1 by more than this is refused (not rounding)."""


@dataclass(frozen=True)
class Infoset:
    """An information set of the exported game: Gambit player (1 the Attacker, 2 the Defender),
    its number, label and action labels (file order)."""

    player: int
    number: int
    label: str
    actions: tuple[str, ...]


@dataclass(frozen=True)
class PeerProfile:
    """A peer's behaviour profile as read, before it is matched to the game.

    Attributes
    ----------
    source : {"gambit", "openspiel"}
        The form (module docstring): ``gambit`` (a profile line, or by name), ``openspiel``.
    name : str
        The file, for messages.
    flat : tuple or None
        A Gambit profile line's probabilities, in Gambit's order.
    by_label : dict or None
        Information set label -> action label -> probability.
    by_action_id : dict or None
        Information set label -> [(OpenSpiel action id, probability)].
    """

    source: str
    name: str
    flat: tuple[Number, ...] | None = None
    by_label: Mapping[str, Mapping[str, Number]] | None = None
    by_action_id: Mapping[str, tuple[tuple[int, Number], ...]] | None = None

    @property
    def description(self) -> str:
        """What was read, for the command's report."""
        if self.source == "openspiel":
            return "OpenSpiel's tabular policy"
        return "Gambit's profile line" if self.flat is not None else "a behaviour profile by name"

    def behaviour(self, infosets: Sequence[Infoset], action_names: Sequence[str]) -> Behaviour:
        """The probabilities per information set and action of the game whose information sets
        (Gambit's order) and global action names (first appearance: OpenSpiel's ids) are
        given; every information set must be there, nothing else.

        Raises
        ------
        ProfileError
            A missing or unknown information set or action (one line, naming it).
        """
        wanted = {s.label: s.actions for s in infosets}
        if self.flat is not None:
            size = sum(len(s.actions) for s in infosets)
            if len(self.flat) != size:
                raise ProfileError(f"{self.name}: {len(self.flat)} probabilities, but the game "
                                   f"has {size} actions at its {len(infosets)} information sets "
                                   "(another horizon, --attacker-blind or --forced-moves?)")
            it = iter(self.flat)
            return {s.label: {a: next(it) for a in s.actions} for s in infosets}
        if self.by_action_id is not None:
            raw: dict[str, dict[str, Number]] = {}
            for label, pairs in self.by_action_id.items():
                row = raw.setdefault(label, {})
                for action, p in pairs:
                    if not 0 <= action < len(action_names):
                        raise ProfileError(f"{self.name}: {label!r}: action id {action} is not "
                                           f"one of the game's {len(action_names)}")
                    name = action_names[action]
                    if name in wanted.get(label, ()):
                        row[name] = p
                    elif p != 0:  # OpenSpiel lists every action, illegal ones at 0
                        raise ProfileError(f"{self.name}: {label!r}: action {name!r} (id "
                                           f"{action}) is not legal there, probability {p}")
        else:
            assert self.by_label is not None
            raw = {label: dict(row) for label, row in self.by_label.items()}
        unknown = sorted(set(raw) - set(wanted))
        missing = [s.label for s in infosets if s.label not in raw]
        if unknown or missing:
            what = (f"information set {unknown[0]!r} is not in the game" if unknown else
                    f"information set {missing[0]!r} of the game is missing")
            raise ProfileError(f"{self.name}: {what} ({len(unknown)} unknown, {len(missing)} "
                               "missing: was the .efg exported with another horizon, "
                               "--attacker-blind or --forced-moves?)")
        out: Behaviour = {}
        for s in infosets:
            row = raw[s.label]
            extra = sorted(set(row) - set(s.actions))
            if extra:
                raise ProfileError(f"{self.name}: {s.label!r} has no action {extra[0]!r} "
                                   f"(its actions: {', '.join(s.actions)})")
            out[s.label] = {a: row.get(a, Fraction(0)) for a in s.actions}
        return out


def _number(value: Any, where: str) -> Number:
    """A probability as given: exact (integer, ``p/q``) or a float."""
    if isinstance(value, bool):
        raise ProfileError(f"{where}: {value!r} is not a probability")
    if isinstance(value, int):
        return Fraction(value)
    if isinstance(value, float):
        x = value
    elif isinstance(value, str):
        text = value.strip()
        if _EXACT.fullmatch(text):
            try:
                return Fraction(text.replace(" ", ""))
            except ZeroDivisionError:
                raise ProfileError(f"{where}: {value!r} divides by zero") from None
        try:
            x = float(text)
        except ValueError:
            raise ProfileError(f"{where}: {value!r} is not a probability") from None
    else:
        raise ProfileError(f"{where}: {value!r} is not a probability")
    if not math.isfinite(x):
        raise ProfileError(f"{where}: {value!r} is not a probability")
    return x


def parse_peer_profile(text: str, name: str) -> PeerProfile:
    """Read a peer's behaviour profile from its text (the form is recognised, module
    docstring).

    Raises
    ------
    ProfileError
        Not one of the forms, or a value that is not a probability (one line).

    Examples
    --------
    >>> p = parse_peer_profile('{"0-0-1-T1 p0 h-": [[0, 0.5], [1, 0.5], [2, 0.0]]}', "x.json")
    >>> p.source, p.by_action_id
    ('openspiel', {'T1 p0 h-': ((0, 0.5), (1, 0.5), (2, 0.0))})
    >>> parse_peer_profile('{"T1 p0": {"go a": "1/3", "go b": "2/3"}}', "x.json").by_label
    {'T1 p0': {'go a': Fraction(1, 3), 'go b': Fraction(2, 3)}}
    >>> parse_peer_profile("hello", "x.txt")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.ProfileError: x.txt is not a behaviour profile: ...
    """
    stripped = text.strip()
    if stripped.startswith(("{", "[")):
        def number(numeral: str) -> float:
            check_numeral(numeral, where=f"{name}: JSON number", error=ProfileError)
            return float(numeral)

        try:
            doc = json.loads(text, parse_float=number, parse_constant=_no_constant)
        except RecursionError:
            raise ProfileError(f"{name}: JSON nested too deep") from None
        except ValueError as exc:
            if isinstance(exc, ProfileError):
                raise
            raise ProfileError(f"{name}: not JSON ({exc})") from None
        check_json_depth(doc, error=ProfileError)
        return _from_json(doc, name)
    lines = [line.strip() for line in stripped.splitlines() if line.strip()]
    profiles = [line for line in lines if line.startswith("NE,")]
    if not profiles:
        raise ProfileError(f"{name} is not a behaviour profile: expected Gambit's 'NE,...' line "
                           "or a JSON object (OpenSpiel's TabularPolicy.to_dict(), or "
                           "{infoset: {action: probability}})")
    if len(profiles) > 1:
        raise ProfileError(f"{name} holds {len(profiles)} profiles (NE lines): keep the one to "
                           "import")
    fields = profiles[0].split(",")[1:]
    return PeerProfile("gambit", name, flat=tuple(
        _number(f, f"{name}: probability {k + 1}") for k, f in enumerate(fields)))


def _no_constant(name: str) -> Any:
    raise ValueError(f"non-finite number {name} is not allowed")


def read_peer_profile(path: str) -> PeerProfile:
    """:func:`parse_peer_profile` of a file (bounded read, UTF-8; ``-`` is standard input).

    Raises
    ------
    ProfileError
        The file cannot be read, or is not a behaviour profile (one line).

    Examples
    --------
    >>> import os, tempfile
    >>> with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as f:
    ...     _ = f.write("NE,1/2,1/2\\n")
    >>> read_peer_profile(f.name).flat
    (Fraction(1, 2), Fraction(1, 2))
    >>> os.unlink(f.name)
    >>> read_peer_profile("/nowhere/p.csv")
    Traceback (most recent call last):
    dppverify.errors.ProfileError: cannot read /nowhere/p.csv: No such file or directory
    """
    try:
        raw = read_input(path)
    except (OSError, ValueError) as exc:
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else exc
        raise ProfileError(f"cannot read {path}: {reason}") from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        raise ProfileError(f"{path} is not a behaviour profile: not UTF-8 text") from None
    return parse_peer_profile(text, str(path))


def _from_json(doc: Any, name: str) -> PeerProfile:
    if not isinstance(doc, dict) or not doc:
        raise ProfileError(f"{name} is not a behaviour profile: expected a non-empty JSON object "
                           "of information sets")
    if all(isinstance(v, list) for v in doc.values()):
        table: dict[str, tuple[tuple[int, Number], ...]] = {}
        for key, pairs in doc.items():
            m = _OPENSPIEL_KEY.fullmatch(key)
            if m is None:
                raise ProfileError(f"{name}: {key!r} is not an OpenSpiel information state of "
                                   "an .efg game ('<player>-<player>-<infoset>-<label>')")
            row = []
            for pair in pairs:
                if not (isinstance(pair, list) and len(pair) == 2 and isinstance(pair[0], int)
                        and not isinstance(pair[0], bool)):
                    raise ProfileError(f"{name}: {key!r}: expected [action id, probability] "
                                       f"pairs, got {pair!r}")
                row.append((pair[0], _number(pair[1], f"{name}: {key!r}")))
            if m.group(1) in table:
                raise ProfileError(f"{name}: information set {m.group(1)!r} appears twice")
            table[m.group(1)] = tuple(row)
        return PeerProfile("openspiel", name, by_action_id=table)
    if all(isinstance(v, dict) for v in doc.values()):
        by_label = {label: {str(a): _number(p, f"{name}: {label!r}, {a!r}")
                            for a, p in row.items()} for label, row in doc.items()}
        return PeerProfile("gambit", name, by_label=by_label)
    raise ProfileError(f"{name} is not a behaviour profile: expected {{infoset: [[action id, "
                       "probability], ...]}} (OpenSpiel) or {infoset: {action: probability}}")


def simplest_within(x: float, tolerance: float) -> Fraction:
    """The rational with the smallest denominator in ``[x - tolerance, x + tolerance]``
    (clipped at 0; ``x`` itself, exactly, when the tolerance is 0).

    Examples
    --------
    >>> simplest_within(0.5714285714285714, 1e-9), simplest_within(1e-17, 1e-9)
    (Fraction(4, 7), Fraction(0, 1))
    >>> simplest_within(0.1, 0) == Fraction(0.1)
    True
    """
    exact = Fraction(x)
    if tolerance == 0:
        return exact
    tol = Fraction(tolerance)
    lo, hi = max(exact - tol, Fraction(0)), exact + tol
    return _simplest(lo, hi)


def _simplest(lo: Fraction, hi: Fraction) -> Fraction:
    """The simplest rational in ``[lo, hi]`` (``0 <= lo <= hi``): continued fractions."""
    floor = lo.numerator // lo.denominator
    if floor == lo or floor + 1 <= hi:
        return Fraction(floor if floor == lo else floor + 1)
    inner = _simplest(1 / (hi - floor), 1 / (lo - floor))
    return floor + 1 / inner


@dataclass(frozen=True)
class Rationalisation:
    """What :func:`rationalise` did: how many probabilities were floats, the tolerance, and the
    largest change it made to one (after the scaling to sum 1)."""

    floats: int
    tolerance: float
    max_change: float

    def summary(self) -> str:
        """One phrase for the command's report.

        Examples
        --------
        >>> Rationalisation(0, 1e-9, 0.0).summary()
        'every probability exact'
        >>> print(Rationalisation(3, 1e-9, 2.5e-17).summary())
        3 float probabilities made exact (simplest rational within 1×10^-9, largest change \
2.5×10^-17)
        """
        if not self.floats:
            return "every probability exact"
        return (f"{count(self.floats, 'float probability')} made exact (simplest rational "
                f"within {decimal(self.tolerance)}, largest change {decimal(self.max_change)})")

    def to_json(self) -> dict[str, Any]:
        """The record a profile keeps under ``solver.rationalised``."""
        return {"floats": self.floats, "tolerance": self.tolerance,
                "max_change": self.max_change}


def rationalise(behaviour: Behaviour, tolerance: float
                ) -> tuple[dict[str, dict[str, Fraction]], Rationalisation]:
    """Every distribution exact: floats snapped (:func:`simplest_within`), then each
    distribution scaled to sum to exactly 1 when it does not.

    Raises
    ------
    ProfileError
        A negative probability, a distribution summing to 0 or off 1 by more than
        :data:`SUM_SLACK` (floats) or at all (exact numbers).

    Examples
    --------
    >>> exact, report = rationalise({"D p1 h-": {"alloc a": 1 / 3, "alloc b": 2 / 3}}, 1e-9)
    >>> exact, report.floats
    ({'D p1 h-': {'alloc a': Fraction(1, 3), 'alloc b': Fraction(2, 3)}}, 2)
    >>> rationalise({"D p1 h-": {"alloc a": Fraction(1, 2)}}, 1e-9)
    Traceback (most recent call last):
    dppverify.errors.ProfileError: 'D p1 h-': the probabilities sum to 0.5, not 1
    """
    out: dict[str, dict[str, Fraction]] = {}
    floats, change = 0, 0.0
    for label, row in behaviour.items():
        snapped = {a: simplest_within(p, tolerance) if isinstance(p, float) else p
                   for a, p in row.items()}
        floats += sum(isinstance(p, float) for p in row.values())
        if any(p < 0 for p in row.values()):
            a = next(a for a, p in row.items() if p < 0)
            raise ProfileError(f"{label!r}: action {a!r} has a negative probability {row[a]}")
        total = sum(snapped.values(), Fraction(0))
        has_floats = any(isinstance(p, float) for p in row.values())
        if total == 0 or abs(total - 1) > (SUM_SLACK if has_floats else 0):
            raise ProfileError(f"{label!r}: the probabilities sum to {decimal(total)}, not 1")
        if total != 1:
            snapped = {a: p / total for a, p in snapped.items()}
        change = max([change, *(abs(float(snapped[a] - Fraction(p))) for a, p in row.items())])
        out[label] = snapped
    return out, Rationalisation(floats, tolerance, change)
