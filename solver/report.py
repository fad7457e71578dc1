"""Human-readable text for an equilibrium (what ``dpp solve`` prints)."""

from __future__ import annotations

from collections.abc import Hashable, Sequence
from typing import TYPE_CHECKING

from solver.numbers import Number

if TYPE_CHECKING:
    from solver.equilibrium import Equilibrium

__all__ = ["summarize"]

_MAX_NODES = 12


def summarize(eq: Equilibrium) -> str:
    """A multi-line summary: goals, ξ² with σ* per step and phases, the primary mixture,
    the type costs, value and VoI."""
    inst = eq.instance
    ph = eq.phases
    lines = [
        f"start {inst.start!r}; primary goal g1 = {inst.primary!r} (prior {inst.b1}), "
        f"secondary goal g2 = {inst.secondary!r} (prior {inst.b2})",
        f"mode: {'exact (rational)' if eq.exact else f'float, tolerance {eq.tolerance:g}'}",
        "",
        f"secondary path xi2 ({ph.T} steps): {_path(eq.secondary_path)}",
        f"  sigma*(g1) per step: {_nums(eq.schedule)}",
        f"  phases: I {_steps(1, ph.t_I)}, II {_steps(ph.t_I + 1, ph.t_II)}, "
        f"III {_steps(ph.t_II + 1, ph.T)}   (t_I={ph.t_I}, t_II={ph.t_II}, T={ph.T})",
        "primary mixture:",
    ]
    for p in eq.primary_paths:
        lines.append(f"  {p.label:7s} p = {p.probability!s:7s} {_path(p.nodes)}")
    lines += [
        "",
        f"U1 (primary cost)   = {_num(eq.U1)}",
        f"U2 (secondary cost) = {_num(eq.U2)}",
        f"U* (value)          = {_num(eq.U)}",
        f"U_bar (complete information) = {_num(eq.U_bar)}",
        f"VoI*                = {_num(eq.VoI)}",
    ]
    return "\n".join(lines)


def _steps(first: int, last: int) -> str:
    return f"= steps {first}..{last}" if first <= last else "absent"


def _num(x: Number) -> str:
    if isinstance(x, float):
        return f"{x:.10g}"
    return f"{x} (~{float(x):.6g})" if x.denominator != 1 else str(x)


def _nums(xs: Sequence[Number]) -> str:
    shown = [str(x) if not isinstance(x, float) else f"{x:.4g}" for x in xs[:_MAX_NODES * 2]]
    more = f" ... (+{len(xs) - len(shown)})" if len(xs) > len(shown) else ""
    return "[" + ", ".join(shown) + "]" + more


def _path(nodes: Sequence[Hashable]) -> str:
    if len(nodes) <= _MAX_NODES:
        return " -> ".join(map(repr, nodes))
    head = " -> ".join(map(repr, nodes[:5]))
    tail = " -> ".join(map(repr, nodes[-5:]))
    return f"{head} -> ... ({len(nodes) - 10} more) ... -> {tail}"
