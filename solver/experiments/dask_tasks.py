"""Running experiment tasks on a dask.distributed scheduler (``--dask ADDRESS``).

One place for connecting, mapping and closing, shared by ``dpp experiment density`` and
``dpp batch``: a missing ``distributed`` package or an unreachable scheduler is one line of
bad input (:class:`~solver.errors.InvalidInstanceError`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from typing import Any

from solver.errors import InvalidInstanceError

__all__ = ["dask_completed"]


def dask_completed(fn: Callable[[Any], Any], tasks: Sequence[Any],
                   address: str) -> Iterator[tuple[int, Any]]:
    """``(index, fn(tasks[index]))`` in completion order, computed by the scheduler at
    ``address``; the client is closed when the iteration ends or stops.

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
    try:
        client = Client(address, timeout="10s")
    except (OSError, TimeoutError) as exc:
        raise InvalidInstanceError(f"cannot reach the Dask scheduler at {address}: "
                                   f"{exc}") from None
    try:
        futures = client.map(fn, list(tasks), pure=False)
        index = {f.key: i for i, f in enumerate(futures)}
        for fut in completed(futures):
            yield index[fut.key], fut.result()
    finally:
        client.close()
