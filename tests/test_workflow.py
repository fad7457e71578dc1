"""A researcher's workflow: one output convention, messages that say what to do next.

Each test is one finding of the issue, run through the ``dpp`` command as a user types it.
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

import click
import pytest
from click.testing import CliRunner

from dpp import main
from tests import _guard

ROOT = Path(__file__).resolve().parents[1]
TRIANGLE = str(ROOT / "examples" / "triangle.json")
PAPER10 = str(ROOT / "examples" / "paper10.map")
GRID = ["--start", "9,0", "--goals", "0,9", "0,0", "--prior", "0.6,0.4"]


def dpp(*args: str) -> click.testing.Result:
    return CliRunner().invoke(main, list(args))


@pytest.fixture()
def profile(tmp_path: Path) -> str:
    p = str(tmp_path / "p.json")
    assert dpp("solve", TRIANGLE, "-o", p).exit_code == 0
    return p


def _one_line_error(r: click.testing.Result) -> str:
    assert r.exit_code == 2, (r.exit_code, r.output)
    assert r.stdout == ""
    lines = r.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), r.stderr
    assert "Fraction(" not in lines[0] and "Traceback" not in lines[0]
    return lines[0]


# ---------------------------------------------------------------- one output convention
@pytest.mark.parametrize("args", [["solve", TRIANGLE], ["certify", TRIANGLE, "PROFILE"],
                                  ["value", TRIANGLE, "-H", "3"]])
def test_json_with_output_writes_the_file_and_prints_one_status_line(
        args: list[str], profile: str, tmp_path: Path) -> None:
    args = [profile if a == "PROFILE" else a for a in args]
    out = tmp_path / "out.json"
    for extra in (["--json"], []):
        r = dpp(*args, *extra, "-o", str(out))
        assert r.exit_code == 0, r.output
        assert r.stdout == ""
        assert r.stderr.startswith(f"wrote {out}: ") and r.stderr.count("\n") == 1
        json.loads(out.read_text())  # the file is the command's JSON document
        out.unlink()
    plain = dpp(*args, "--json")
    assert plain.exit_code == 0 and json.loads(plain.stdout)


def _leaves(group: click.Group = main, prefix: str = ""):  # type: ignore[no-untyped-def]
    for name, cmd in group.commands.items():
        if isinstance(cmd, click.Group):
            yield from _leaves(cmd, f"{prefix}{name} ")
        else:
            yield prefix + name, cmd


NO_JSON = {"export-efg", "import-profile", "plot map", "plot beliefs", "plot voi", "audit",
           "batch"}
"""Commands whose product is a file or folder they write (.efg, the imported profile, a figure,
the failure folder, the batch CSV): their stdout carries no data to print as JSON."""

NO_MAP = {"plot voi", "experiment density", "experiment goal-selection", "audit", "batch",
          "experiment baselines"}
"""Commands that take no single grid game: a density CSV, random grids (the density sweep's,
also for goal selection), a solver, a .scen file (which names its maps), several maps (--map
repeated)."""


def test_one_convention_on_every_command() -> None:
    for name, cmd in _leaves():
        opts = {o for p in cmd.params for o in getattr(p, "opts", [])}
        assert "--progress" in opts and "--no-progress" in {
            o for p in cmd.params for o in getattr(p, "secondary_opts", [])}, name
        assert "--output" in opts or "--output-dir" in opts, name
        assert ("--json" in opts) == (name not in NO_JSON), name
        if name not in NO_MAP:
            assert "--map" in opts, name


def test_progress_on_the_short_commands_shows_the_phase(tmp_path: Path) -> None:
    r = dpp("solve", TRIANGLE, "--progress", "-o", str(tmp_path / "p.json"))
    assert r.exit_code == 0 and "solve: reading the instance" in r.stderr
    r = dpp("plot", "map", "--progress", "-o", str(tmp_path / "m.png"))
    assert r.exit_code == 0 and "plot map: reading the instance" in r.stderr
    quiet = dpp("solve", TRIANGLE, "-o", str(tmp_path / "q.json"))
    assert quiet.stderr.startswith("wrote")


def test_experiment_compare_json() -> None:
    r = dpp("experiment", "compare", TRIANGLE, "--json")
    rows = json.loads(r.stdout)
    assert r.exit_code == 0 and len(rows) == 14 and rows[0]["U"] == "12/5"


def test_certificate_file_has_the_exact_numbers_the_table_abbreviates(tmp_path: Path) -> None:
    from dppverify.certificate import CheckRecord
    from dppverify.cli.table import _numbers

    big = {"U1_profile": 10**40 + 1, "ratio": 10**40 // 7 / 10**39}
    rec = CheckRecord("value.U1", "pass", "", big)  # type: ignore[arg-type]
    lines = _numbers(rec)
    assert all(len(line) <= 44 for line in lines) and not any("..." in x for x in lines)
    assert lines[0].split()[0] == "U1_profile=≈1×10^40"


def test_output_never_overwrites_an_input(profile: str) -> None:
    before = Path(profile).read_text()
    line = _one_line_error(dpp("certify", TRIANGLE, profile, "-o", profile))
    assert "is an input of this command" in line and Path(profile).read_text() == before


# ---------------------------------------------------------------- float mode detected
def test_eight_connected_maps_certify_without_float(tmp_path: Path) -> None:
    p = str(tmp_path / "p.json")
    grid = ["--map", PAPER10, *GRID, "--connectivity", "8"]
    assert dpp("solve", *grid, "-o", p).exit_code == 0
    r = dpp("certify", *grid, p)
    assert r.exit_code == 0, r.output
    assert "float mode" in r.stdout.splitlines()[0]


# ---------------------------------------------------------------- profile of another game
# One verdict: a profile of another game is refuted (exit 1) by the check that
# names its claim, as dppverify.certify() and dpp audit refute it, with a note on stderr.
def _refuted_with_note(r: click.testing.Result) -> str:
    assert r.exit_code == 1, (r.exit_code, r.output)
    assert r.stdout.startswith("verdict: FAIL"), r.stdout[:300]
    notes = [line for line in r.stderr.splitlines() if line.startswith("note: ")]
    assert len(notes) == 1 and "looks made for another instance" in notes[0], r.stderr
    return notes[0]


def _row(r: click.testing.Result, check: str) -> str:
    return next(line for line in r.stdout.splitlines() if line.startswith(check + " "))


def test_profile_of_another_prior_is_refuted_naming_the_claim(profile: str,
                                                              tmp_path: Path) -> None:
    doc = json.loads(Path(TRIANGLE).read_text())
    doc["prior"] = ["3/5", "2/5"]
    other = tmp_path / "other.json"
    other.write_text(json.dumps(doc))
    r = dpp("certify", str(other), profile)
    note = _refuted_with_note(r)
    assert "(7/10, 3/10)" in note and f"dpp solve {other} -o PROFILE" in note
    row = _row(r, "pbne.belief_consistency")
    assert " fail " in row and "the profile states the prior (7/10, 3/10)" in row


def test_profile_of_another_map_is_refuted_naming_the_claim(tmp_path: Path) -> None:
    p = str(tmp_path / "p.json")
    assert dpp("solve", "--map", PAPER10, *GRID, "-o", p).exit_code == 0
    moved = ["--start", "9,0", "--goals", "0,9", "0,5", "--prior", "0.6,0.4"]
    r = dpp("certify", "--map", PAPER10, *moved, p)
    note = _refuted_with_note(r)
    assert "its goals are [0, 9], [0, 0], the instance's are [0, 9], [0, 5]" in note
    assert " fail " in _row(r, "profile.wellformed")
    # same cells, another map: refuted by the complete-information value the profile states
    m = tmp_path / "open.map"
    m.write_text("type octile\nheight 10\nwidth 10\nmap\n" + "..........\n" * 10)
    r = dpp("certify", "--map", str(m), *GRID, p)
    note = _refuted_with_note(r)
    assert "Ū = 88/5" in note and "72/5" in note
    assert "the profile claims U_bar = 88/5" in _row(r, "value.VoI")


# ---------------------------------------------------------------- wrong kind of file
def test_swapped_arguments_and_map_files_get_a_hint(profile: str) -> None:
    assert "are the arguments swapped?" in _one_line_error(dpp("certify", profile, TRIANGLE))
    line = _one_line_error(dpp("certify", PAPER10, profile))
    assert f"--map {PAPER10} --start R,C" in line
    line = _one_line_error(dpp("solve", PAPER10))
    assert f"dpp solve --map {PAPER10}" in line
    assert "not an instance" in _one_line_error(dpp("solve", profile))


def test_ngoal_profiles_in_the_wrong_place_get_the_same_hints(profile: str,
                                                             tmp_path: Path) -> None:
    three = ["--map", PAPER10, "--start", "9,0", "--goals", "0,9", "0,0", "9,9", "--prior",
             "1/2,1/4,1/4"]
    p3, i3 = str(tmp_path / "p3.json"), str(tmp_path / "i3.json")
    assert dpp("solve", *three, "-o", p3, "--save-instance", i3).exit_code == 0
    assert "are the arguments swapped?" in _one_line_error(dpp("certify", p3, i3))
    for command in ("value", "solve"):
        line = _one_line_error(dpp(command, p3))
        assert f"dpp-ngoal-profile/1 document, not an instance: dpp {command}" in line
    line = _one_line_error(dpp("export-efg", p3, "-H", "2", "-o", str(tmp_path / "g.efg")))
    assert "not an instance" in line
    r = dpp("certify", TRIANGLE, p3)   # 3 goals against 2: refuted, as by certify()
    assert "its goals are [0, 9], [0, 0], [9, 9]" in _refuted_with_note(r)
    assert " fail " in _row(r, "profile.wellformed")


def test_plot_voi_on_the_wrong_file_names_it_and_the_command(profile: str,
                                                             tmp_path: Path) -> None:
    line = _one_line_error(dpp("plot", "voi", profile, "-o", str(tmp_path / "v.png")))
    assert profile in line and "dpp experiment density --output-dir" in line
    csv = tmp_path / "compare.csv"
    csv.write_text("defender,attacker,U1\nsigma*,gamma*,1\n")
    line = _one_line_error(dpp("plot", "voi", str(csv), "-o", str(tmp_path / "v.png")))
    assert str(csv) in line and "dpp experiment density" in line
    assert not (tmp_path / "v.png").exists()


def test_plot_map_accepts_the_saved_grid_instance(tmp_path: Path) -> None:
    inst = tmp_path / "grid.json"
    r = dpp("solve", "--map", PAPER10, *GRID, "--save-instance", str(inst))
    assert r.exit_code == 0
    r = dpp("plot", "map", str(inst), "-o", str(tmp_path / "m.png"))
    assert r.exit_code == 0, r.output
    assert (tmp_path / "m.png").stat().st_size > 1000
    assert "need a grid instance" in _one_line_error(
        dpp("plot", "map", TRIANGLE, "-o", str(tmp_path / "t.png")))


# ---------------------------------------------------------------- the --map option group
def test_a_bad_prior_with_map_is_blamed_on_prior() -> None:
    line = _one_line_error(dpp("solve", "--map", PAPER10, "--start", "9,0", "--goals", "0,9",
                               "0,0", "--prior", "0.6,0.5"))
    assert line == "error: --prior must sum to exactly 1, got 3/5 + 1/2 = 11/10"
    assert "paper10" not in line


def test_goals_as_one_quoted_argument_gets_a_precise_hint() -> None:
    line = _one_line_error(dpp("solve", "--map", PAPER10, "--start", "9,0", "--goals",
                               "0,9 0,0", "--prior", "0.6,0.4"))
    assert "separate arguments ROW,COL ROW,COL, e.g. --goals 0,9 0,0" in line


@pytest.mark.parametrize("goals", [["0, 9", "0,0"], ["0 , 9", "0, 0"], ["0 9 0 0"]])
def test_goals_with_spaces_get_a_hint_that_works(goals: list[str]) -> None:
    """The hint's suggestion is itself a valid --goals (it was `--goals 0, 9` for `"0, 9"`)."""
    line = _one_line_error(dpp("solve", "--map", PAPER10, "--start", "9,0", "--goals",
                               *goals, "--prior", "0.6,0.4"))
    suggested = line.split("e.g. --goals ")[1].split(", not one quoted")[0]
    assert suggested == "0,9 0,0"
    r = dpp("solve", "--map", PAPER10, "--start", "9,0", "--goals", *suggested.split(),
            "--prior", "0.6,0.4")
    assert r.exit_code == 0, r.output


@pytest.mark.parametrize("command", [["solve"], ["value"], ["certify", "PROFILE"],
                                     ["plot", "map", "-o", "OUT.png"]])
def test_a_short_prior_names_the_file_and_shows_what_was_written(command: list[str],
                                                                  profile: str,
                                                                  tmp_path: Path) -> None:
    doc = json.loads(Path(TRIANGLE).read_text())
    doc["prior"] = [0.7]
    bad = tmp_path / "short-prior.json"
    bad.write_text(json.dumps(doc))
    args = [a.replace("PROFILE", profile).replace("OUT", str(tmp_path / "f"))
            for a in command]
    line = _one_line_error(dpp(*args[:1], str(bad), *args[1:]) if args[0] != "plot" else
                           dpp(*args[:2], str(bad), *args[2:]))
    assert str(bad) in line and "must be a list of two numbers" in line
    assert line.endswith("got [0.7]")


@pytest.mark.parametrize("command", [["solve"], ["value"], ["certify", "p.json"],
                                     ["plot", "map", "-o", "m.png"]])
def test_a_scenario_file_as_map_names_its_map_and_dpp_batch(command: list[str],
                                                            tmp_path: Path) -> None:
    scen = tmp_path / "paper10.scen"
    scen.write_text("version 1\n0\tpaper10.map\t10\t10\t0\t9\t9\t0\t18\n")
    line = _one_line_error(dpp(*command[:2 if command[0] == "plot" else 1], "--map", str(scen),
                               *GRID, *command[2 if command[0] == "plot" else 1:]))
    assert "a MovingAI scenario file (.scen), not a map" in line
    assert "--map paper10.map" in line and f"dpp batch {scen}" in line


@pytest.mark.parametrize("command", ["solve", "value", "certify", "export-efg"])
def test_n_goals_with_connectivity_8_are_refused_in_option_terms(command: str) -> None:
    line = _one_line_error(dpp(command, "--map", PAPER10, "--start", "9,0", "--goals", "0,9",
                               "0,0", "9,9", "5,5", "--prior", "1/4,1/4,1/4,1/4",
                               "--connectivity", "8",
                               *{"certify": ["p.json"], "export-efg": ["-H", "2", "-o", "g.efg"]
                                 }.get(command, [])))
    assert "--connectivity 8" in line and "with 4 goals" in line and "--connectivity 4" in line
    assert '"numbers"' not in line


# ---------------------------------------------------------------- help and progress
def test_short_help_is_never_cut() -> None:
    def walk(group: click.Group):  # type: ignore[no-untyped-def]
        for cmd in group.commands.values():
            yield cmd
            if isinstance(cmd, click.Group):
                yield from walk(cmd)

    for cmd in walk(main):
        text = cmd.get_short_help_str(limit=60)
        assert not text.endswith("..."), (cmd.name, text)
        assert "Figs." not in text


@pytest.mark.parametrize("name", ["map", "beliefs", "voi"])
def test_plot_help_has_examples(name: str) -> None:
    r = dpp("plot", name, "--help")
    assert r.exit_code == 0 and "Examples:" in r.output and f"dpp plot {name}" in r.output


def test_certify_progress_shows_a_bar_before_the_tree(profile: str) -> None:
    r = dpp("certify", TRIANGLE, profile, "--progress")
    assert r.exit_code == 0
    first = r.stderr.replace("\r", "\n").strip().splitlines()[0]
    assert first.startswith("certify: reading the instance")


# ---------------------------------------------------------------- the audit from anywhere
def test_the_mutant_audit_runs_from_any_folder(tmp_path: Path) -> None:
    env = {k: v for k, v in os.environ.items() if not k.startswith(("DPP_", "PYTEST_"))}
    env["PYTHONPATH"] = str(ROOT)
    run = _guard.run(
        [sys.executable, "-c", "import sys; sys.argv[0] = 'dpp'; from dpp import main; "
         "main()", "audit", "--solver", "tests.mutants.solvers:mutant_drop_phase_ii",
         "--examples", "40", "--no-shrink", "--output-dir", "failure"],
        cwd=tmp_path, env=env, text=True, capture_output=True)
    assert run.returncode == 1, run.stderr
    assert "cannot import" not in run.stderr
    assert (tmp_path / "failure" / "instance.json").exists()


# ---------------------------------------------------------------- the solver's objects
def test_certify_takes_the_solvers_objects() -> None:
    import dppverify
    import solver

    inst = solver.load_instance(TRIANGLE)
    eq = solver.solve(inst)
    assert inst.to_json() == solver.instance_to_json(inst)
    with pytest.warns(DeprecationWarning, match="equilibrium_to_json is deprecated"):
        assert eq.to_json() == solver.equilibrium_to_json(eq)
    assert dppverify.certify(inst, eq).verdict == "pass"
    assert dppverify.game_value(inst, 2).bracket.closed


# ---------------------------------------------------------------- messages of the API
def test_structured_prior_mismatch_has_no_fraction_repr() -> None:
    import dppverify
    import solver

    inst = solver.load_instance(TRIANGLE)
    doc = solver.solve(inst).to_json()
    doc["prior"] = {"primary": "3/5", "secondary": "2/5"}
    cert = dppverify.certify(inst, doc, route="structured")
    rec = cert.check("pbne.belief_consistency")
    assert rec.status == "fail"
    assert "(3/5, 2/5)" in rec.message and "(7/10, 3/10)" in rec.message
    assert "Fraction(" not in rec.message


# ---------------------------------------------------------------- the light install
def test_the_runtime_dependencies_stay_light() -> None:
    import re
    import tomllib

    with open(ROOT / "pyproject.toml", "rb") as f:
        project = tomllib.load(f)["project"]
    names = {re.split(r"[<>=!\[ ;]", d, maxsplit=1)[0].lower() for d in project["dependencies"]}
    assert "cvxpy-base" in names and "clarabel" in names and "cvxpy" not in names
    assert not names & {"scs", "osqp", "ecos", "pandas", "highspy", "dask"}
    # sympy is a runtime dependency on purpose (the tree LP's exact closure, lp_exact); it is
    # imported only when a bracket stays open, never at start-up (tests of the lazy imports)
    assert "sympy" in names


@pytest.mark.parametrize("command", [["value", "-H", "2"], ["export-efg", "-H", "1", "-o", "g.efg"],
                                     ["plot", "map", "-o", "m.png"], ["experiment", "compare"]])
def test_a_map_file_as_instance_names_the_right_command(command: list[str]) -> None:
    name = " ".join(c for c in command if not c.startswith("-") and not c[0].isdigit()
                    and "." not in c)
    line = _one_line_error(dpp(*command[:1 + (command[0] in ("plot", "experiment"))], PAPER10,
                               *command[1 + (command[0] in ("plot", "experiment")):]))
    assert f"give it as dpp {name} --map {PAPER10}" in line


@pytest.mark.parametrize("goals,prior", [(["0,9", "0,0"], "0.6,0.4"),
                                         (["0,9", "0,0", "9,9"], "1/2,1/4,1/4")])
def test_a_start_on_a_goal_is_solved_with_a_note(goals: list[str], prior: str) -> None:
    r = dpp("solve", "--map", PAPER10, "--start", "0,9", "--goals", *goals, "--prior", prior)
    assert r.exit_code == 0, r.output
    assert r.stderr.startswith("note: the start is a goal: the game ends before any step")
    assert len(r.stderr.splitlines()) == 1
    r = dpp("solve", "--map", PAPER10, *GRID)
    assert r.exit_code == 0 and r.stderr == ""


# ---------------------------------------------------------------- plurals and numbers
def test_one_example_is_singular() -> None:
    from dppverify.audit.report import AuditReport

    assert AuditReport(True, 1, 0, 0, None, None).summary().startswith(
        "audit PASS: 1 example certified (seed 0")
    assert "5 examples certified" in AuditReport(True, 5, 0, 0, None, None).summary()


def test_one_rule_for_decimals_in_text() -> None:
    """Every decimal shown beside an exact value has dppio.text.DIGITS significant digits,
    in the checker's lines, the solver's summaries, the comparison table and the figures."""
    from fractions import Fraction

    from dppio.text import decimal
    from dppverify.text import show_value
    from solver.experiments.compare import _num
    from solver.plots.style import num_label
    from solver.twogoal.report import format_value

    x = Fraction(71, 18)
    assert decimal(x) == "3.944"
    assert show_value(x) == format_value(x) == _num(x) == "71/18 (≈ 3.944)"
    assert num_label(x) == "71/18 ≈ 3.944"
    r = dpp("value", TRIANGLE, "-H", "2", "--route", "tree")
    assert "(≈ 2.4)" in r.stdout and "LP value 2.4 " in r.stdout


def test_no_format_spec_bypasses_the_decimal_rule() -> None:
    """Decimals are formatted by dppio.text.decimal only: no f-string precision spec in the
    packages (CSV data columns of dpp batch excepted: they are data, not text)."""
    import re

    spec = re.compile(r"\{[^{}]*:[<>^+ ]?[0-9]*\.[0-9]+[fgeF%]\}")
    found = []
    for pkg in ("solver", "dppverify", "dppio"):
        for path in (ROOT / pkg).rglob("*.py"):
            if path.name == "text.py" and path.parent.name == "dppio":
                continue
            for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                if spec.search(line) and "_seconds=f" not in line and "seconds=f\"" not in line:
                    found.append(f"{path.relative_to(ROOT)}:{n}: {line.strip()}")
    assert not found, "\n".join(found)


@pytest.mark.parametrize("name", ["map", "beliefs", "voi"])
def test_plot_marks_its_output_required(name: str) -> None:
    help_text = " ".join(dpp("plot", name, "--help").stdout.split())
    assert "-o, --output FILE" in help_text and "[required]" in help_text
    r = dpp("plot", name, *(["x.csv"] if name == "voi" else []))
    assert r.exit_code == 2 and "Missing option '--output'" in r.stderr


def test_plot_map_draws_an_n_goal_equilibrium_from_map_or_saved_instance(tmp_path: Path) -> None:
    cells = ["--start", "9,0", "--goals", "0,9", "0,0", "9,9", "--prior", "1/2,1/3,1/6"]
    r = dpp("plot", "map", "--map", PAPER10, *cells, "-o", str(tmp_path / "n3.png"))
    assert r.exit_code == 0 and (tmp_path / "n3.png").stat().st_size > 10_000, r.output
    inst = tmp_path / "i3.json"
    assert dpp("solve", "--map", PAPER10, *cells, "-o", str(tmp_path / "p3.json"),
               "--save-instance", str(inst)).exit_code == 0
    r = dpp("plot", "map", str(inst), "-o", str(tmp_path / "i3.png"))
    assert r.exit_code == 0 and (tmp_path / "i3.png").is_file(), r.output
    line = _one_line_error(dpp("plot", "beliefs", "--map", PAPER10, *cells,
                               "-o", str(tmp_path / "b.png")))
    assert "this command takes two goals, got 3" in line
    assert not (tmp_path / "b.png").exists()


@pytest.mark.parametrize("goals", [["0,9", "0,0"], ["0,9", "0,0", "9,9"]])
def test_plot_refuses_a_wrong_suffix_before_any_work(goals: list[str], tmp_path: Path,
                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    import solver.coalitions.construction as construction
    import solver.plots.grid as grid

    def boom(*args: object, **kwargs: object) -> None:
        raise AssertionError("solved before the output name was checked")

    monkeypatch.setattr(construction, "coalition_equilibrium", boom)
    monkeypatch.setattr(grid, "PairEvaluator", type("P", (), {"of": staticmethod(boom)}))
    prior = "0.6,0.4" if len(goals) == 2 else "1/2,1/3,1/6"
    line = _one_line_error(dpp("plot", "map", "--map", PAPER10, "--start", "9,0", "--goals",
                               *goals, "--prior", prior, "-o", str(tmp_path / "m.txt")))
    assert line.endswith("m.txt: the output file must end in .png, .svg or .pdf")


def test_plot_map_of_a_graph_that_is_no_grid_is_one_line() -> None:
    import tempfile

    from dppverify.game.examples import star3_document
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "star3.json"
        path.write_text(json.dumps(star3_document()))
        line = _one_line_error(dpp("plot", "map", str(path), "-o", str(Path(d) / "s.png")))
    assert "map figures need a grid instance" in line
