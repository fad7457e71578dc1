"""Running experiment tasks on a dask.distributed scheduler (``--dask ADDRESS``).

One place for connecting, mapping and closing, shared by ``dpp experiment density`` and
``dpp batch``: a missing ``distributed`` package, an unreachable scheduler, or a port where
something else answers (checked first, within :data:`CONNECT_SECONDS`: a scheduler greets a
new connection at once, an HTTP server or a silent port does not) is one line of bad input
(:class:`~solver.errors.InvalidInstanceError`). At most a bounded number of tasks is in
flight, so ``tasks`` may be a lazy iterator of any length.
"""

from __future__ import annotations

import contextlib
import os
import re
import socket
from collections.abc import Callable, Generator, Iterable
from typing import Any, TypeVar, cast

from solver.errors import InvalidInstanceError

T = TypeVar("T")

CONNECT_SECONDS = 10.0
"""How long a scheduler may take to accept a connection and greet it (the environment variable
``DPP_DASK_CONNECT_SECONDS`` overrides it: :func:`connect_seconds`)."""


def connect_seconds() -> float:
    """:data:`CONNECT_SECONDS`, or ``DPP_DASK_CONNECT_SECONDS`` when it is a positive number.

    Examples
    --------
    >>> connect_seconds() > 0
    True
    """
    try:
        seconds = float(os.environ.get("DPP_DASK_CONNECT_SECONDS", CONNECT_SECONDS))
    except ValueError:
        return CONNECT_SECONDS
    return seconds if 0 < seconds < float("inf") else CONNECT_SECONDS


def check_scheduler(address: str, seconds: float | None = None) -> None:
    """Refuse at once an address where no Dask scheduler answers: for ``tcp://`` (or a bare
    ``host:port``), connect and wait for the scheduler's greeting (the comm handshake it
    sends first); other protocols are left to ``distributed``.

    Examples
    --------
    >>> check_scheduler("tcp://127.0.0.1:1")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: cannot reach the Dask scheduler at tcp://127.0.0.1:1: ...
    """
    seconds = connect_seconds() if seconds is None else seconds
    m = re.fullmatch(r"(?:tcp://)?\[?([^\[\]/]+?)\]?:(\d+)", address)
    if m is None:  # another protocol (tls://, ucx://, ...): left to distributed
        return
    host, port = m.group(1), int(m.group(2))
    try:
        with socket.create_connection((host, port), timeout=seconds) as sock:
            sock.settimeout(seconds)
            greeting = sock.recv(1)
    except TimeoutError:
        raise InvalidInstanceError(f"--dask {address}: something listens there but it is not a "
                                   f"Dask scheduler (no greeting within {seconds:g} s)") from None
    except OSError as exc:
        raise InvalidInstanceError(f"cannot reach the Dask scheduler at {address}: "
                                   f"{exc.strerror or exc}") from None
    if not greeting:
        raise InvalidInstanceError(f"--dask {address}: something listens there but it is not a "
                                   "Dask scheduler (it closed the connection)")


def dask_completed(fn: Callable[[T], Any], tasks: Iterable[T],
                   address: str) -> Generator[tuple[T, Any], None, None]:
    """``(task, fn(task))`` in completion order, computed by the scheduler at ``address``;
    at most twice its threads (at least 8) tasks in flight; the client is closed when the
    iteration ends or stops.

    Examples
    --------
    >>> next(dask_completed(len, ["ab"], "tcp://127.0.0.1:1"))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: cannot reach the Dask scheduler at tcp://127.0.0.1:1: ...
    """
    try:
        from distributed import Client
        from distributed import as_completed as completed
    except ImportError:  # pragma: no cover - dask is in the test and dask extras
        raise InvalidInstanceError("--dask needs dask[distributed]: pip install "
                                   "'dppverify[dask]'") from None
    check_scheduler(address)
    try:
        client = Client(address, timeout=f"{connect_seconds():g}s")
    except Exception as exc:  # unreachable, a protocol without its settings (tls:// ...)
        raise InvalidInstanceError(f"cannot reach the Dask scheduler at {address}: "
                                   f"{' '.join(str(exc).split())}") from None
    try:
        threads = 4
        with contextlib.suppress(Exception):
            threads = sum(client.nthreads().values())
        inflight = max(8, 2 * threads)
        todo = iter(tasks)
        running: dict[Any, T] = {}
        pending = completed([])

        def submit() -> bool:
            item = next(todo, _END)
            if item is _END:
                return False
            fut = client.submit(fn, item, pure=False)
            running[fut.key] = cast(T, item)
            pending.add(fut)
            return True

        while len(running) < inflight and submit():
            pass
        for fut in pending:
            task = running.pop(fut.key)
            yield task, fut.result()
            submit()
    finally:
        client.close()


_END = object()
