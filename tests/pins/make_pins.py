"""Write the expected records of the CLI pins: ``tests/pins/expected/<case>.txt``.

Usage (from the repository root)::

    PYTHONPATH=. python tests/pins/make_pins.py          # every case of cases.py
    PYTHONPATH=. python tests/pins/make_pins.py NAME...  # only these cases
    PYTHONPATH=. python tests/pins/make_pins.py --data   # first rewrite tests/pins/data/

The pins were written on the commit before the refactor that made one model serve any N;
rewriting them afterwards defeats their purpose unless a change of output is intended (say so
in the commit). ``--data`` imports the bundled examples by their old module paths
(``pin_data.py``), so it only works on a commit with the old layout.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

if __package__ in (None, ""):  # run as a script: make ``tests.pins`` importable
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent.parent))

from tests.pins.cases import CASES
from tests.pins.runner import EXPECTED, record, run_case


def main(argv: list[str]) -> int:
    """Write the expected records (all, or the cases named in ``argv``); return 0."""
    if "--data" in argv:
        from tests.pins.pin_data import write_data

        print("data:", ", ".join(write_data()))
        argv = [a for a in argv if a != "--data"]
    names = {c.name for c in CASES}
    if len(names) != len(CASES):
        raise SystemExit("cases.py: duplicate case names")
    unknown = set(argv) - names
    if unknown:
        raise SystemExit(f"unknown case(s): {', '.join(sorted(unknown))}")
    EXPECTED.mkdir(parents=True, exist_ok=True)
    if not argv:
        for stale in EXPECTED.glob("*.txt"):
            if stale.stem not in names:
                stale.unlink()
    total = time.perf_counter()
    for case in CASES:
        if argv and case.name not in argv:
            continue
        t0 = time.perf_counter()
        text = run_case(case)
        record(case).write_text(text, encoding="utf-8")
        codes = [line.split()[-1] for line in text.splitlines() if line.startswith("--- exit ")]
        print(f"{case.name:45s} exit {','.join(codes):8s} {time.perf_counter() - t0:5.2f} s")
    print(f"total {time.perf_counter() - total:.1f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
