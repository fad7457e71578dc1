"""``--progress``'s status line keeps its clock running during a long phase (it used to stop: a
refused four-goal solve showed ``[00:05]`` for two minutes)."""

from __future__ import annotations

import io
import sys
import threading

import pytest

from dppio.cli.conventions import PhaseBar


def test_the_elapsed_time_is_redrawn_without_any_call(monkeypatch: pytest.MonkeyPatch) -> None:
    err = io.StringIO()
    monkeypatch.setattr(sys, "stderr", err)
    bar = PhaseBar(True, "solve", "certifying (structured route, H = inf)", interval=0.01)
    start = bar.bar.start_t
    bar.bar._time = lambda: start + 65  # the clock jumps; only the ticker can show it
    shown = threading.Event()
    for _ in range(1000):  # bounded: up to 10 s on a loaded machine
        if "[01:05]" in err.getvalue():
            shown.set()
            break
        shown.wait(0.01)
    bar.close()
    assert shown.is_set(), err.getvalue()
    assert "solve: certifying" in err.getvalue()
    assert not any(t.name == "PhaseBar" and t.is_alive() for t in threading.enumerate())


def test_close_is_idempotent_and_a_silent_bar_starts_no_thread() -> None:
    before = threading.active_count()
    bar = PhaseBar(False, "solve", "reading the instance")
    assert threading.active_count() == before
    bar.phase("solving")
    bar.close()
    bar.close()
