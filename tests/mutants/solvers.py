"""Deliberately wrong solvers: ``mutant_xxx(instance_doc) -> profile_doc``.

Each starts from the real solver's equilibrium (ξ², σ* schedule, phases) and corrupts one
step of the construction. The profiles carry no ``value``/``phases`` claims, so the audit
can only catch a mutant through the game itself (well-formedness, regrets, sequential
rationality, beliefs), never by comparing claimed numbers. Shortest paths to ``g1`` come from
the reference model of ``tests/properties/_reference.py``.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable, Sequence
from fractions import Fraction
from typing import Any

from solver import Equilibrium, instance_from_json
from solver.twogoal.equilibrium import paper_equilibrium
from tests.properties._reference import INF, Game

Doc = dict[str, Any]
Path = tuple[Hashable, ...]


def _json(v: Hashable) -> Any:
    return list(v) if isinstance(v, tuple) else v


def _base(doc: Doc) -> tuple[Equilibrium, Game]:
    return paper_equilibrium(instance_from_json(doc)), Game.from_doc(doc)


def _psi(game: Game, u: Hashable, *, avoid_first: Hashable | None = None) -> Path:
    """A shortest path ``u -> g1`` following tight arcs (the first listed tight arc)."""
    path = [u]
    while path[-1] != game.g1:
        x = path[-1]
        d = game.d_to(x, game.g1)
        path.append(next(v for v, w in game.succ[x]
                         if w + game.d_to(v, game.g1) == d
                         and not (len(path) == 1 and v == avoid_first)))
    return tuple(path)


def _branch(game: Game, xi2: Path, t: int) -> Path:
    """``ξ²[0..t] + ψ(ξ²[t], g1)``; ξ² itself when ``t = T``."""
    if t >= len(xi2) - 1:
        return xi2
    return xi2[:t] + _psi(game, xi2[t])


def _profile(game: Game, primary: Sequence[tuple[Path, Fraction]], xi2: Path,
             defender: Doc | None = None) -> Doc:
    merged: dict[Path, Fraction] = {}
    for path, p in primary:
        if p > 0:
            merged[path] = merged.get(path, Fraction(0)) + p
    return {
        "format": "dpp-profile/1",
        "goals": {"primary": _json(game.g1), "secondary": _json(game.g2)},
        "defender": defender or {"rule": "progress", "goal": _json(game.g1)},
        "attacker": {
            "primary": [{"path": [_json(v) for v in path], "probability": str(p)}
                        for path, p in merged.items()],
            "secondary": [{"path": [_json(v) for v in xi2], "probability": "1"}],
        },
    }


def _mixture(game: Game, xi2: Path, t_i: int, t_ii: int, p_ii: Fraction) -> list[
        tuple[Path, Fraction]]:
    return [(_branch(game, xi2, t_i), 1 - p_ii), (_branch(game, xi2, t_ii), p_ii)]


def _phases(game: Game, xi2: Path) -> tuple[int, int]:
    t_i, t_ii, _ = game.phases(xi2)
    return t_i, t_ii


# ----------------------------------------------------------------------------- mutants
def mutant_swapped_mixing(doc: Doc) -> Doc:
    """The sentence before eq. (15): ξ^{1,I} with b2/b1 and ξ^{1,II} with 1 − b2/b1."""
    eq, game = _base(doc)
    xi2 = eq.secondary_path
    t_i, t_ii = _phases(game, xi2)
    p_ii = 1 - game.b2 / game.b1
    return _profile(game, _mixture(game, xi2, t_i, t_ii, p_ii), xi2)


def mutant_late_branch(doc: Doc) -> Doc:
    """Both primary paths leave ξ² one step after t_I and t_II."""
    eq, game = _base(doc)
    xi2 = eq.secondary_path
    t_i, t_ii = _phases(game, xi2)
    return _profile(game, _mixture(game, xi2, t_i + 1, t_ii + 1, game.b2 / game.b1), xi2)


def mutant_xi2_shortest_path(doc: Doc) -> Doc:
    """ξ² is a plain shortest path s0 → g2 (cut at the first goal); the rest is eq. (15)."""
    _, game = _base(doc)
    path = [game.start]
    while not game.is_goal(path[-1]):
        x = path[-1]
        d = game.d_to(x, game.g2)
        path.append(next(v for v, w in game.succ[x] if w + game.d_to(v, game.g2) == d))
    xi2 = tuple(path)
    t_i, t_ii = _phases(game, xi2)
    return _profile(game, _mixture(game, xi2, t_i, t_ii, game.b2 / game.b1), xi2)


def mutant_no_goal_avoidance(doc: Doc) -> Doc:
    """ξ² = shortest s0 → v* then v* → g2, NOT cut at the first goal it reaches (walks that
    pass through g1 on the way to g2)."""
    _, game = _base(doc)
    d0 = _distances_from(game)
    pivot = min((v for v in game.nodes if v in d0),
                key=lambda v: d0[v] + game.d_to(v, game.g1) + game.d_to(v, game.g2))
    head = [pivot]
    while head[-1] != game.start:
        x = head[-1]
        head.append(next(u for u in game.nodes if u in d0 and any(
            v == x and d0[u] + w == d0[x] for v, w in game.succ[u])))
    tail = [pivot]
    while tail[-1] != game.g2:
        x = tail[-1]
        d = game.d_to(x, game.g2)
        tail.append(next(v for v, w in game.succ[x] if w + game.d_to(v, game.g2) == d))
    xi2 = tuple(head[::-1]) + tuple(tail[1:])
    t_i, t_ii = _phases(game, xi2)
    return _profile(game, _mixture(game, xi2, t_i, t_ii, game.b2 / game.b1), xi2)


def mutant_defender_lag(doc: Doc) -> Doc:
    """σ* one step late (c_{t-1} read where c_t is due): after s0 … s_t the table Defender
    plays σ*'s allocation of the previous step (0 on the first step). A ``table`` Defender
    listing every walk of at most H steps, with σ* (`"default": "progress"`) on longer ones so
    that it is defined on every walk of the untruncated game."""
    eq, game = _base(doc)
    profile = _profile(game, [(p.nodes, p.probability) for p in eq.primary_paths],
                       eq.secondary_path)
    horizon = max(len(p.nodes) - 1 for p in eq.primary_paths)
    horizon = max(horizon, len(eq.secondary_path) - 1)
    entries = []
    for walk in _walks(game, horizon):
        sigma = game.sigma(walk)
        lagged = sigma[-2] if len(sigma) >= 2 else Fraction(0)
        entries.append({"walk": [_json(v) for v in walk], "probability": str(lagged)})
    profile["defender"] = {"rule": "table", "goal": _json(game.g1), "entries": entries,
                           "default": "progress"}  # defined on every walk of the game
    return profile


def mutant_drop_phase_ii(doc: Doc) -> Doc:
    """Phase II dropped: the primary always branches at t_I."""
    eq, game = _base(doc)
    xi2 = eq.secondary_path
    t_i, _ = _phases(game, xi2)
    return _profile(game, [(_branch(game, xi2, t_i), Fraction(1))], xi2)


def mutant_tie_uniform(doc: Doc) -> Doc:
    """Wrong tie handling: at b1 = b2 = 1/2 mix ξ^{1,I} and ξ^{1,II} half and half (eq. (15)
    puts all weight on ξ^{1,II})."""
    eq, game = _base(doc)
    xi2 = eq.secondary_path
    t_i, t_ii = _phases(game, xi2)
    p_ii = Fraction(1, 2) if game.b1 == game.b2 else game.b2 / game.b1
    return _profile(game, _mixture(game, xi2, t_i, t_ii, p_ii), xi2)


def mutant_detour_branch(doc: Doc) -> Doc:
    """The primary leaves ξ² at t_I / t_II along a cheapest NON-shortest first step (then a
    shortest path to g1), when such a step exists."""
    eq, game = _base(doc)
    xi2 = eq.secondary_path
    t_i, t_ii = _phases(game, xi2)

    def branch(t: int) -> Path:
        if t >= len(xi2) - 1:
            return xi2
        b = xi2[t]
        d = game.d_to(b, game.g1)
        worse = sorted(((w + game.d_to(v, game.g1), str(v), v) for v, w in game.succ[b]
                        if w + game.d_to(v, game.g1) > d and v != game.g2
                        and game.d_to(v, game.g1) != INF), key=lambda x: (x[0], x[1]))
        if not worse:
            return _branch(game, xi2, t)
        v = worse[0][2]
        return xi2[:t + 1] + _psi(game, v)

    p_ii = game.b2 / game.b1
    return _profile(game, [(branch(t_i), 1 - p_ii), (branch(t_ii), p_ii)], xi2)


def mutant_defender_wrong_goal(doc: Doc) -> Doc:
    """The real Attacker, but σ* measures progress towards g2 instead of g1."""
    eq, game = _base(doc)
    profile = _profile(game, [(p.nodes, p.probability) for p in eq.primary_paths],
                       eq.secondary_path)
    profile["defender"] = {"rule": "progress", "goal": _json(game.g2)}
    return profile


def mutant_first_walk_only(doc: Doc) -> Doc:
    """The primary plays only the first of its walks, with probability 1 (it passes
    small budgets and is caught only where the primary mixes, i.e. when phase II exists)."""
    eq, game = _base(doc)
    first = eq.primary_paths[0]
    return _profile(game, [(first.nodes, Fraction(1))], eq.secondary_path)


MUTANTS: dict[str, Callable[[Doc], Doc]] = {
    "swapped mixing probabilities": mutant_swapped_mixing,
    "branching one step late": mutant_late_branch,
    "xi2 = plain shortest path to g2": mutant_xi2_shortest_path,
    "ignoring goal avoidance (xi2 not cut)": mutant_no_goal_avoidance,
    "sigma* lagging one step (table)": mutant_defender_lag,
    "dropping phase II": mutant_drop_phase_ii,
    "b = 1/2 tie mixed half/half": mutant_tie_uniform,
    "primary branch not a shortest path": mutant_detour_branch,
    "sigma* towards g2": mutant_defender_wrong_goal,
    "primary plays only its first walk": mutant_first_walk_only,
}
"""Every mutant, by a short description."""


# ----------------------------------------------------------------------------- helpers
def _distances_from(game: Game) -> dict[Hashable, Fraction]:
    import heapq

    dist: dict[Hashable, Fraction] = {game.start: Fraction(0)}
    heap: list[tuple[Fraction, int, Hashable]] = [(Fraction(0), 0, game.start)]
    tick = 0
    while heap:
        d, _, u = heapq.heappop(heap)
        if d > dist[u]:
            continue
        for v, w in game.succ[u]:
            if v not in dist or d + w < dist[v]:
                dist[v] = d + w
                tick += 1
                heapq.heappush(heap, (dist[v], tick, v))
    return dist


def _walks(game: Game, horizon: int) -> list[Path]:
    """Every walk from s0 with 1..horizon steps that does not pass a goal before its end."""
    out: list[Path] = []
    frontier: list[Path] = [(game.start,)]
    for _ in range(horizon):
        nxt: list[Path] = []
        for walk in frontier:
            if game.is_goal(walk[-1]):
                continue
            for v, _w in game.succ[walk[-1]]:
                nxt.append((*walk, v))
        out.extend(nxt)
        frontier = nxt
    return out
