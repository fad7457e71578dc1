"""Human-readable text for an equilibrium (what ``dpp solve`` prints)."""

from __future__ import annotations

from collections.abc import Hashable, Sequence
from typing import TYPE_CHECKING

from dppio.text import count, decimal
from solver.numbers import Number, format_value

if TYPE_CHECKING:
    from solver.twogoal.equilibrium import Equilibrium


_MAX_NODES = 12


def path_label(label: str) -> str:
    """A path label in text: ``xi1_II`` -> ``ξ^{1,II}``, ``xi1`` (one primary path) -> ``ξ¹``.

    Examples
    --------
    >>> path_label("xi1_II"), path_label("xi1"), path_label("xi2")
    ('ξ^{1,II}', 'ξ¹', 'ξ²')
    """
    head, _, tail = label.partition("_")
    sup = {"xi1": "1", "xi2": "2"}.get(head)
    if sup is None:
        return label
    if not tail:
        return "ξ¹" if sup == "1" else "ξ²"
    return "ξ^{" + sup + "," + tail + "}"


def summarize(eq: Equilibrium) -> str:
    """What ``dpp solve`` prints for the solver's result ``eq``: goals, ξ² with σ* per step and
    phases, the primary mixture, the type costs, value and VoI (several lines).

    Examples
    --------
    >>> from solver.game.instance import triangle
    >>> from solver.twogoal.equilibrium import paper_equilibrium
    >>> print(summarize(paper_equilibrium(triangle())))
    start 's'; primary goal g1 = 'g1' (prior 7/10), secondary goal g2 = 'g2' (prior 3/10)
    mode: exact (rational)
    <BLANKLINE>
    secondary path ξ² (1 step): 's' -> 'g2'
      σ*(g1) per step: [1/2]
      phases: I absent, II = steps 1..1, III absent   (t_I=0, t_II=1, T=1)
    primary mixture:
      ξ^{1,I}   p = 4/7     's' -> 'g1'
      ξ^{1,II}  p = 3/7     's' -> 'g2'
    <BLANKLINE>
    U1 (primary cost)   = 3
    U2 (secondary cost) = 1
    U* (value)          = 12/5 (≈ 2.4)
    Ū (complete information) = 27/10 (≈ 2.7)
    VoI*                = 1/9 (≈ 0.1111)
    """
    inst = eq.instance
    ph = eq.phases
    lines = [
        f"start {inst.start!r}; primary goal g1 = {inst.primary!r} (prior {inst.b1}), "
        f"secondary goal g2 = {inst.secondary!r} (prior {inst.b2})",
        f"mode: {eq.numbers.describe()}",
        "",
        f"secondary path ξ² ({count(ph.T, 'step')}): {_path(eq.secondary_path)}",
        f"  σ*(g1) per step: {_nums(eq.schedule)}",
        f"  phases: I {_steps(1, ph.t_I)}, II {_steps(ph.t_I + 1, ph.t_II)}, "
        f"III {_steps(ph.t_II + 1, ph.T)}   (t_I={ph.t_I}, t_II={ph.t_II}, T={ph.T})",
        "primary mixture:",
    ]
    for p in eq.primary_paths:
        label = path_label(p.label)
        lines.append(f"  {label:9s} p = {p.probability!s:7s} {_path(p.nodes)}")
    lines += [
        "",
        f"U1 (primary cost)   = {_num(eq.U1)}",
        f"U2 (secondary cost) = {_num(eq.U2)}",
        f"U* (value)          = {_num(eq.U)}",
        f"Ū (complete information) = {_num(eq.U_bar)}",
        f"VoI*                = {_num(eq.VoI)}",
    ]
    return "\n".join(lines)


def _steps(first: int, last: int) -> str:
    return f"= steps {first}..{last}" if first <= last else "absent"


_num = format_value


def _nums(xs: Sequence[Number]) -> str:
    shown = [str(x) if not isinstance(x, float) else decimal(x) for x in xs[:_MAX_NODES * 2]]
    more = f" ... (+{len(xs) - len(shown)})" if len(xs) > len(shown) else ""
    return "[" + ", ".join(shown) + "]" + more


def _path(nodes: Sequence[Hashable]) -> str:
    if len(nodes) <= _MAX_NODES:
        return " -> ".join(map(repr, nodes))
    head = " -> ".join(map(repr, nodes[:5]))
    tail = " -> ".join(map(repr, nodes[-5:]))
    return f"{head} -> ... ({len(nodes) - 10} more) ... -> {tail}"
