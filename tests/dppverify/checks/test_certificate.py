"""dpp-certificate/1: JSON round trip and malformed documents."""

from __future__ import annotations

import json
from fractions import Fraction

import pytest

from dppverify import CertificateError, certify
from dppverify.certificate import Certificate, CheckRecord, verdict_of
from tests.dppverify._helpers import three_phase_doc, three_phase_profile, triangle_doc


def test_round_trip_through_json_text() -> None:
    cert = certify(three_phase_doc(), three_phase_profile(), trials=1, horizon=4)
    doc = cert.to_json()
    assert doc["format"] == "dpp-certificate/1" and doc["verdict"] == "pass"
    text = json.dumps(doc)
    again = Certificate.from_json(text)
    assert again == cert and again.to_json() == doc
    assert again.check("value.U").numbers["U"] == Fraction(71, 18)
    assert isinstance(again.check("value.U").numbers["U_lp"], float)
    assert doc["checks"][0]["numbers"]["defects"] == 0


def test_verdict_precedence() -> None:
    rec = {s: CheckRecord("x", s, "") for s in ("pass", "fail", "error", "skipped")}
    assert verdict_of((rec["pass"],)) == "pass"
    assert verdict_of((rec["pass"], rec["skipped"])) == "incomplete"
    assert verdict_of((rec["skipped"], rec["error"])) == "error"
    assert verdict_of((rec["error"], rec["fail"])) == "fail"


def test_failed_certificate_round_trips() -> None:
    prof = three_phase_profile()
    prof["attacker"]["primary"] = [{"path": [3, 1, 2], "probability": 1}]
    cert = certify(three_phase_doc(), prof, trials=1)
    assert cert.verdict == "fail"
    assert Certificate.from_json(cert.to_json()).verdict == "fail"


@pytest.mark.parametrize("doc", [
    "not json", "[]", {"format": "dpp-certificate/2"},
    {"format": "dpp-certificate/1", "checks": []},
    {"format": "dpp-certificate/1", "horizon": 1, "exact": True, "verdict": "pass",
     "checks": [{"id": "a", "status": "maybe"}]},
    {"format": "dpp-certificate/1", "horizon": 1, "exact": True, "verdict": "pass",
     "checks": [{"id": "a", "status": "fail", "message": "", "numbers": {}}]},
    {"format": "dpp-certificate/1", "horizon": 1, "exact": True, "verdict": "pass",
     "checks": [{"id": "a", "status": "pass", "numbers": {"x": "one"}}]},
])
def test_malformed_certificates(doc: object) -> None:
    with pytest.raises(CertificateError):
        Certificate.from_json(doc)


def test_record_rejects_unknown_status() -> None:
    with pytest.raises(CertificateError):
        CheckRecord("a", "maybe", "")  # type: ignore[arg-type]


def test_skipped_checks_make_the_verdict_incomplete_or_fail() -> None:
    prof = three_phase_profile()
    prof["attacker"]["secondary"] = [{"path": [3, 1, 0, 4], "probability": "1/2"},
                                     {"path": [3, 1, 2], "probability": "1/2"}]
    prof.pop("phases")
    cert = certify(three_phase_doc(), prof, trials=1)
    assert cert.check("lemma.L5.induced_beliefs").status == "skipped"
    assert cert.verdict == "fail"  # the mixed secondary is not a best response here
    assert certify(triangle_doc(), {"format": "dpp-profile/1"}).verdict == "fail"


def test_counts_are_json_integers_and_values_exact_strings() -> None:
    from dppverify.certificate import COUNT_KEYS

    doc = certify(three_phase_doc(), three_phase_profile(), trials=1, horizon=4).to_json()
    seen = set()
    for check in doc["checks"]:
        for key, value in check["numbers"].items():
            if key in COUNT_KEYS:
                assert type(value) is int, (check["id"], key, value)
                seen.add(key)
            else:
                assert value is None or isinstance(value, str | float), (check["id"], key)
    assert {"H", "walks", "prefixes", "t_II"} <= seen
    assert json.loads(json.dumps(doc))["checks"][0]["numbers"]["defects"] == 0
