"""Signals of the ``dpp`` commands: SIGINT, SIGTERM and SIGHUP end a command cleanly.

While a command runs (:func:`signals_as_exceptions`), SIGTERM and SIGHUP raise
:class:`Terminated` and SIGINT raises ``KeyboardInterrupt`` in the main thread, so every
``finally`` and ``with`` block on the way out runs: temporary files are removed, no partial
output file is left (``dppio.files.write_files`` cleans up on any exception), child
processes and their process groups are killed. The command group then prints one line and
exits with the shell's convention, ``128 + signal number`` (130 for SIGINT, 143 for SIGTERM,
129 for SIGHUP; :func:`exit_code`). A second signal during that cleanup is ignored, so the
cleanup itself is not cut short.

Examples
--------
>>> exit_code(KeyboardInterrupt()), exit_code(Terminated(signal.SIGTERM))
(130, 143)
>>> message(Terminated(signal.SIGTERM))
'error: terminated by SIGTERM; temporary files and child processes were cleaned up'
"""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Iterator
from types import FrameType
from typing import Any

_RECEIVED: list[int] = []
"""The signals received inside the current :func:`signals_as_exceptions` block."""


def as_signal(exc: BaseException) -> BaseException | None:
    """The signal exception an error stands for: ``exc`` itself if it is one, else — when a
    signal arrived during the command and a library turned its exception into another error
    (hypothesis does) — that signal's exception; None otherwise.

    Examples
    --------
    >>> as_signal(ValueError("x")) is None
    True
    >>> exit_code(as_signal(KeyboardInterrupt()))
    130
    """
    if isinstance(exc, KeyboardInterrupt | Terminated):
        return exc
    if _RECEIVED:
        n = _RECEIVED[-1]
        return KeyboardInterrupt() if n == signal.SIGINT else Terminated(n)
    return None

HANDLED = (signal.SIGTERM, signal.SIGHUP)
"""Signals turned into :class:`Terminated` (SIGINT is Python's ``KeyboardInterrupt``)."""


class Terminated(BaseException):
    """The process received SIGTERM or SIGHUP (a ``BaseException``, like
    ``KeyboardInterrupt``: no ``except Exception`` swallows it).

    Attributes
    ----------
    signum : int
        The signal number.
    """

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = int(signum)


def exit_code(exc: BaseException) -> int:
    """``128 + n`` for the signal ``exc`` stands for (130 for ``KeyboardInterrupt``).

    Examples
    --------
    >>> exit_code(Terminated(signal.SIGHUP))
    129
    """
    if isinstance(exc, Terminated):
        return 128 + exc.signum
    return 128 + int(signal.SIGINT)


def message(exc: BaseException) -> str:
    """The one line a command prints when a signal ends it.

    Examples
    --------
    >>> message(KeyboardInterrupt())
    'error: interrupted by SIGINT; temporary files and child processes were cleaned up'
    """
    if isinstance(exc, Terminated):
        what = f"terminated by {signal.Signals(exc.signum).name}"
    else:
        what = "interrupted by SIGINT"
    return f"error: {what}; temporary files and child processes were cleaned up"


@contextlib.contextmanager
def signals_as_exceptions() -> Iterator[None]:
    """Within the block, SIGTERM/SIGHUP raise :class:`Terminated` and SIGINT raises
    ``KeyboardInterrupt``; once one has been raised, further signals are ignored until the
    block ends. Outside the main thread it does nothing (Python delivers signals there only).

    Examples
    --------
    >>> import os
    >>> try:
    ...     with signals_as_exceptions():
    ...         os.kill(os.getpid(), signal.SIGTERM)
    ... except Terminated as exc:
    ...     print(exit_code(exc))
    143
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    state: dict[str, Any] = {"fired": False, "retry": False, "watchdog": None}
    main_id = threading.main_thread().ident
    assert main_id is not None  # the main thread is running this

    def redeliver(signum: int, retry: bool) -> None:
        state["retry"] = retry
        if retry:  # and once more later, should this one be swallowed too
            again = threading.Timer(RETRY_SECONDS, redeliver, args=(signum, True))
            again.daemon = True
            again.start()
            state["watchdog"] = again
        # a real signal to the main thread: it also interrupts a blocking call (select, wait)
        signal.pthread_kill(main_id, signum)

    def handler(signum: int, frame: FrameType | None) -> None:
        if _in_callback(frame):  # an exception raised here would be swallowed: a moment later
            threading.Timer(0.05, redeliver, args=(signum, False)).start()
            return
        if state["fired"] and not state["retry"]:
            return  # cleaning up after the first signal: do not cut the cleanup short
        state["fired"], state["retry"] = True, False
        _RECEIVED.append(signum)
        if state["watchdog"] is None:  # swallowed anyway (a callback we did not recognise)?
            watchdog = threading.Timer(RETRY_SECONDS, redeliver, args=(signum, True))
            watchdog.daemon = True
            watchdog.start()
            state["watchdog"] = watchdog
        if signum == signal.SIGINT:
            raise KeyboardInterrupt
        raise Terminated(signum)

    previous = {s: signal.getsignal(s) for s in (*HANDLED, signal.SIGINT)}
    previous = {s: h for s, h in previous.items() if h is not signal.SIG_IGN}  # nohup stays
    for s in previous:
        signal.signal(s, handler)
    try:
        yield
    finally:
        _RECEIVED.clear()
        if state["watchdog"] is not None:
            state["watchdog"].cancel()
        for s, h in previous.items():
            signal.signal(s, h if h is not None else signal.SIG_DFL)


RETRY_SECONDS = 2.0
"""If the command is still running this long after a signal was turned into an exception
(swallowed by a callback, or by a library's bare ``except:`` while it was being imported),
the signal is delivered once more, and again every ``RETRY_SECONDS``."""

_CALLBACKS = frozenset({"__del__", "gc_callback", "_gc_callback"})


def _in_callback(frame: FrameType | None) -> bool:
    """True when the signal arrived inside a callback whose exceptions Python ignores (a gc
    callback, a finaliser)."""
    f = frame
    for _ in range(3):
        if f is None:
            return False
        if f.f_code.co_name in _CALLBACKS:
            return True
        f = f.f_back
    return False
