"""N-goal strategy profiles (``dpp-ngoal-profile/1``, ``docs/formats.md`` §2b), read leniently.

Only a document that is not JSON, not an object or not tagged ``dpp-ngoal-profile/1`` raises
:class:`~dppverify.errors.ProfileError`. Everything else wrong — probabilities outside [0, 1]
or not summing to 1, walks that are not walks of the game, a Defender entry of the wrong
length, a number of types that is not N — is recorded as a defect, and the certificate then
refutes the profile (check ``ngoal.profile.wellformed``) instead of crashing.

Document::

    {"format": "dpp-ngoal-profile/1",
     "goals": [g^1, …, g^N],                       (optional; must be the instance's, in order)
     "attacker": [[{"path": [s0, …, g], "probability": p, "label": …}, …],   one list per type
                  …],
     "defender": {"rule": "table",
                  "entries": [{"walk": [s0, …, s_t], "probabilities": [q_1, …, q_N]}, …],
                  "default": [q_1, …, q_N]},        (optional)
              or {"rule": "guarantee", "h": [h_1, …, h_N]}   (dppverify.structured.guarantee)
     "value": {"U": …}}                             (optional, informative)

``attacker[θ]`` is type θ's mixed strategy over walks (type θ's goal is ``goals[θ]``); after
observing the walk ``s0 … s_t`` the Defender puts the step's weight on goal ``g^i`` with
probability ``q_i``; or the Defender is the guarantee rule of :mod:`dppverify.structured.guarantee`.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import Any

from dppverify.errors import ProfileError
from dppverify.exact import Number
from dppverify.formats.json_reading import (
    JsonReadError,
    lookup_node,
    parse_number,
    parse_probability,
    read_json_file,
    resolve_walk,
)
from dppverify.game.profile import StrategyPath
from dppverify.ngoal.instance import NInstance
from dppverify.structured.guarantee import RULE as GUARANTEE
from dppverify.structured.guarantee import GuaranteeRule, parse_guarantee

__all__ = ["NGOAL_PROFILE_FORMAT", "NProfile", "load_nprofile_document",
           "nprofile_from_json"]

NGOAL_PROFILE_FORMAT = "dpp-ngoal-profile/1"


@dataclass(frozen=True)
class NProfile:
    """An N-goal profile resolved against an instance, with its defects.

    Attributes
    ----------
    attacker : tuple
        ``attacker[θ]``: type θ's valid walks.
    entries : Mapping
        The Defender's table: walk (node indices) -> goal distribution.
    default : tuple or None
        The Defender's distribution for unlisted walks.
    claimed_u : Number or None
        The profile's ``value.U`` (informative).
    longest : int
        Steps of the longest listed walk.
    defects : tuple of str
        Everything that makes the profile ill-formed (``where: what``).
    rule : GuaranteeRule or None
        The Defender's rule when it is ``{"rule": "guarantee", ...}`` (then ``entries`` is
        empty and ``default`` None; :mod:`dppverify.structured.guarantee`).
    """

    attacker: tuple[tuple[StrategyPath, ...], ...]
    entries: Mapping[tuple[int, ...], tuple[Fraction, ...]]
    default: tuple[Fraction, ...] | None
    claimed_u: Number | None
    longest: int
    defects: tuple[str, ...]
    rule: GuaranteeRule | None = None

    @property
    def wellformed(self) -> bool:
        """True when the profile has no defect."""
        return not self.defects


def load_nprofile_document(source: str | Path | bytes) -> dict[str, Any]:
    """Read an N-goal profile (a path, or JSON bytes) and check its format tag.

    Raises
    ------
    ProfileError
        One line when it cannot be read, is not JSON or not tagged ``dpp-ngoal-profile/1``.

    Examples
    --------
    >>> load_nprofile_document(b'{"format": "dpp-profile/1"}')
    Traceback (most recent call last):
    dppverify.errors.ProfileError: profile: "format" must be "dpp-ngoal-profile/1" for an \
instance with more than two goals, got "dpp-profile/1"
    """
    name = "profile" if isinstance(source, bytes) else str(source)
    try:
        doc = read_json_file(source, kind="profile")
    except JsonReadError as exc:
        raise ProfileError(f"{name}: {exc}") from None
    if not isinstance(doc, Mapping):
        raise ProfileError(f"{name}: a profile must be a JSON object, got {type(doc).__name__}")
    if doc.get("format") != NGOAL_PROFILE_FORMAT:
        raise ProfileError(f"{name}: \"format\" must be \"{NGOAL_PROFILE_FORMAT}\" for an "
                           f"instance with more than two goals, got "
                           f"{json.dumps(doc.get('format'), default=str)}")
    return dict(doc)


def _probability(raw: Any, where: str, defects: list[str]) -> Fraction | None:
    try:
        return parse_probability(raw, where=where)
    except ValueError as exc:
        defects.append(str(exc))
        return None


def _distribution(raw: Any, n: int, where: str, defects: list[str]
                  ) -> tuple[Fraction, ...] | None:
    if not isinstance(raw, list) or len(raw) != n:
        defects.append(f"{where}: must be a list of {n} probabilities (one per goal)")
        return None
    qs = [_probability(x, f"{where}[{i}]", defects) for i, x in enumerate(raw)]
    if any(q is None for q in qs):
        return None
    out = tuple(q for q in qs if q is not None)
    if sum(out) != 1:
        defects.append(f"{where}: probabilities sum to {sum(out)}, not 1")
        return None
    return out


def nprofile_from_json(instance: NInstance, doc: Mapping[str, Any]) -> NProfile:
    """Resolve an N-goal profile document against ``instance``, recording defects.

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3, star3_profile
    >>> p = nprofile_from_json(star3(), star3_profile())
    >>> p.wellformed, [w.walk for w in p.attacker[1]], p.default
    (True, [(0, 1, 3)], (Fraction(1, 1), Fraction(0, 1), Fraction(0, 1)))
    >>> bad = {**star3_profile(), "attacker": star3_profile()["attacker"][:2]}
    >>> nprofile_from_json(star3(), bad).defects
    ('attacker: must be a list of 3 mixed strategies (one per goal), got 2',)
    """
    inst = instance
    n = inst.n_goals
    defects: list[str] = []
    longest = 0
    goals = doc.get("goals")
    if goals is not None:
        same = isinstance(goals, list) and [lookup_node(inst.index, g) for g in goals] == list(
            inst.goals)
        if not same:
            defects.append("goals: must list the instance's goals in the instance's order")
    raw_att = doc.get("attacker")
    types: list[tuple[StrategyPath, ...]] = [() for _ in range(n)]
    if not isinstance(raw_att, list) or len(raw_att) != n:
        got = len(raw_att) if isinstance(raw_att, list) else type(raw_att).__name__
        defects.append(f"attacker: must be a list of {n} mixed strategies (one per goal), "
                       f"got {got}")
    else:
        for theta, mix in enumerate(raw_att):
            where = f"attacker[{theta}]"
            if not isinstance(mix, list) or not mix:
                defects.append(f"{where}: must be a non-empty list of walks")
                continue
            walks: list[StrategyPath] = []
            total = Fraction(0)
            for j, entry in enumerate(mix):
                at = f"{where}[{j}]"
                if not isinstance(entry, Mapping) or "path" not in entry:
                    defects.append(f"{at}: must be an object with \"path\" and \"probability\"")
                    continue
                if isinstance(entry["path"], list):
                    longest = max(longest, len(entry["path"]) - 1)
                walk = resolve_walk(inst, entry["path"], complete=True, subject="")
                prob = _probability(entry.get("probability"), f"{at}.probability", defects)
                if isinstance(walk, str):
                    defects.append(f"{at}.path {walk}")
                    continue
                if prob is None:
                    continue
                if any(w.walk == walk for w in walks):
                    defects.append(f"{at}.path: the same walk is listed twice")
                    continue
                total += prob
                label = entry.get("label")
                walks.append(StrategyPath(walk, prob, None if label is None else str(label)))
            if total != 1:
                defects.append(f"{where}: probabilities sum to {total}, not 1")
            types[theta] = tuple(walks)
    entries: dict[tuple[int, ...], tuple[Fraction, ...]] = {}
    default: tuple[Fraction, ...] | None = None
    raw_def = doc.get("defender")
    rule: GuaranteeRule | None = None
    if isinstance(raw_def, Mapping) and raw_def.get("rule") == GUARANTEE:
        rule = parse_guarantee(raw_def, n, defects)
    elif not isinstance(raw_def, Mapping) or raw_def.get("rule") != "table":
        defects.append("defender: must be {\"rule\": \"table\", \"entries\": [...], "
                       "\"default\": [...]} or {\"rule\": \"guarantee\", \"h\": [...]}")
    else:
        for j, entry in enumerate(raw_def.get("entries", [])):
            at = f"defender.entries[{j}]"
            if not isinstance(entry, Mapping) or "walk" not in entry:
                defects.append(f"{at}: must be an object with \"walk\" and \"probabilities\"")
                continue
            walk = resolve_walk(inst, entry["walk"], complete=False, subject="")
            dist = _distribution(entry.get("probabilities"), n, f"{at}.probabilities", defects)
            if isinstance(walk, str):
                defects.append(f"{at}.walk {walk}")
            elif dist is not None:
                if walk in entries:
                    defects.append(f"{at}.walk: the same walk is listed twice")
                entries[walk] = dist
        if raw_def.get("default") is not None:
            default = _distribution(raw_def["default"], n, "defender.default", defects)
    claimed: Number | None = None
    value = doc.get("value")
    if isinstance(value, Mapping) and value.get("U") is not None:
        try:
            claimed = parse_number(value["U"], where="value.U")
        except ValueError as exc:
            defects.append(str(exc))
    return NProfile(attacker=tuple(types), entries=entries, default=default, claimed_u=claimed,
                    longest=longest, defects=tuple(defects), rule=rule)
