"""`dpp audit` contains every misbehaving solver: exceptions, exits, hangs, garbage, children
that outlive a timeout; a solver that cannot be started is bad input; PASS only when every
example was certified; the failure is written at once; shrinking keeps to its budget."""

from __future__ import annotations

import json
import os
import sys
import time
from pathlib import Path

import pytest
from click.testing import CliRunner, Result

from dppverify.cli.audit import audit_command
from tests import _guard

HOSTILE = "tests.dppverify.audit.hostile_solvers"


def run(*args: str) -> Result:
    result = CliRunner().invoke(audit_command, ["--no-progress", *args])
    assert "Traceback" not in result.output
    assert result.exception is None or isinstance(result.exception, SystemExit)
    return result


@pytest.mark.parametrize("name, check, words", [
    ("exits_zero", "solver.error", "SystemExit: 0"),
    ("interrupts", "solver.error", "KeyboardInterrupt"),
    ("kills_itself", "solver.error", "process exited"),
    ("signals_itself", "solver.error", "process exited"),
    ("prints_garbage", "solver.output", "not JSON"),
    ("returns_nan", "solver.output", "non-finite"),
    ("huge_answer", "solver.output", "larger than the limit of 64 MiB"),
    ("huge_traceback", "solver.error", "ValueError"),
])
def test_misbehaving_python_solvers_fail_the_audit(tmp_path: Path, name: str, check: str,
                                                   words: str) -> None:
    result = run("--solver", f"{HOSTILE}:{name}", "--examples", "3", "--no-shrink",
                 "--output-dir", str(tmp_path / "out"))
    assert result.exit_code == 1, result.output
    assert f"failing check: {check}" in result.stdout
    assert words in result.stdout
    assert "garbage on stdout" not in result.output  # the solver's output is not ours
    if name.startswith("huge"):  # bounded like every input: no 80 MB file, no 80 MB line
        assert not (tmp_path / "out" / "profile.json").exists()
        assert (tmp_path / "out" / "failure.json").stat().st_size < 200_000
        assert len(result.output) < 20_000


def test_a_failure_that_cannot_be_written_is_one_line_exit_2(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The output folder passed the check made before the first example but cannot take the
    failure's files (here: a file took the folder's place meanwhile): one line, exit 2 — not
    exit 1 with a report claiming the files were written."""
    import dppverify.audit.campaign as campaign
    from dppverify.audit.report import check_output_folder

    out = tmp_path / "out"

    def check_then_block(folder: str | Path) -> None:
        check_output_folder(folder)
        out.write_text("not a folder")

    monkeypatch.setattr(campaign, "check_output_folder", check_then_block)
    result = run("--solver", f"{HOSTILE}:exits_zero", "--examples", "2", "--no-shrink",
                 "--output-dir", str(out))
    assert result.exit_code == 2, result.output
    assert result.stdout == "" and result.stderr.count("\n") == 1, result.stderr
    assert result.stderr.startswith("error: cannot write the failing example (solver.error)")
    assert out.read_text() == "not a folder"


def test_a_hanging_solver_times_out_and_its_children_die(tmp_path: Path,
                                                         monkeypatch: pytest.MonkeyPatch) -> None:
    pidfile = tmp_path / "child.pid"
    monkeypatch.setenv("DPP_TEST_PIDFILE", str(pidfile))
    result = run("--solver", f"{HOSTILE}:spawns_and_hangs", "--examples", "2", "--no-shrink",
                 "--timeout", "2", "--output-dir", str(tmp_path / "out"))
    assert result.exit_code == 1, result.output
    # the audit ended the run (a solver left to its sleep would return None: solver.output),
    # with no wall-clock assertion that load could break
    assert "failing check: solver.timeout" in result.stdout
    child = int(pidfile.read_text())
    _assert_dead(child)


def test_a_timed_out_command_leaves_no_child(tmp_path: Path) -> None:
    script = tmp_path / "hang.py"
    pidfile = tmp_path / "child.pid"
    script.write_text(
        "import subprocess, sys, time\n"
        "child = subprocess.Popen([sys.executable, '-c', 'import time; time.sleep(300)'])\n"
        f"open({str(pidfile)!r}, 'w').write(str(child.pid))\n"
        "time.sleep(300)\n")
    result = run("--solver-cmd", f"{sys.executable} {script} {{instance}} {{profile}}",
                 "--examples", "2", "--timeout", "2", "--no-shrink",
                 "--output-dir", str(tmp_path / "out"))
    assert result.exit_code == 1, result.output
    assert "failing check: solver.timeout" in result.stdout
    _assert_dead(int(pidfile.read_text()))


def _assert_dead(pid: int) -> None:
    for _ in range(int(_guard.latency(50))):  # 0.05 s each: a latency, stretched by the load
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return
        if Path(f"/proc/{pid}/stat").exists() and \
                Path(f"/proc/{pid}/stat").read_text().split()[2] == "Z":
            return  # a zombie waiting for init: dead
        time.sleep(0.05)
    pytest.fail(f"process {pid} survived the timeout")


def test_garbage_from_a_command_is_its_failure(tmp_path: Path) -> None:
    result = run("--solver-cmd", f"{sys.executable} -c \"import sys; "
                 f"open(sys.argv[2], 'wb').write(bytes([255, 0]))\" {{instance}} {{profile}}",
                 "--examples", "2", "--no-shrink", "--output-dir", str(tmp_path / "out"))
    assert result.exit_code == 1, result.output
    assert "failing check: solver.output" in result.stdout


@pytest.mark.parametrize("args, words", [
    (["--solver-cmd", "no-such-program-xyz {instance} {profile}"], "not found"),
    (["--solver-cmd", "/no/such/dir/prog {instance} {profile}"], "not found"),
    (["--solver", "tests.dppverify.audit.no_such_module:solve"], "cannot import module"),
])
def test_a_solver_that_cannot_start_is_bad_input(tmp_path: Path, args: list[str],
                                                  words: str) -> None:
    result = run(*args, "--examples", "2", "--output-dir", str(tmp_path / "out"))
    assert result.exit_code == 2, result.output
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and words in lines[0]
    assert not (tmp_path / "out").exists()


def test_a_module_that_exits_on_import_is_bad_input(tmp_path: Path,
                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    (tmp_path / "exits_on_import.py").write_text("import sys\nsys.exit(0)\n")
    monkeypatch.chdir(tmp_path)
    monkeypatch.syspath_prepend(str(tmp_path))
    result = run("--solver", "exits_on_import:solve", "--examples", "2")
    assert result.exit_code == 2, result.output
    assert "SystemExit" in result.output and len(result.output.strip().splitlines()) == 1


def test_no_pass_unless_every_example_was_certified(tmp_path: Path,
                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("DPP_TEST_CALLED", raising=False)
    result = run("--solver", f"{HOSTILE}:correct_then_exit", "--examples", "5", "--no-shrink",
                 "--output-dir", str(tmp_path / "out"))
    assert result.exit_code == 1, result.output
    assert "PASS" not in result.output


def test_the_first_failure_is_written_at_once_and_no_shrink_says_so(tmp_path: Path) -> None:
    out = tmp_path / "out"
    result = run("--solver", "tests.mutants.solvers:mutant_drop_phase_ii", "--no-shrink",
                 "--examples", "300", "--output-dir", str(out))
    assert result.exit_code == 1
    assert "shrunk" not in result.output and "minimal" not in result.output
    assert "no shrinking" in result.stdout and "failing instance: {" in result.stdout
    assert "written to" in result.stderr  # the status line, before any shrinking
    assert json.loads((out / "failure.json").read_text())["check"].startswith("pbne.")
    assert oct((out / "instance.json").stat().st_mode & 0o777) == oct(0o666 & ~_umask())


def test_shrinking_keeps_to_its_budget(tmp_path: Path) -> None:
    result = run("--solver", "tests.mutants.solvers:mutant_drop_phase_ii", "--examples", "300",
                 "--shrink-calls", "3", "--output-dir", str(tmp_path / "out"))
    assert result.exit_code == 1
    assert "shrinking stopped at its budget after 3 solver calls" in result.stdout
    assert "smallest failing instance found: {" in result.stdout
    assert "budget: 3 solver calls" in result.stderr


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask
