"""The CLI gives the same results as on the commit the pins were written on (before the
refactor to one model for any N).

Every case of ``cases.py`` is re-run (``runner.py``: ``dpp.main`` in-process, or the
documented command line in a subprocess) and its normalized record (exit codes, stdout,
stderr, files written) must equal ``expected/<case>.txt`` exactly. A difference is shown as a
unified diff. To re-pin after an intended change of output, run
``PYTHONPATH=. python tests/pins/make_pins.py CASE...`` and say why in the commit.
"""

from __future__ import annotations

import difflib

import pytest

from tests.pins.cases import CASES, Case
from tests.pins.runner import EXPECTED, record, run_case


def test_every_case_has_a_record_and_every_record_a_case() -> None:
    names = [c.name for c in CASES]
    assert len(names) == len(set(names)), "duplicate case names in cases.py"
    assert sorted(p.stem for p in EXPECTED.glob("*.txt")) == sorted(names)


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_cli_output_is_pinned(case: Case) -> None:
    expected = record(case).read_text(encoding="utf-8")
    got = run_case(case)
    if got != expected:
        diff = "".join(difflib.unified_diff(
            expected.splitlines(keepends=True), got.splitlines(keepends=True),
            fromfile=f"expected/{case.name}.txt", tofile="this run"))
        pytest.fail(f"the CLI output of case {case.name} changed:\n{diff}", pytrace=False)
