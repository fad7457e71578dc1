"""Certificate provenance: recorded hashes, and ``dpp certify --verify-provenance``."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from dppverify import __version__
from dppverify.certificate import Certificate
from dppverify.certify import certify
from dppverify.cli.certify import certify_command
from dppverify.game.examples import triangle_document, triangle_profile
from dppverify.provenance import canonical_json, verify_provenance

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def files(tmp_path: Path) -> tuple[Path, Path, Path]:
    inst = tmp_path / "instance.json"
    inst.write_bytes((ROOT / "examples" / "triangle.json").read_bytes())
    prof = tmp_path / "profile.json"
    prof.write_text(json.dumps(triangle_profile(), indent=1))
    result = CliRunner().invoke(certify_command, [str(inst), str(prof), "--json"])
    assert result.exit_code == 0, result.output
    cert = tmp_path / "cert.json"
    cert.write_text(result.output)
    return cert, inst, prof


def test_certificate_records_the_hashes_of_the_file_bytes(files: tuple[Path, Path, Path]
                                                          ) -> None:
    cert, inst, prof = files
    prov = json.loads(cert.read_text())["provenance"]
    assert prov["instance"] == {"sha256": hashlib.sha256(inst.read_bytes()).hexdigest(),
                                "bytes": "file"}
    assert prov["profile"] == {"sha256": hashlib.sha256(prof.read_bytes()).hexdigest(),
                               "bytes": "file"}
    assert prov["dppverify"] == __version__
    assert (prov["route"], prov["numbers"]) == ("structured", "exact")  # H = inf by default
    # invoked from Python (not as the `dpp` process): the command path and its parameters
    assert prov["command"][0] == "certify"
    assert {f"instance={inst}", f"profile={prof}", "as_json=True"} <= set(prov["command"])
    # the record survives a round trip through Certificate
    assert Certificate.from_json(cert.read_text()).to_json()["provenance"] == prov


def test_documents_are_hashed_by_their_canonical_json() -> None:
    doc, prof = triangle_document(), triangle_profile()
    prov = certify(doc, prof).provenance
    assert prov is not None
    assert prov["instance"]["sha256"] == hashlib.sha256(canonical_json(doc)).hexdigest()
    assert prov["instance"]["bytes"] == prov["profile"]["bytes"] == "canonical-json"
    # key order does not matter for a document; the values do
    reordered = dict(reversed(list(doc.items())))
    assert verify_provenance({"provenance": prov}, reordered, prof).ok
    assert not verify_provenance({"provenance": prov}, triangle_document(("1/4", "3/4")),
                                 prof).ok


def test_untouched_certificate_passes(files: tuple[Path, Path, Path]) -> None:
    cert, inst, prof = files
    r = CliRunner().invoke(certify_command, ["--verify-provenance", str(cert), str(inst),
                                             str(prof)])
    assert r.exit_code == 0
    assert r.output.startswith("provenance OK: instance, profile match")
    assert r.output.count("\n") == 1


@pytest.mark.parametrize("which", ["instance", "profile"])
def test_any_changed_byte_fails_in_one_line(files: tuple[Path, Path, Path], which: str) -> None:
    cert, inst, prof = files
    target = inst if which == "instance" else prof
    original = target.read_bytes()
    doc = json.loads(cert.read_text())
    for pos in range(len(original)):   # every byte position, changed to another byte
        changed = bytearray(original)
        changed[pos] = (changed[pos] + 1) % 256
        target.write_bytes(bytes(changed))
        check = verify_provenance(doc, str(inst), str(prof))
        assert not check.ok and check.mismatches[0].startswith(f"{which} sha256 differs")
    target.write_bytes(original + b"\n")  # one byte more, through the command
    r = CliRunner().invoke(certify_command, ["--verify-provenance", str(cert), str(inst),
                                             str(prof)])
    assert r.exit_code == 1
    assert r.output.count("\n") == 1
    assert r.output.startswith(f"provenance MISMATCH: {which} sha256 differs")


def test_bad_certificate_is_exit_2(files: tuple[Path, Path, Path], tmp_path: Path) -> None:
    _, inst, prof = files
    old = tmp_path / "old.json"
    doc = certify(triangle_document(), triangle_profile()).to_json()
    del doc["provenance"]
    old.write_text(json.dumps(doc))
    forged = tmp_path / "forged.json"
    doc = json.loads(files[0].read_text())
    doc["checks"][0]["status"] = "fail"  # the verdict "pass" no longer agrees
    forged.write_text(json.dumps(doc))
    for cert in (tmp_path / "missing.json", inst, old, forged):
        r = CliRunner().invoke(certify_command, ["--verify-provenance", str(cert), str(inst),
                                                 str(prof)])
        assert r.exit_code == 2
        assert r.output.count("\n") == 1 and r.output.startswith("error: ")


def test_map_certificate_pins_the_map_file(tmp_path: Path, monkeypatch: pytest.MonkeyPatch
                                           ) -> None:
    m = tmp_path / "tiny.map"
    m.write_text("type octile\nheight 2\nwidth 3\nmap\n...\n.@.\n")
    prof = tmp_path / "p.json"
    cells = ["--start", "1,0", "--goals", "1,2", "0,0", "--prior", "1/2,1/2"]
    grid = ["--map", str(m), *cells]
    from dpp import main

    saved = tmp_path / "saved" / "i.json"
    saved.parent.mkdir()
    assert CliRunner().invoke(main, ["solve", *grid, "-o", str(prof), "--save-instance",
                                     str(saved)]).exit_code == 0
    r = CliRunner().invoke(certify_command, [*grid, str(prof), "--json"])
    assert r.exit_code == 0
    cert = tmp_path / "c.json"
    cert.write_text(r.output)
    # the instance hash is that of the compact map instance dpp solve --save-instance wrote,
    # its map path cut to the file's name (the map's bytes are pinned by map_sha256)
    rec = json.loads(r.output)["provenance"]["instance"]
    compact = json.loads(saved.read_text())
    assert compact["map"] == "../tiny.map"
    assert rec["sha256"] == hashlib.sha256(canonical_json({**compact, "map": "tiny.map"})
                                           ).hexdigest()
    assert rec["bytes"] == "canonical-json" and rec["map"]["sha256"] == compact["map_sha256"]
    ok = CliRunner().invoke(certify_command, ["--verify-provenance", str(cert), *grid, str(prof)])
    assert ok.exit_code == 0 and "map" in ok.output
    # the same map given from another folder: the same game, the same hashes
    monkeypatch.chdir(saved.parent)
    again = CliRunner().invoke(certify_command, ["--verify-provenance", str(cert), "--map",
                                                 "../tiny.map", *cells, str(prof)])
    assert again.exit_code == 0, again.output
    other = CliRunner().invoke(certify_command, ["--verify-provenance", str(cert), "--map",
                                                 "../tiny.map", *cells[:-1], "2/3,1/3",
                                                 str(prof)])
    assert other.exit_code == 1 and "instance sha256 differs" in other.output
    m.write_text("type octile\nheight 2\nwidth 3\nmap\n...\n.@@\n")  # same cells used? no: map
    bad = CliRunner().invoke(certify_command, ["--verify-provenance", str(cert), *grid,
                                               str(prof)])
    assert bad.exit_code == 1 and "map sha256 differs" in bad.output


def test_swapped_inputs_and_missing_profile_are_named(files: tuple[Path, Path, Path]) -> None:
    cert, inst, prof = files
    r = CliRunner().invoke(certify_command, ["--verify-provenance", str(cert), str(prof),
                                             str(inst)])
    assert r.exit_code == 1 and r.output.count("\n") == 1
    assert "look swapped: give CERT INSTANCE PROFILE" in r.output
    r = CliRunner().invoke(certify_command, ["--verify-provenance", str(cert), str(inst)])
    assert r.exit_code == 2 and r.output.count("\n") == 1
    assert "--verify-provenance CERT INSTANCE PROFILE" in r.output
