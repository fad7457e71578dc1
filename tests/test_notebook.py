"""The example notebook (``examples/workflow.ipynb``) runs, and is kept without outputs.

It is executed here with nbclient, in a fresh folder holding a copy of ``examples/`` (so it
runs offline, on the bundled ``paper10.map``, and writes nothing into the checkout); every
cell must run without an error and the results it shows must be the ones it describes.
"""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOK = ROOT / "examples" / "workflow.ipynb"


def _read() -> Any:
    import nbformat

    return nbformat.read(NOTEBOOK, as_version=4)


def test_the_notebook_is_stored_without_outputs() -> None:
    import nbformat

    nb = _read()
    nbformat.validate(nb)
    code = [c for c in nb.cells if c.cell_type == "code"]
    assert code
    for cell in code:
        assert cell.outputs == [] and cell.execution_count is None, cell.source[:60]
        assert not cell.metadata, cell.source[:60]


def _text(cell: Any) -> str:
    out = []
    for o in cell.outputs:
        out.append(o.get("text", ""))
        out.append(o.get("data", {}).get("text/plain", ""))
    return "".join(out)


@pytest.mark.filterwarnings("ignore::DeprecationWarning")  # jupyter_client's own
def test_the_notebook_runs_end_to_end(tmp_path: Path) -> None:
    from nbclient import NotebookClient

    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    nb = _read()
    # no per-cell wall-clock budget (load could exceed any): a cell's work is bounded by
    # what it computes, and a hung kernel by CI's own limit
    NotebookClient(nb, timeout=None, kernel_name="python3",
                   resources={"metadata": {"path": str(tmp_path / "examples")}}).execute()
    code = [c for c in nb.cells if c.cell_type == "code"]
    errors = [o for c in code for o in c.outputs if o.output_type == "error"]
    assert not errors, errors
    shown = "\n".join(_text(c) for c in code)
    assert "Fraction(68, 5)" in shown and "Fraction(5, 22)" in shown  # U*, VoI* exactly
    assert "('pass', {'horizon': 'inf', 'truncated': False})" in shown
    assert "wrote p3.json: U = 34/3" in shown and "('dpp-value/1', 3, '34/3', True" in shown
    for png in ("paper10.png", "paper10-n3.png"):
        assert (tmp_path / "examples" / png).stat().st_size > 10_000
    images = [o for c in code for o in c.outputs if "image/png" in o.get("data", {})]
    assert len(images) == 2
    assert not (ROOT / "examples" / "p3.json").exists()
