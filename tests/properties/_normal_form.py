"""An independent route to V_H on tiny games: the normal-form LP over pure strategies in
which the Attacker observes the Defender's past allocations.

Defender pure strategies: one allocation (g1 or g2) per walk prefix of the truncated tree.
Attacker pure strategies of type θ: a next node for every history (walk prefix AND the
Defender's allocations so far); their cost vectors (one cost per Defender pure strategy) are
built recursively: at prefix p choose a child q, then continue with one strategy when the
Defender allocated to g1 at q and another when it allocated to g2. Then

    V_H = max_{y ∈ Δ(D)}  b1 min_{π1} c_{π1}·y + b2 min_{π2} c_{π2}·y

solved with scipy's HiGHS (float; tolerance set by the caller)."""

from __future__ import annotations

import itertools
from collections.abc import Hashable

import numpy as np
from scipy.optimize import linprog

from tests.properties._reference import Game

Walk = tuple[Hashable, ...]


class TooLarge(Exception):
    """The normal form would be too large to enumerate."""


def tree_prefixes(game: Game, horizon: int) -> list[Walk]:
    """Non-root prefixes of the walks (≤ horizon steps, ending at their first goal)."""
    seen: dict[Walk, None] = {}
    for walk in game.walks(horizon):
        for t in range(1, len(walk)):
            seen.setdefault(walk[: t + 1])
    return list(seen)


def normal_form_value(game: Game, horizon: int, *, max_defender: int = 2 ** 11,
                      max_attacker: int = 20_000) -> float:
    prefixes = tree_prefixes(game, horizon)
    if 2 ** len(prefixes) > max_defender:
        raise TooLarge(f"{len(prefixes)} prefixes")
    index = {p: i for i, p in enumerate(prefixes)}
    pures = np.array(list(itertools.product((0, 1), repeat=len(prefixes))), dtype=float)
    n_def = len(pures)
    children: dict[Walk, list[Walk]] = {}
    for p in prefixes:
        children.setdefault(p[:-1], []).append(p)

    def vectors(p: Walk, theta: int) -> set[tuple[float, ...]]:
        end = p[-1]
        if game.is_goal(end):
            goal = game.g1 if theta == 1 else game.g2
            return {tuple([float(game.d_to(end, goal))] * n_def)}
        out: set[tuple[float, ...]] = set()
        for q in children.get(p, []):
            w = float(game.weight(p[-1], q[-1]))
            alloc = pures[:, index[q]]                        # 1: allocated to g1
            paid = w * (alloc if theta == 1 else 1 - alloc)   # pays when guarding θ's goal
            cont = [np.array(c) for c in vectors(q, theta)]
            if len(out) + len(cont) ** 2 > max_attacker:
                raise TooLarge("too many attacker strategies")
            for c1, c0 in itertools.product(cont, cont):
                out.add(tuple(paid + np.where(alloc == 1, c1, c0)))
        return out

    root = (game.start,)
    c1 = np.array(sorted(vectors(root, 1)))
    c2 = np.array(sorted(vectors(root, 2)))
    # variables: y (n_def), v1, v2; maximise b1 v1 + b2 v2
    n = n_def + 2
    cost = np.zeros(n)
    cost[-2], cost[-1] = -float(game.b1), -float(game.b2)
    rows = []
    for c in c1:
        rows.append(np.concatenate([-c, [1.0, 0.0]]))
    for c in c2:
        rows.append(np.concatenate([-c, [0.0, 1.0]]))
    a_eq = np.concatenate([np.ones(n_def), [0.0, 0.0]])[None, :]
    bounds = [(0, None)] * n_def + [(None, None)] * 2
    res = linprog(cost, A_ub=np.array(rows), b_ub=np.zeros(len(rows)), A_eq=a_eq, b_eq=[1.0],
                  bounds=bounds, method="highs")
    if res.status != 0:
        raise RuntimeError(f"normal-form LP: {res.message}")
    return float(-res.fun)


