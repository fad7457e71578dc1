"""The Python API as a user meets it: solver objects straight into the checker, networkx-style
weight names, a helpful message for float priors."""

from __future__ import annotations

import json
from fractions import Fraction
from pathlib import Path
from typing import Any

import networkx as nx
import pytest

import dppverify
from dppverify.errors import InvalidInstanceError as CheckerInstanceError
from dppverify.errors import ProfileError
from solver import Instance, instance_to_json, solve
from solver.errors import InvalidInstanceError

ROOT = Path(__file__).resolve().parents[1]


def _triangle(**attrs: str) -> nx.Graph:
    name = attrs.get("name", "weight")
    g = nx.Graph()
    for u, v, w in (("s", "g2", 2), ("g2", "g1", 2), ("s", "g1", 3)):
        g.add_edge(u, v, **{name: w})
    return g


class _Wrapped:
    """Any object with ``to_json()`` (duck typing: dppverify never imports the solver)."""

    def __init__(self, doc: dict[str, Any]) -> None:
        self.doc = doc

    def to_json(self) -> dict[str, Any]:
        return self.doc


def test_certify_and_value_accept_objects_dicts_and_paths(tmp_path: Path) -> None:
    inst = Instance(_triangle(), "s", ("g1", "g2"), ("7/10", "3/10"))
    inst_doc, prof_doc = instance_to_json(inst), solve(inst).to_json()
    cert = dppverify.certify(_Wrapped(inst_doc), _Wrapped(prof_doc))
    assert cert.passed and cert.check("value.U").numbers["U"] == Fraction(12, 5)
    assert dppverify.game_value(_Wrapped(inst_doc), 3).bracket.exact == Fraction(12, 5)
    (tmp_path / "p.json").write_text(json.dumps(prof_doc))
    assert dppverify.certify(inst_doc, tmp_path / "p.json").passed
    assert dppverify.game_value(str(ROOT / "examples" / "triangle.json"), 2).bracket.closed


def test_wrong_types_are_named_errors_not_type_errors() -> None:
    with pytest.raises(CheckerInstanceError, match="got int"):
        dppverify.certify(42, {})
    inst = Instance(_triangle(), "s", ("g1", "g2"), ("7/10", "3/10"))
    with pytest.raises(ProfileError, match="dpp-profile/1"):
        dppverify.certify(inst, {})  # the solver's Instance is taken (to_json), {} is not a profile
    with pytest.raises(ProfileError, match="got float"):
        dppverify.certify(instance_to_json(inst), 1.5)


def test_weight_attribute_name_like_networkx() -> None:
    g = _triangle(name="cost")
    unit = solve(Instance(g, "s", ("g1", "g2"), ("7/10", "3/10"), weight=None))
    cost = solve(Instance(g, "s", ("g1", "g2"), ("7/10", "3/10"), weight="cost"))
    assert cost.U == Fraction(12, 5) and unit.U != cost.U
    g.add_edge("s", "x")  # no cost on this edge: an error naming it, not a silent 1
    with pytest.raises(InvalidInstanceError, match=r"edge \('s', 'x'\) has no 'cost'"):
        Instance(g, "s", ("g1", "g2"), ("7/10", "3/10"), weight="cost")


@pytest.mark.parametrize("prior, hint", [((2 / 3, 1 / 3), '("2/3", "1/3")'),
                                         ((1 / 7, 6 / 7), '("1/7", "6/7")')])
def test_inexact_float_priors_suggest_fractions(prior: tuple[float, float], hint: str) -> None:
    with pytest.raises(InvalidInstanceError) as err:
        Instance(_triangle(), "s", ("g1", "g2"), prior)
    assert hint in str(err.value) and "16" not in str(err.value).split("got")[0]
    assert repr(prior[0]) in str(err.value)  # the float as the user wrote it


def test_exact_decimal_floats_still_work() -> None:
    assert Instance(_triangle(), "s", ("g1", "g2"), (0.6, 0.4)).b1 == Fraction(3, 5)
