"""Per ``dpp certify``, each input file is opened once and parsed once, for two and N goals.

Every way a file can be opened (``builtins.open``, ``os.open``: the bounded reader of
``dppio.inputs`` opens with ``os.open``) and every JSON parse (``json.loads``, which the
checker's exact parser calls) is counted while the command runs; the certificate's provenance
then hashes the bytes that were parsed, so it must still record each file's sha256.
"""

from __future__ import annotations

import builtins
import hashlib
import json
import os
from collections import Counter
from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner

from dppverify.cli.certify import certify_command
from dppverify.game.examples import (
    star3_document,
    star3_profile,
    triangle_document,
    triangle_profile,
)

CASES = {
    "two goals": (triangle_document(), triangle_profile()),
    "N goals": (star3_document(), star3_profile()),
    "two goals, a per-goal profile": (triangle_document(), {
        "format": "dpp-ngoal-profile/1", "goals": ["g1", "g2"],
        "attacker": [[{"path": ["s", "g1"], "probability": "4/7"},
                      {"path": ["s", "g2"], "probability": "3/7"}],
                     [{"path": ["s", "g2"], "probability": 1}]],
        "defender": {"rule": "guarantee", "h": [3, 1]}}),
}


def _counting(monkeypatch: pytest.MonkeyPatch, files: dict[str, str]) -> tuple[Counter[str],
                                                                                Counter[str]]:
    """Count the opens of ``files`` (paths) and the JSON parses of their texts."""
    opened: Counter[str] = Counter()
    parsed: Counter[str] = Counter()
    by_path = {os.path.realpath(p): name for name, p in files.items()}
    by_text = {Path(p).read_text(encoding="utf-8"): name for name, p in files.items()}
    real_open, real_os_open, real_loads = builtins.open, os.open, json.loads

    def note_open(path: Any) -> None:
        if isinstance(path, str | os.PathLike):
            name = by_path.get(os.path.realpath(os.fspath(path)))
            if name is not None:
                opened[name] += 1

    def counting_open(file: Any, *args: Any, **kw: Any) -> Any:
        note_open(file)
        return real_open(file, *args, **kw)

    def counting_os_open(path: Any, *args: Any, **kw: Any) -> Any:
        note_open(path)
        return real_os_open(path, *args, **kw)

    def counting_loads(s: Any, *args: Any, **kw: Any) -> Any:
        text = s.decode("utf-8") if isinstance(s, bytes | bytearray) else s
        name = by_text.get(text)
        if name is not None:
            parsed[name] += 1
        return real_loads(s, *args, **kw)

    monkeypatch.setattr(builtins, "open", counting_open)
    monkeypatch.setattr(os, "open", counting_os_open)
    monkeypatch.setattr(json, "loads", counting_loads)
    return opened, parsed


@pytest.mark.parametrize("case", CASES, ids=CASES.keys())
@pytest.mark.parametrize("args", [[], ["--json"], ["--horizon", "2", "--route", "both"]],
                         ids=["table", "json", "both routes"])
def test_each_input_file_is_opened_and_parsed_once(tmp_path: Path, case: str, args: list[str],
                                                   monkeypatch: pytest.MonkeyPatch) -> None:
    doc, prof = CASES[case]
    files = {"instance": str(tmp_path / "instance.json"), "profile": str(tmp_path / "p.json")}
    Path(files["instance"]).write_text(json.dumps(doc, indent=1), encoding="utf-8")
    Path(files["profile"]).write_text(json.dumps(prof, indent=1), encoding="utf-8")
    out = tmp_path / "cert.json"
    opened, parsed = _counting(monkeypatch, files)
    result = CliRunner().invoke(certify_command,
                                [files["instance"], files["profile"], *args, "-o", str(out)])
    monkeypatch.undo()
    assert result.exit_code in (0, 1), result.output  # certified or refuted: read either way
    assert opened == {"instance": 1, "profile": 1}, opened
    cert = json.loads(out.read_text(encoding="utf-8"))
    # on a PASS the trusted kernel parses the same bytes once more with its own reader
    # (docs/checker.md, "One verdict"); the engine's reader parses each file once
    extra = 1 if cert["info"]["kernel"]["status"] == "pass" else 0
    assert parsed["instance"] == 1 + extra and parsed["profile"] == 1 + extra, parsed
    prov = cert["provenance"]
    for name, path in files.items():
        assert prov[name] == {"sha256": hashlib.sha256(Path(path).read_bytes()).hexdigest(),
                              "bytes": "file"}


def test_the_counts_see_a_second_reading(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The counting above can fail: reading a file twice outside one session counts twice."""
    from dppverify.game.inputs import as_instance

    path = tmp_path / "instance.json"
    path.write_text(json.dumps(triangle_document()), encoding="utf-8")
    opened, parsed = _counting(monkeypatch, {"instance": str(path)})
    as_instance(str(path))
    as_instance(str(path))
    monkeypatch.undo()
    assert opened == {"instance": 2} and parsed == {"instance": 2}
