"""The extracted Coq checker (proofs/coq: ``Kernel.decide``, proved sound in ``KSound.v``)
gives exactly the Python kernel's verdict — pass, refuted, bad-input or undecided — on the
pinned and conformance cases (two goals, and N goals with the guarantee rule), on random grids,
on random N-goal instances solved with the guarantee rule, on hypothesis-drawn two-goal and
N-goal table instances, and on mutants of every witness (labels moved by small rationals or
nulled, mixture probabilities, priors, table entries and the guarantee rule's h moved, its σ,
duals and covers moved, witness shapes broken).

The default run compares a few hundred witnesses; ``-m slow`` runs the full corpus (every
conformance and pinned case, more mutants, more drawn instances: over 1,000 witnesses).
Without ``coqc`` (``python3 dev.py coq`` builds the checker) the comparisons are skipped.
"""

from __future__ import annotations

import random
import re
from collections import Counter
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings

from tests.dppverify.kernel.test_kernel_properties import per_goal_cases, two_goal_cases
from tests.proofs._coq import KCHECK, ROOT, compare, corpus, engine_triple, mutants, translator

COQ = ROOT / "proofs" / "coq"
needs_checker = pytest.mark.skipif(not KCHECK.exists(),
                                   reason="no extracted checker (python3 dev.py coq builds it)")


def test_no_coq_file_assumes_anything() -> None:
    """Every .v file is compiled (listed in _CoqProject) and none admits, assumes or
    postulates anything (the words are refused even in comments)."""
    listed = set(re.findall(r"\S+\.v", (COQ / "_CoqProject").read_text()))
    files = {p.name for p in COQ.glob("*.v")}
    assert files == listed
    for name in files:
        text = (COQ / name).read_text()
        for word in ("Admitted", "Axiom", "Parameter", "admit"):
            assert word not in text, (name, word)
    assert "Print Assumptions KSound.kernel_sound." in (COQ / "Assumptions.v").read_text()


def _check(named: list[tuple[str, Any]]) -> Counter[tuple[str, str, str]]:
    table, bad = compare(named)
    assert not bad, bad[:5]
    return table


@needs_checker
def test_the_checkers_agree_on_pinned_and_conformance_cases_and_their_mutants() -> None:
    table = _check(list(corpus(random.Random(1), 12, 3, grids=2, ngoal=3, quick=True)))
    verdicts = {p for _, p, _ in table}
    # a constant checker could not pass: the corpus holds passes, refutations and failures
    assert {"pass", "refuted", "undecided"} <= verdicts, table
    assert sum(table.values()) >= 60


def _drawn(case: tuple[dict[str, Any], dict[str, Any]], seed: int, per: int) -> None:
    t = engine_triple(*case)
    if t is not None:
        _check([("drawn", t), *mutants(t, random.Random(seed), per)])


@needs_checker
@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(two_goal_cases())
def test_the_checkers_agree_on_drawn_two_goal_instances(case: Any) -> None:
    _drawn(case, 2, 4)


@needs_checker
@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(per_goal_cases())
def test_the_checkers_agree_on_drawn_n_goal_instances(case: Any) -> None:
    _drawn(case, 3, 4)


@pytest.mark.slow
@needs_checker
def test_the_checkers_agree_on_the_full_corpus() -> None:
    table = _check(list(corpus(random.Random(0), None, 6, grids=12, ngoal=30)))
    assert sum(table.values()) >= 1000, table


@pytest.mark.slow
@needs_checker
@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(two_goal_cases())
def test_the_checkers_agree_on_many_drawn_two_goal_instances(case: Any) -> None:
    _drawn(case, 4, 8)


@pytest.mark.slow
@needs_checker
@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(per_goal_cases())
def test_the_checkers_agree_on_many_drawn_n_goal_instances(case: Any) -> None:
    _drawn(case, 5, 8)


def test_the_glue_reads_nothing_it_should_decide() -> None:
    """The translator refuses only what the Python kernel's reader refuses (structure), and
    hands every semantic condition to the checker: a walk along no edge is a token stream."""
    import json

    tokens = translator()
    inst = {"graph": {"nodes": [{"id": "s"}, {"id": "a"}, {"id": "b"}],
                      "edges": [{"source": "s", "target": "a"}]},
            "start": "s", "goals": ["a", "b"], "prior": ["1/2", "1/2"]}
    prof = {"format": "dpp-ngoal-profile/1",
            "attacker": [[{"path": ["s", "a"], "probability": 1}],
                         [{"path": ["s", "b"], "probability": 1}]],
            "defender": {"rule": "table", "default": ["1/2", "1/2"], "entries": []}}
    ib, pb = json.dumps(inst).encode(), json.dumps(prof).encode()
    assert tokens(ib, pb, b"[").startswith("VERDICT bad-input")
    from dppverify.kernel.reading import sha256
    w = {"format": "dpp-witness/1", "instance_sha256": sha256(ib), "profile_sha256": sha256(pb),
         "denominator": 1, "distances": [[1, 0, None], [None, None, 0]],
         "types": [{"trie": [1], "exit": [1, 0, None]}, {"trie": [None], "exit": [None] * 3}]}
    assert not tokens(ib, pb, json.dumps(w).encode()).startswith("VERDICT")
