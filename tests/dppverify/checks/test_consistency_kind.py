"""Consistency checks (two computations of the checker's own) are reported apart from the
evidence: outside the ``N/M checks passed`` count, under their own heading in the text report
and with ``kind`` in the certificate; the verdict still counts them. The telescoping check
can fail: it multiplies σ*'s probabilities by the step weights instead of reusing σ*'s
stored increments."""

from __future__ import annotations

import dataclasses
from fractions import Fraction

from dppverify import certify
from dppverify.certificate import Certificate, CheckRecord
from dppverify.checks.lemmas import OFF_XI2, l5_induced_beliefs, telescoping
from dppverify.cli.table import CONSISTENCY_HEADING, FACTS_HEADING, format_table
from dppverify.registry import checks_of
from tests.dppverify._helpers import three_phase_doc, three_phase_profile
from tests.dppverify.checks.doctest_inputs import triangle_context

CONSISTENCY = {c.id for c in checks_of("two-goal") if c.kind == "consistency"}
FACTS = {c.id for c in checks_of("two-goal") if c.kind == "fact"}


def test_the_registry_names_the_consistency_checks() -> None:
    assert CONSISTENCY == {"pbne.belief_consistency", "lemma.TEL.telescoping"}


def test_the_pass_count_leaves_consistency_checks_out() -> None:
    cert = certify(three_phase_doc(), three_phase_profile(), trials=1, horizon=4)
    evidence = len(cert.checks) - len(CONSISTENCY) - len(FACTS)
    assert cert.counts() == {"check": (evidence, evidence),
                             "consistency": (len(CONSISTENCY), len(CONSISTENCY)),
                             "fact": (len(FACTS), len(FACTS))}
    lines = format_table(cert).splitlines()
    assert lines[0].startswith(f"verdict: PASS for the game truncated at H = 4 ({evidence}/"
                               f"{evidence} checks passed; {len(CONSISTENCY)}/"
                               f"{len(CONSISTENCY)} consistency checks agree;")
    rows = [line for line in lines if not line.startswith(" ")]  # wrapped numbers continue
    cut = rows.index(CONSISTENCY_HEADING)
    facts = rows.index(FACTS_HEADING)
    above = {line.split()[0] for line in rows[3:cut]}   # verdict, note, column heads
    below = {line.split()[0] for line in rows[cut + 1:facts]}
    assert below == CONSISTENCY and not above & CONSISTENCY and len(above) == evidence
    assert {line.split()[0] for line in rows[facts + 1:-1]} == FACTS
    assert rows[-1].startswith("exploitability on the game truncated at H = 4: NashConv 0 = ")
    doc = cert.to_json()
    assert {r["id"] for r in doc["checks"] if r["kind"] == "consistency"} == CONSISTENCY
    assert doc["counts"]["check"] == {"passed": evidence, "total": evidence}
    assert Certificate.from_json(doc) == cert


def test_a_failed_consistency_check_is_not_counted_but_fails_the_verdict() -> None:
    cert = certify(three_phase_doc(), three_phase_profile(), trials=1, horizon=4)
    broken = tuple(dataclasses.replace(r, status="fail", message="disagree")
                   if r.id == "lemma.TEL.telescoping" else r for r in cert.checks)
    bad = dataclasses.replace(cert, checks=broken)
    evidence = len(cert.checks) - len(CONSISTENCY) - len(FACTS)
    assert bad.verdict == "fail"
    assert bad.counts()["check"] == (evidence, evidence)
    assert bad.counts()["consistency"] == (len(CONSISTENCY) - 1, len(CONSISTENCY))
    head = format_table(bad).splitlines()[0]
    assert f"({evidence}/{evidence} checks passed; 1/2 consistency checks agree;" in head


def test_a_record_of_an_unknown_id_counts_as_evidence() -> None:
    assert CheckRecord("some.future.check", "pass", "").kind == "check"


def test_telescoping_fails_when_sigma_star_probabilities_are_off() -> None:
    ctx = triangle_context()
    assert telescoping(ctx).status == "pass"
    s1 = list(ctx.sigma_star.sigma1)
    s1[2] = Fraction(1, 3)   # s -> g2: σ*(g1) is 1/2 (progress 1 over weight 2)
    off = dataclasses.replace(ctx, sigma_star=dataclasses.replace(ctx.sigma_star,
                                                                  sigma1=tuple(s1)))
    r = telescoping(off)
    assert r.status == "fail" and r.numbers["sum_violations"] == 1


def test_l5_says_the_belief_off_xi2_is_not_evidence() -> None:
    r = l5_induced_beliefs(triangle_context())
    assert r.status == "pass" and r.message.endswith(OFF_XI2)


def test_a_failed_fact_never_decides_the_verdict() -> None:
    """The paper's lemmas and construction are reported beside the verdict."""
    cert = certify(three_phase_doc(), three_phase_profile(), trials=1, horizon=4)
    for fid in FACTS:
        for status in ("fail", "skipped", "error"):
            off = tuple(dataclasses.replace(r, status=status) if r.id == fid else r
                        for r in cert.checks)
            assert dataclasses.replace(cert, checks=off).verdict == "pass"
