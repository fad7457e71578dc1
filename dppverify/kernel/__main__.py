"""``python dppverify/kernel/__main__.py INSTANCE PROFILE WITNESS`` (what ``dpp check`` runs):
the kernel alone in a fresh interpreter, one line of output, exit 0 PASS, 1 refuted, 2 bad
input, 3 not decided. Run as a file it loads only ``dppverify.kernel`` (a bare ``dppverify``
package object stands in for the checker's, whose imports it never runs);
``python -m dppverify.kernel`` works too, after importing the whole checker.
"""

from __future__ import annotations

import sys
import types
from pathlib import Path

if __package__ in (None, ""):  # run as a file: the kernel without the rest of dppverify
    _package = types.ModuleType("dppverify")
    _package.__path__ = [str(Path(__file__).resolve().parents[1])]
    sys.modules.setdefault("dppverify", _package)

from dppverify.kernel.check import check
from dppverify.kernel.reading import MAX_BYTES

USAGE = ("usage: dpp check [--base-dir DIR] INSTANCE PROFILE WITNESS   (- reads one of them "
         "from standard input; DIR: where a map instance's map path starts)")


def main(argv: list[str]) -> int:
    """Run the kernel on the three files named by ``argv``; print one line; return the exit code.

    Examples
    --------
    >>> main(["missing.json", "p.json", "w.json"])
    2
    """
    base, argv = (Path(argv[1]), argv[2:]) if argv[:1] == ["--base-dir"] else (None, argv)
    if len(argv) != 3 or argv.count("-") > 1:
        print(f"error: {USAGE}", file=sys.stderr)
        return 2
    data = []
    for name in argv:
        try:
            with open(sys.stdin.fileno() if name == "-" else name, "rb", closefd=name != "-") as f:
                data.append(f.read(MAX_BYTES + 1))
        except OSError as exc:
            print(f"error: {name}: cannot read ({exc.strerror})", file=sys.stderr)
            return 2
    base = base or (Path.cwd() if argv[0] == "-" else Path(argv[0]).resolve().parent)
    v = check(data[0], data[1], data[2], base_dir=base)
    out = {"pass": "", "refuted": "REFUTED: ", "undecided": "NOT PROVED: "}
    print(out.get(v.status, "error: ") + v.message, file=sys.stdout if v.status in out else
          sys.stderr)
    return v.exit_code


if __name__ == "__main__":
    try:
        code = main(sys.argv[1:])
    except Exception as exc:  # never a traceback, and never exit 1 (refuted) for a failure
        print(f"error: internal error in the kernel ({exc!r})"[:300], file=sys.stderr)
        code = 3
    sys.exit(code)
