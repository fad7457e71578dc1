"""``dpp batch``'s inputs, validated where they enter: a ``.scen`` file with a byte-order mark
and CRLF lines is read like any other, a published length that is not a finite non-negative
decimal is an error row with its reason, ``--shard`` and ``--lines`` take ASCII digits only
(in-process; the hostile suite runs the same as real processes: ``tests/hostile/``)."""

from __future__ import annotations

import csv
from pathlib import Path

import pytest
from click.testing import CliRunner

from dpp import main
from dppverify.formats.scen import parse_scen

MAP = "type octile\nheight 3\nwidth 4\nmap\n....\n.@@.\n....\n"
LINES = ["0\tt.map\t4\t3\t0\t0\t3\t2\t5", "0\tt.map\t4\t3\t3\t0\t0\t2\t5",
         "0\tt.map\t4\t3\t0\t2\t3\t0\t3"]
TIMES = ("solve_seconds", "certify_seconds")


def _batch(d: Path, scen_text: bytes, *args: str) -> tuple[int, list[dict[str, str]], str]:
    (d / "t.map").write_text(MAP)
    scen = d / "s.scen"
    scen.write_bytes(scen_text)
    out = d / "b.csv"
    r = CliRunner().invoke(main, ["batch", str(scen), "-o", str(out), "--no-progress", *args])
    rows = []
    if out.exists():
        with open(out, encoding="utf-8", newline="") as fh:
            rows = [{k: v for k, v in row.items() if k not in TIMES and k != "config"}
                    for row in csv.DictReader(fh)]
    return r.exit_code, rows, r.stderr


def test_a_byte_order_mark_and_crlf_lines_read_as_the_plain_file(tmp_path: Path) -> None:
    plain = ("version 1\n" + "\n".join(LINES) + "\n").encode()
    windows = b"\xef\xbb\xbf" + plain.replace(b"\n", b"\r\n")
    a, b = tmp_path / "a", tmp_path / "b"
    a.mkdir()
    b.mkdir()
    code_a, rows_a, _ = _batch(a, plain)
    code_b, rows_b, err = _batch(b, windows)
    assert code_a == code_b == 0, err
    assert rows_b == rows_a and [r["status"] for r in rows_b] == ["ok"] * 3
    assert [s.line for s in parse_scen(windows.decode("utf-8"))] == [2, 3, 4]


@pytest.mark.parametrize("length", ["nan", "inf", "1e999999999", "-7", "1" * 5000, "0x10",
                                    "1_000", "\u0665", ""])
def test_a_published_length_that_is_no_finite_decimal_is_an_error_row(tmp_path: Path,
                                                                      length: str) -> None:
    bad = LINES[0].rsplit("\t", 1)[0] + "\t" + length
    code, rows, _ = _batch(tmp_path, ("version 1\n" + "\n".join([bad, *LINES]) + "\n")
                           .encode())
    assert code == 2
    first = rows[0]
    assert first["status"] == "error" and first["scen_optimal"] == ""
    if length:  # (an empty ninth field leaves eight: the line's other reason)
        assert "is not a finite non-negative decimal" in first["reason"]
        assert len(first["reason"]) < 300
    assert [r["status"] for r in rows[1:]] == ["ok"] * 3


@pytest.mark.parametrize("length", ["5", "53.89949493", "0.5", ".5", "7."])
def test_published_lengths_as_movingai_writes_them_are_kept(tmp_path: Path,
                                                            length: str) -> None:
    line = LINES[0].rsplit("\t", 1)[0] + "\t" + length
    code, rows, err = _batch(tmp_path, ("version 1\n" + "\n".join([line, *LINES[1:]]) + "\n")
                             .encode())
    assert code == 0, err
    assert rows[0]["scen_optimal"] == length


@pytest.mark.parametrize("option, value", [("--shard", "1/\u0662"), ("--shard", "\u0661/2"),
                                           ("--shard", "1/\uff12"), ("--shard", "1\u00a0/2"),
                                           ("--lines", "\u0662-3"), ("--lines", "2-\uff13"),
                                           ("--lines", "2\t-3")])
def test_shard_and_lines_take_ascii_digits_only(tmp_path: Path, option: str,
                                                value: str) -> None:
    code, rows, err = _batch(tmp_path, ("version 1\n" + "\n".join(LINES) + "\n").encode(),
                             option, value)
    assert code == 2 and rows == []
    assert err.startswith(f"error: {option} takes") and "ASCII digits" in err
    assert err.count("\n") == 1
