"""One corpus of invalid documents (tests/data/invalid, manifest.json), rejected by BOTH
parsers — the solver's and the checker's, which share no code — with a one-line message that
names the field or word the manifest gives."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from dppverify.errors import CheckerError
from dppverify.game.instance import load_instance as checker_load
from solver.errors import DPPError
from solver.formats.movingai import read_map
from solver.game.instance_reading import load_instance as solver_load

CORPUS = Path(__file__).resolve().parent / "data" / "invalid"
MANIFEST = json.loads((CORPUS / "manifest.json").read_text())


def test_the_corpus_is_complete() -> None:
    files = {p.name for p in CORPUS.iterdir()} - {"manifest.json"}
    assert files == set(MANIFEST)
    assert len(MANIFEST) >= 20


def _one_line(exc: Exception, word: str) -> None:
    text = str(exc)
    assert "\n" not in text and text.strip()
    assert word.lower() in text.lower(), text


@pytest.mark.parametrize("name", sorted(n for n, m in MANIFEST.items() if m["kind"] == "instance"))
def test_both_instance_parsers_reject(name: str) -> None:
    word = MANIFEST[name]["names"]
    with pytest.raises(DPPError) as solver_exc:
        solver_load(CORPUS / name)
    _one_line(solver_exc.value, word)
    with pytest.raises(CheckerError) as checker_exc:
        checker_load(CORPUS / name)
    _one_line(checker_exc.value, word)


@pytest.mark.parametrize("name", sorted(n for n, m in MANIFEST.items() if m["kind"] == "map"))
def test_the_map_reader_rejects(name: str) -> None:
    with pytest.raises(DPPError) as exc:
        read_map(CORPUS / name)
    _one_line(exc.value, MANIFEST[name]["names"])
