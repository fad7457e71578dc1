"""``dpp experiment ...`` and ``dpp plot ...``: outputs, files, one-line errors (exit 2)."""

from __future__ import annotations

import csv
from fractions import Fraction
from pathlib import Path

import pytest
from click.testing import CliRunner

from dpp import main
from solver.experiments.compare import paper10_instance
from solver.literature.strategy_pairs import COMPARE_PAIRS, PAIRS, PairEvaluator

ROOT = Path(__file__).resolve().parents[3]
PAPER10 = str(ROOT / "examples" / "paper10.map")


def _run(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(main, list(args))
    return result.exit_code, result.stdout, result.stderr


def test_compare_default_and_explicit_map_agree(tmp_path: Path) -> None:
    code, out, _ = _run("experiment", "compare", "--output-dir", str(tmp_path))
    assert code == 0
    code2, out2, _ = _run("experiment", "compare", "--map", PAPER10, "--start", "9,0",
                          "--goals", "0,9", "0,0", "--prior", "0.6,0.4")
    assert code2 == 0 and out2.splitlines()[:17] == out.splitlines()[:17]
    results = PairEvaluator.of(paper10_instance()).compare(COMPARE_PAIRS)
    with open(tmp_path / "compare.csv", encoding="utf-8") as f:
        table = list(csv.DictReader(f))
    assert [(r["defender"], r["attacker"]) for r in table] == list(COMPARE_PAIRS)
    for rec, res in zip(table, results, strict=True):
        assert Fraction(rec["U"]) == res.U and Fraction(rec["VoI"]) == res.VoI
    u = {(r.defender, r.attacker): r.U for r in results}
    holds = u[("sigma'", "gamma*")] < u[("sigma*", "gamma*")]
    assert ("does NOT hold" in out) != holds


def test_density_writes_csv_and_summary(tmp_path: Path) -> None:
    code, out, err = _run("experiment", "density", "--samples", "2", "--densities", "0,30",
                          "--size", "8", "--seed", "1", "--workers", "1", "--output-dir",
                          str(tmp_path))
    assert code == 0, err
    assert "Paper's claims on this data" in out
    with open(tmp_path / "density.csv", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 2 * 2 * len(PAIRS)
    assert (tmp_path / "summary.txt").read_text().startswith("VoI by density")
    magic = {".png": b"\x89PNG", ".svg": b"<?xml", ".pdf": b"%PDF"}
    for suffix, head in magic.items():  # the suffix picks the format; one file per -o
        figs = tmp_path / f"figs{suffix}"
        code, _, err = _run("plot", "voi", str(tmp_path / "density.csv"), "-o",
                            str(figs / f"voi{suffix}"))
        assert code == 0, err
        assert [p.name for p in figs.iterdir()] == [f"voi{suffix}"]
        assert (figs / f"voi{suffix}").read_bytes().startswith(head)
    code, _, err = _run("plot", "voi", str(tmp_path / "density.csv"), "-o",
                        str(tmp_path / "voi"))
    assert code == 2 and "must end in .png, .svg or .pdf" in err
    assert not (tmp_path / "voi").exists() and not (tmp_path / "voi.png").exists()


@pytest.mark.parametrize("kind", ["map", "beliefs"])
def test_plot_instance_figures(tmp_path: Path, kind: str) -> None:
    target = tmp_path / f"{kind}.png"
    code, _, err = _run("plot", kind, "-o", str(target))
    assert code == 0, err
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and target.stat().st_size > 10_000


@pytest.mark.parametrize("args,message", [
    (("experiment", "density", "--densities", "a,b"), "--densities must be integers"),
    (("experiment", "density", "--densities", "0,100", "--samples", "1"), "percentage"),
    (("experiment", "density", "--samples", "0"), "'--samples': 0 is not in the range"),
    (("experiment", "density", "--workers", "0", "--samples", "1", "--densities", "0",
      "--size", "4"), "--workers must be at least 1"),
    (("experiment", "compare", "--map", "missing.map", "--start", "0,0", "--goals", "1,1",
      "0,1", "--prior", "0.6,0.4"), "cannot read map file"),
    (("experiment", "compare", "--start", "0,0"), "--start goes with --map FILE"),
    (("plot", "voi", "missing.csv", "-o", "x.png"), "missing.csv: cannot read file"),
])
def test_bad_input_is_one_line_exit_2(args: tuple[str, ...], message: str) -> None:
    code, out, err = _run(*args)
    assert code == 2, (out, err)
    assert message in err and "Traceback" not in err + out
    assert len(err.strip().splitlines()) == 1


def test_unreachable_goal_on_a_map(tmp_path: Path) -> None:
    m = tmp_path / "wall.map"
    m.write_text("type octile\nheight 3\nwidth 3\nmap\n.@.\n.@.\n.@.\n")
    code, _, err = _run("plot", "map", "--map", str(m), "--start", "0,0", "--goals", "2,2",
                        "0,2", "--prior", "3/5,2/5", "-o", str(tmp_path / "x.png"))
    assert code == 2 and "unreachable" in err and "Traceback" not in err


def test_bad_csv(tmp_path: Path) -> None:
    bad = tmp_path / "bad.csv"
    bad.write_text("a,b\n1,2\n")
    code, _, err = _run("plot", "voi", str(bad), "-o", str(tmp_path / "v.png"))
    assert code == 2 and "CSV lacks column" in err
