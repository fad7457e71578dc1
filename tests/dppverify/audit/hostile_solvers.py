"""Solvers that misbehave in every way a solver can: the audit must contain each one."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from typing import Any

from solver.adapter import solve_json


def exits_zero(doc: dict[str, Any]) -> Any:
    sys.exit(0)


def interrupts(doc: dict[str, Any]) -> Any:
    raise KeyboardInterrupt


def loops(doc: dict[str, Any]) -> Any:
    while True:
        time.sleep(0.05)


def kills_itself(doc: dict[str, Any]) -> Any:
    os._exit(0)


def signals_itself(doc: dict[str, Any]) -> Any:
    os.kill(os.getpid(), signal.SIGTERM)


def prints_garbage(doc: dict[str, Any]) -> Any:
    print("garbage on stdout")
    return {"format": "dpp-profile/1", "attacker": object()}


def returns_nan(doc: dict[str, Any]) -> Any:
    return {"format": "dpp-profile/1", "value": {"U": float("nan")}}


def spawns_and_hangs(doc: dict[str, Any]) -> Any:
    pidfile = os.environ["DPP_TEST_PIDFILE"]
    child = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(300)"])
    with open(pidfile, "w") as fh:
        fh.write(str(child.pid))
    time.sleep(300)


def correct_then_exit(doc: dict[str, Any]) -> Any:
    """Right on the first call, then exits the process."""
    if os.environ.get("DPP_TEST_CALLED"):
        os._exit(3)
    os.environ["DPP_TEST_CALLED"] = "1"
    return solve_json(doc)


def huge_answer(doc: dict[str, Any]) -> Any:
    """A correct profile padded past the input limit (64 MiB): bounded like every input."""
    return solve_json(doc) | {"padding": "x" * (80 << 20)}


def huge_traceback(doc: dict[str, Any]) -> Any:
    raise ValueError("y" * (80 << 20))
