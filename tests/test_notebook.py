"""The example notebook (``examples/workflow.ipynb``) is kept without outputs: it is executed
when the documentation site is built (myst-nb, in a fresh folder: it reads the map by its
bundled name, ``examples:paper10``), and ``tests/test_docs_site.py`` checks that every cell ran
and shows the results it describes, on the notebook's page.
"""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOK = ROOT / "examples" / "workflow.ipynb"


def test_the_notebook_is_stored_without_outputs() -> None:
    import nbformat

    nb = nbformat.read(NOTEBOOK, as_version=4)
    nbformat.validate(nb)
    code = [c for c in nb.cells if c.cell_type == "code"]
    assert code
    for cell in code:
        assert cell.outputs == [] and cell.execution_count is None, cell.source[:60]
        assert not cell.metadata, cell.source[:60]


def test_the_notebook_runs_from_any_folder() -> None:
    """It names the map by its bundled name, never by a path relative to the checkout."""
    import nbformat

    source = "".join(c.source for c in nbformat.read(NOTEBOOK, as_version=4).cells)
    assert 'example_path("paper10")' in source and '"examples:paper10"' in source
    assert 'Path("paper10.map")' not in source and "examples/" not in source.replace(
        "examples/workflow.ipynb", "")
