"""``V_H`` without the walk tree: three hop-bounded Bellman–Ford fields (proofs/DP.md).

For ``k`` steps left and every node ``v`` (goals terminal, with their terminal costs)::

    D1_k(v) = min over walks from v with <= k steps of  L(walk) + d(end, g1)
    D2_k(v) = min over walks from v with <= k steps of  L(walk) + d(end, g2)
    m_k(v)  = min( min_u [ w(v,u) + m_{k-1}(u) ],  D1_k(v) + D2_k(v) )
    goals:  D1(g1) = 0, D1(g2) = d(g2,g1);  D2(g1) = d(g1,g2), D2(g2) = 0;
            m(g1) = d(g1,g2), m(g2) = d(g2,g1);  non-goals at k = 0: +inf

    V_H = b2 · m_H(s0) + (b1 − b2) · D1_H(s0)          (b1 >= b2)

``O(H·E)`` work, vectorised over the arcs with numpy — or, where the fields have reached their
fixpoint, three Dijkstra runs (:func:`~dppverify.twogoal.value_fixpoint.fixpoint_fields`,
proofs/DP.md DP.5): the fixpoint fields
are shortest-path fields (``D1``, ``D2`` from the goals, ``m`` from every node's split value),
and a lexicographic (value, steps) Dijkstra also gives the first step at which each node's
fields are final, hence the step the iteration would stop at and whether ``H`` reaches it; the
result is the iteration's, entry for entry. Exact mode scales the rational weights
to integers over their common denominator; the fields are ``int64`` arrays when a bound
computed up front shows every number fits, Python integers (numpy ``object`` arrays)
otherwise. Float-mode instances are computed in ``float64``. The fields only decrease with
``k`` and reach a fixpoint after at most ``2n`` steps; the iteration stops there, which gives the
untruncated game's value for ``horizon=None`` (``--horizon inf``).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Literal

import numpy as np

from dppverify.errors import HorizonError
from dppverify.exact import Number, normalize
from dppverify.game.instance import Instance, Roles
from dppverify.twogoal.value_fixpoint import Arcs, fixpoint_fields, goal_terminal_arcs


@dataclass(frozen=True, eq=False)
class Fields:
    """The three fields after ``steps`` iterations (scaled numbers; ``sentinel`` = unreachable).

    Attributes
    ----------
    d1, d2, m : numpy.ndarray
        ``D1_k``, ``D2_k``, ``m_k`` for every node, scaled by :attr:`scale`.
    steps : int
        ``k``: the number of steps left the fields describe (``min(H, fixpoint)``).
    fixpoint : bool
        True when step ``k`` changed nothing: the fields are those of every larger horizon.
    sentinel : int or float
        Values ``>= sentinel`` mean "no goal within ``k`` steps" (``inf`` in float mode).
    scale : int
        The common denominator of the exact weights.
    arithmetic : str
        ``"int64"``, ``"python-int"`` or ``"float64"``.
    """

    d1: np.ndarray
    d2: np.ndarray
    m: np.ndarray
    steps: int
    fixpoint: bool
    sentinel: int | float
    scale: int
    arithmetic: str

    def number(self, x: int | float | np.integer[Any] | np.floating[Any]) -> Number:
        """A field entry as an unscaled number (``math.inf`` when unreachable)."""
        if isinstance(x, float | np.floating):
            return float(x)
        xi = int(x)
        if xi >= self.sentinel:
            return math.inf
        return normalize(Fraction(xi, self.scale))


@dataclass(frozen=True)
class StructuredValue:
    """``V_H`` by the three-field DP.

    Attributes
    ----------
    horizon : int or None
        ``H`` (None: the untruncated game).
    value : Number
        ``V_H``, exact (``int``/``Fraction``) on rational instances, ``float`` in float mode.
    d1, d2, m : Number
        ``D1_H(s0)``, ``D2_H(s0)``, ``m_H(s0)`` (unscaled).
    steps : int
        Iterations done (stops early at the fixpoint).
    fixpoint : bool
        True when the fields reached their fixpoint (``V_H`` equals every larger horizon's).
    arithmetic : str
        ``"int64"``, ``"python-int"`` or ``"float64"``.
    exact : bool
        False in float mode.
    seconds : float
        Wall time of the DP.
    """

    horizon: int | None
    value: Number
    d1: Number
    d2: Number
    m: Number
    steps: int
    fixpoint: bool
    arithmetic: str
    exact: bool
    seconds: float



def value_fields(instance: Instance, horizon: int | None, roles: Roles | None = None, *,
                 method: Literal["auto", "layers"] = "auto") -> Fields:
    """Iterate the three fields ``min(H, fixpoint)`` times.

    Parameters
    ----------
    instance : Instance
        The game.
    horizon : int or None
        ``H >= 0``; None iterates to the fixpoint (the untruncated game).
    roles : Roles, optional
        Which goal is ``g1``; default the instance's primary goal.
    method : {"auto", "layers"}
        ``"auto"``: the Dijkstra fixpoint (:func:`fixpoint_fields`) when ``H`` reaches it
        (the same fields, steps and flags as the iteration), else the layers;
        ``"layers"``: always the hop-by-hop iteration.

    Returns
    -------
    Fields

    Raises
    ------
    HorizonError
        If ``horizon`` is negative (None is the untruncated game, not an error).

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> f = value_fields(triangle(), None)
    >>> [f.number(x) for x in (f.d1[0], f.d2[0], f.m[0])], f.steps, f.fixpoint
    ([3, 2, 4], 2, True)
    """
    return _value_fields(instance, horizon, roles, method, None)


def _arithmetic(inst: Instance, r: Roles, limit: int) -> tuple[
        Arcs, int | float, type, str, tuple[int, int, int] | tuple[float, float, float]]:
    """How the value fields are computed up to ``limit`` steps: the goal-terminal arcs, the
    sentinel above every finite value, the dtype and its name (int64 while every sum fits,
    else Python integers; float64 in float mode), and the goals' entries ``(0, d(g2, g1),
    d(g1, g2))`` at the arcs' scale."""
    d12, d21 = r.d2[r.g1], r.d1[r.g2]
    if inst.exact:
        arcs = goal_terminal_arcs(inst, extra=(d12, d21))
        wmax = int(arcs.weights.max()) if arcs.weights.size else 0
        term = int(max(d12, d21) * arcs.scale)
        bound = 2 * (limit * wmax + term) + 1  # every finite field value is below this
        sentinel: int | float = 2 * bound  # sums of two sentinels plus a weight must fit
        if 2 * sentinel + wmax < 2**63:
            dtype: type = np.int64
            arithmetic = "int64"
        else:
            dtype = object
            arithmetic = "python-int"
            arcs = Arcs(tails=arcs.tails, starts=arcs.starts, heads=arcs.heads,
                        weights=np.asarray([int(w) for w in arcs.weights], dtype=object),
                        scale=arcs.scale)
        g_vals: tuple[int, int, int] | tuple[float, float, float] = (
            0, int(d21 * arcs.scale), int(d12 * arcs.scale))
    else:
        arcs = goal_terminal_arcs(inst)
        sentinel = math.inf
        dtype = np.float64
        arithmetic = "float64"
        g_vals = (0.0, float(d21), float(d12))
    return arcs, sentinel, dtype, arithmetic, g_vals


def _value_fields(instance: Instance, horizon: int | None, roles: Roles | None,
                  method: Literal["auto", "layers"], node: int | None) -> Fields:
    """:func:`value_fields`; with ``node``, only that node's entries are asked for, and the
    Dijkstra fixpoint serves as soon as they are final by ``H`` (steps and flags unchanged)."""
    if horizon is not None and horizon < 0:
        raise HorizonError(f"the horizon must be a non-negative integer, got {horizon}")
    inst = instance
    r = inst.roles() if roles is None else roles
    n = inst.n_nodes
    cap = 2 * n + 2  # the fields are constant from k = 2n - 2 on (proofs/DP.md, DP.3)
    limit = cap if horizon is None else min(horizon, cap)
    arcs, sentinel, dtype, arithmetic, g_vals = _arithmetic(inst, r, limit)
    zero, g2_to_g1, g1_to_g2 = g_vals
    if method == "auto" and arithmetic == "int64":
        fx = fixpoint_fields(inst, r, arcs=arcs)
        if fx is not None and (fx.last <= limit if node is None else
                               max(fx.h1[node], fx.h2[node], fx.hm[node]) <= limit):
            def final(col: np.ndarray) -> np.ndarray:
                return np.where(col < np.iinfo(np.int64).max, col, sentinel).astype(np.int64)

            return Fields(d1=final(fx.d1), d2=final(fx.d2), m=final(fx.m),
                          steps=min(fx.last + 1, limit), fixpoint=fx.last + 1 <= limit,
                          sentinel=sentinel, scale=arcs.scale, arithmetic=arithmetic)

    # the three fields side by side: columns D1, D2, m (one gather and one reduceat per step)
    def goals(f: np.ndarray) -> None:
        f[r.g1] = (zero, g1_to_g2, g1_to_g2)
        f[r.g2] = (g2_to_g1, zero, g2_to_g1)

    def split(new: np.ndarray) -> None:  # m = min(relaxed m, D1 + D2), in place
        both = new[:, 0] + new[:, 1]
        np.minimum(both, sentinel, out=both)
        np.minimum(new[:, 2], both, out=new[:, 2])

    front = _Frontier(arcs, n)
    fields: np.ndarray = np.full((n, 3), sentinel, dtype=dtype)
    goals(fields)
    steps = 0
    fixpoint = False
    changed: np.ndarray | None = None  # nodes changed by the last step (None: all of them)
    while steps < limit:
        if changed is None or front.large(changed):
            new: np.ndarray = np.full((n, 3), sentinel, dtype=dtype)
            if arcs.tails.size:
                cand = arcs.weights[:, None] + fields[arcs.heads]
                new[arcs.tails] = np.minimum.reduceat(cand, arcs.starts, axis=0)
                np.minimum(new, sentinel, out=new)
            goals(new)
            split(new)
            changed = np.flatnonzero((new != fields).any(axis=1))
            if changed.size:
                fields = new
        else:  # only tails of arcs into changed nodes can change (proofs/DP.md, DP.4)
            changed = front.step(fields, changed, sentinel, split)
        steps += 1
        if not changed.size:
            fixpoint = True
            break
    d1, d2, m = (np.ascontiguousarray(fields[:, i]) for i in range(3))
    if horizon is None and not fixpoint:  # pragma: no cover - DP.3 bounds the iterations
        raise AssertionError(f"the value fields did not reach their fixpoint in {cap} steps")
    if not fixpoint and steps == cap:  # pragma: no cover - same bound, finite horizon
        fixpoint = True
    return Fields(d1=d1, d2=d2, m=m, steps=steps, fixpoint=fixpoint, sentinel=sentinel,
                  scale=arcs.scale, arithmetic=arithmetic)


def structured_value(instance: Instance, horizon: int | None) -> StructuredValue:
    """``V_H`` of the game truncated at ``horizon`` steps (None: untruncated), without the tree.

    ``V_H = b2·m_H(s0) + (b1 − b2)·D1_H(s0)`` with the instance's primary goal as ``g1``
    (``b1 >= b2``; the value does not depend on the labelling at ``b1 = b2``).

    Parameters
    ----------
    instance : Instance
        The game.
    horizon : int or None
        ``H >= 0``; None for the untruncated game (``--horizon inf``).

    Returns
    -------
    StructuredValue

    Raises
    ------
    HorizonError
        If ``horizon`` is negative or no walk from ``s0`` reaches a goal within it (the same
        refusal as the walk tree's).

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> inst = triangle()
    >>> [str(structured_value(inst, h).value) for h in (1, 2)], structured_value(inst, None).value
    (['12/5', '12/5'], Fraction(12, 5))
    >>> structured_value(inst, 0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.HorizonError: no walk from the start reaches a goal within H = 0 steps ...
    """
    t0 = time.perf_counter()
    roles = instance.roles()
    s0 = instance.start
    f = _value_fields(instance, horizon, roles, "auto", s0)
    d1, d2, m = f.number(f.d1[s0]), f.number(f.d2[s0]), f.number(f.m[s0])
    if d1 == math.inf:
        raise HorizonError(f"no walk from the start reaches a goal within H = {horizon} steps "
                           f"(the nearest goal is {instance.hops[s0]} steps away)")
    if instance.exact:
        value: Number = normalize(roles.b2 * m + (roles.b1 - roles.b2) * d1)
    else:
        value = float(roles.b2) * float(m) + float(roles.b1 - roles.b2) * float(d1)
    return StructuredValue(horizon=horizon, value=value, d1=d1, d2=d2, m=m, steps=f.steps,
                           fixpoint=f.fixpoint, arithmetic=f.arithmetic, exact=instance.exact,
                           seconds=time.perf_counter() - t0)


class _Frontier:
    """Sparse Bellman–Ford steps: recompute only the tails of arcs into changed nodes."""

    def __init__(self, arcs: Arcs, n: int) -> None:
        self.arcs = arcs
        deg = np.diff(np.append(arcs.starts, arcs.heads.size))
        self.first = np.zeros(n, dtype=np.int64)
        self.deg = np.zeros(n, dtype=np.int64)
        self.first[arcs.tails] = arcs.starts
        self.deg[arcs.tails] = deg
        tail_of_arc = np.repeat(arcs.tails, deg)
        order = np.argsort(arcs.heads, kind="stable")
        self.in_tails = tail_of_arc[order]  # tails of the arcs into each head, head by head
        self.in_first = np.zeros(n, dtype=np.int64)
        self.in_deg = np.bincount(arcs.heads, minlength=n).astype(np.int64)
        self.in_first[1:] = np.cumsum(self.in_deg)[:-1]
        self.limit = max(1, arcs.tails.size // 4)
        self.has_arcs = self.deg > 0

    def large(self, changed: np.ndarray) -> bool:
        """True when a full vectorised step is cheaper than a sparse one."""
        return int(changed.size) > self.limit

    @staticmethod
    def _ranges(first: np.ndarray, count: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        offs = np.cumsum(count) - count
        idx = np.repeat(first - offs, count) + np.arange(int(count.sum()), dtype=np.int64)
        return idx, offs

    def step(self, fields: np.ndarray, changed: np.ndarray, sentinel: int | float,
             split: Callable[[np.ndarray], None]) -> np.ndarray:
        """Advance ``fields`` (columns D1, D2, m) one step in place; the nodes that changed.

        Recomputing a node whose successors did not change gives its value again (the step
        is the same minimum over the same numbers), so one set of nodes serves all three
        fields: the tails of arcs into nodes where any field changed.
        """
        idx, _ = self._ranges(self.in_first[changed], self.in_deg[changed])
        mark = np.zeros(self.has_arcs.size, dtype=bool)
        mark[self.in_tails[idx]] = True
        mark &= self.has_arcs  # goals and dead ends never change after step 1
        todo = np.flatnonzero(mark)
        if not todo.size:
            return todo
        a = self.arcs
        idx, offs = self._ranges(self.first[todo], self.deg[todo])
        new = np.minimum.reduceat(a.weights[idx, None] + fields[a.heads[idx]], offs, axis=0)
        np.minimum(new, sentinel, out=new)
        split(new)
        moved = (new != fields[todo]).any(axis=1)
        fields[todo] = new  # every new value was computed from the old fields above
        return todo[moved]
