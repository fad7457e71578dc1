"""The documentation site builds with warnings as errors (``python3 dev.py docs``), renders
the figures and holds the API reference generated from the docstrings."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

from tests import _guard
from tests.test_docstrings import public_modules

ROOT = Path(__file__).resolve().parents[1]


def _dev() -> object:
    spec = importlib.util.spec_from_file_location("dev", ROOT / "dev.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_site_builds_without_warnings(tmp_path: Path) -> None:
    out = tmp_path / "html"
    cmd = _dev().docs_command(out, python=sys.executable)  # type: ignore[attr-defined]
    proc = _guard.run(cmd, capture_output=True, text=True, cwd=ROOT)
    assert proc.returncode == 0, (proc.stdout + proc.stderr)[-5000:]
    assert (out / "index.html").is_file() and (out / "docs/site/index.html").is_file()
    # the guides, the proofs and the README are pages; their figures are rendered
    for page in ("README.html", "docs/formats.html", "docs/experiments.html",
                 "proofs/NGOAL.html", "CHANGELOG.html", "dppverify/checks.html"):
        assert (out / page).is_file(), page
    images = {p.name for p in (out / "_images").iterdir()}
    assert {"paper10_map.png", "paper10_beliefs.png", "baselines.png"} <= images
    assert 'src="../_images/paper10_map.png"' in (out / "docs/experiments.html").read_text()
    # the API reference, from the docstrings (numpy sections rendered as fields)
    # exactly the public modules of docs/cli.md "Python API", each with its __all__
    api = (out / "docs/site/_generated/dppverify.html").read_text()
    assert 'id="dppverify.certify"' in api and "Parameters" in api and "Examples" in api
    generated = {p.stem for p in (out / "docs/site/_generated").glob("*.html")}
    assert generated == set(public_modules()), generated ^ set(public_modules())
