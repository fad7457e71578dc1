"""The project is a publishable package: it builds, its metadata renders, it can be cited.

- ``python -m build`` (sdist and wheel, ``--no-isolation``: the test environment has
  setuptools; a copy of the sources is built, so the checkout gets no ``build/``) and
  ``twine check`` on both files;
- the wheel holds the three packages with their typing markers and data, the ``dpp`` launcher
  and its ``dpp-python`` entry point, and the license, and no tests;
- ``CITATION.cff`` is valid Citation File Format 1.2.0 (its JSON schema, ``tests/data``) and
  states the version and license that ``pyproject.toml`` states;
- the changelog has a section for the version.
"""

from __future__ import annotations

import json
import shutil
import sys
import tomllib
import zipfile
from pathlib import Path
from typing import Any

import pytest

from tests import _guard

ROOT = Path(__file__).resolve().parents[1]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
VERSION = PYPROJECT["project"]["version"]
IGNORED = (".venv", ".git", "build", "dist", "*.egg-info", "__pycache__", ".*_cache",
           ".hypothesis", "out", "docs/_build", "_build")


@pytest.fixture(scope="module")
def dists(tmp_path_factory: pytest.TempPathFactory) -> list[Path]:
    src = tmp_path_factory.mktemp("src") / "dppverify"
    shutil.copytree(ROOT, src, ignore=shutil.ignore_patterns(*IGNORED))
    out = tmp_path_factory.mktemp("dist")
    proc = _guard.run([sys.executable, "-m", "build", "--no-isolation", "--sdist",
                       "--wheel", "--outdir", str(out), str(src)],
                      capture_output=True, text=True)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    files = sorted(out.iterdir())
    assert sorted(p.suffix for p in files) == [".gz", ".whl"], files
    return files


def test_twine_check_passes(dists: list[Path]) -> None:
    proc = _guard.run([sys.executable, "-m", "twine", "check", "--strict",
                       *map(str, dists)], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert proc.stdout.count("PASSED") == 2


def test_the_wheel_holds_the_packages_the_command_and_the_license(dists: list[Path]) -> None:
    wheel = next(p for p in dists if p.suffix == ".whl")
    assert wheel.name.startswith(f"dppverify-{VERSION}-py3-none-any")
    names = zipfile.ZipFile(wheel).namelist()
    for must in ("dppverify/py.typed", "solver/py.typed", "dppio/py.typed",
                 "dppverify/checks.md", "dppio/data/paper10.map", "dppio/data/triangle.json",
                 "dppverify/certify.py"):
        assert must in names, must
    assert not any(n.startswith(("tests/", "docs/", "benchmarks/")) for n in names)
    info = f"dppverify-{VERSION}.dist-info"
    assert f"{info}/licenses/LICENSE" in names
    entry = zipfile.ZipFile(wheel).read(f"{info}/entry_points.txt").decode()
    assert "dpp-python = dpp:console" in entry
    # `dpp` itself is the shell launcher (standard input a folder stops any Python), as is
    launcher = zipfile.ZipFile(wheel).read(f"dppverify-{VERSION}.data/scripts/dpp")
    assert launcher == (ROOT / "bin" / "dpp").read_bytes() and launcher.startswith(b"#!/bin/sh")
    meta = zipfile.ZipFile(wheel).read(f"{info}/METADATA").decode()
    for line in ("License-Expression: MIT", "Requires-Python: >=3.11",
                 "Project-URL: Paper, https://arxiv.org/abs/2506.13650"):
        assert line in meta, line


def _citation() -> dict[str, Any]:
    import yaml

    doc = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    assert isinstance(doc, dict)
    return doc


def test_citation_is_valid_cff_and_matches_the_package() -> None:
    import jsonschema

    schema = json.loads((ROOT / "tests/data/citation-cff-1.2.0.schema.json").read_text())
    doc = json.loads(json.dumps(_citation(), default=str))  # dates as strings, as in JSON
    jsonschema.Draft7Validator(schema, format_checker=jsonschema.FormatChecker()).validate(doc)
    assert doc["cff-version"] == "1.2.0" and doc["type"] == "software"
    assert doc["version"] == VERSION and doc["license"] == PYPROJECT["project"]["license"]
    paper = doc["references"][0]
    assert paper["title"] == "Deceptive Path Planning: A Bayesian Game Approach"
    assert [a["family-names"] for a in paper["authors"]] == [
        "Rostobaya", "Berneburg", "Guan", "Dorothy", "Shishika"]


def test_an_invalid_citation_is_caught() -> None:
    """The validation above can fail: a citation without authors is refused."""
    import jsonschema

    schema = json.loads((ROOT / "tests/data/citation-cff-1.2.0.schema.json").read_text())
    doc = json.loads(json.dumps(_citation(), default=str))
    del doc["authors"]
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.Draft7Validator(schema).validate(doc)


def test_the_changelog_has_this_version() -> None:
    text = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    assert f"## [{VERSION}]" in text and "## [Unreleased]" in text
