"""One name per concept across both packages (the glossary of docs/architecture.md).

The old names of a concept must not come back into the code of ``solver``, ``dppverify`` or
``dppio``: every Python name token is checked (comments and strings are not code), and the
bound 2**53 is written as each package's ``EXACT_FLOAT_LIMIT`` only. The deprecated aliases
that the public API keeps (``solver.StrategyPath``, ``solver.equilibrium_to_json``) are
served by ``solver/__init__.py`` as strings.
"""

from __future__ import annotations

import io
import re
import tokenize
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("solver", "dppverify", "dppio")

OLD_NAMES = {
    "StrategyPath": "StrategyWalk (a walk, not a path)",
    "primary_slot": "primary_goal_index (the goal index)",
    "primary_index": "primary_goal_index (the goal index)",
    "EXACT_FLOAT": "EXACT_FLOAT_LIMIT",
    "NGame": "Instance (one instance type for any N)",
    "NEquilibrium": "CoalitionEquilibrium",
    "solve_ngoal": "coalition_equilibrium",
    "nequilibrium_to_json": "CoalitionEquilibrium.to_json",
    "ngame_from_json": "instance_from_json",
    "ngame_from_grid": "Instance.from_grid",
    "MAX_NGOALS": "MAX_GOALS",
    "game_of": "as_instance (the checker's one door, dppverify.game.inputs)",
    "ngoal_game": "the profile's check suite (dppverify.checks.suites.suite_of)",
    "NGOAL_CHECKS": "checks_of(\"per-goal\") (one registry)",
    "NGOAL_CHECK_IDS": "check_ids(\"per-goal\") (one registry)",
    "load_profile_document": "as_profile (the checker's one door)",
}
"""Old name -> the glossary's name."""


def _code_tokens(path: Path) -> list[tuple[int, int, str]]:
    """``(type, line, text)`` of the NAME and NUMBER/OP tokens of a module (no comments or
    strings)."""
    text = path.read_text(encoding="utf-8")
    return [(tok.type, tok.start[0], tok.string)
            for tok in tokenize.generate_tokens(io.StringIO(text).readline)
            if tok.type in (tokenize.NAME, tokenize.NUMBER, tokenize.OP)]


def _modules() -> list[Path]:
    return sorted(p for package in PACKAGES for p in (ROOT / package).rglob("*.py"))


@pytest.mark.parametrize("old", sorted(OLD_NAMES))
def test_old_names_stay_out_of_the_code(old: str) -> None:
    found = [f"{p.relative_to(ROOT)}:{line}" for p in _modules()
             for kind, line, text in _code_tokens(p) if kind == tokenize.NAME and text == old]
    assert not found, f"{old} is now {OLD_NAMES[old]}: {found}"


def test_the_float64_bound_has_one_name() -> None:
    """``2**53`` appears in code only where a package defines ``EXACT_FLOAT_LIMIT``."""
    found = []
    for p in _modules():
        toks = _code_tokens(p)
        for k in range(len(toks) - 2):
            if [t[2] for t in toks[k:k + 3]] == ["2", "**", "53"]:
                before = [t[2] for t in toks[max(0, k - 2):k]]
                if before != ["EXACT_FLOAT_LIMIT", "="]:
                    found.append(f"{p.relative_to(ROOT)}:{toks[k][1]}")
    assert not found, f"write EXACT_FLOAT_LIMIT, not 2**53: {found}"


def test_the_glossary_names_what_the_test_enforces() -> None:
    glossary = (ROOT / "docs" / "architecture.md").read_text(encoding="utf-8")
    section = glossary[glossary.index("## Names (the glossary)"):]
    for old in ("StrategyPath", "primary_slot", "primary_index", "EXACT_FLOAT", "NGame",
                "NEquilibrium"):
        assert re.search(rf"`{old}`", section), f"the glossary does not name {old}"


def test_theta_is_a_goal_index_in_the_checker() -> None:
    """``theta`` names a goal index (0 .. N-1); the two-goal labelling's 1 / 2 is a ``role``:
    no ``theta`` of the checker is compared with, or drawn from, the roles 1 and 2."""
    found = []
    for p in sorted((ROOT / "dppverify").rglob("*.py")):
        toks = [t[2] for t in _code_tokens(p)]
        lines = [t[1] for t in _code_tokens(p)]
        for k in range(len(toks) - 2):
            if toks[k] == "theta" and toks[k + 1] in ("==", "!=") and toks[k + 2] in ("1", "2"):
                found.append(f"{p.relative_to(ROOT)}:{lines[k]}")
            if toks[k:k + 3] == ["for", "theta", ","] and "(" in toks[k + 3:k + 8] and any(
                    toks[j:j + 2] == ["(", "1"] for j in range(k + 3, k + 10)):
                found.append(f"{p.relative_to(ROOT)}:{lines[k]}")
    assert not found, f"a role (1 primary, 2 secondary) is named theta: {found}"
