"""The N-goal construction: coalition Attacker and guarantee-vector Defender (proofs/NSOLVE.md).

- **Root.** The cover LP ``min Σ_S c_S m_S(s0)`` s.t. ``Σ_S c_S 1_S = b`` (exact simplex,
  :func:`solver.coalitions.coalition_dp.cover_lp`) gives the starting coalitions (mass
  ``c_S``); ``h`` is its lexicographically largest optimal dual in the priority order (the
  simplex on a lexicographically perturbed right-hand side): ``h(S) <= m_S(s0)``, ``h·b`` =
  the coalition DP's value; for two goals the paper's ``(d(s0, g1), M - d(s0, g1))``.
- **Attacker.** Each coalition ``S`` of mass ``μ`` at a node ``v`` follows an argmin of the DP:
  it steps ``v -> u`` when ``m_S(v) = w(v, u) + m_S(u)`` (preferred: coalitions stay together;
  among such arcs the one to the lowest node index), else splits into the minimal balanced
  collection ``{T: λ_T}`` attaining ``m_S(v)`` (children of mass ``μ·λ_T``), and stops at a
  goal. Type ``θ`` plays each resulting walk with probability (mass of the coalitions ``∋ θ``
  ending on it) / ``b_θ``.
- **Defender.** The guarantee rule with ``h``: :mod:`solver.coalitions.guarantee_rule`, written
  to the profile as ``{"rule": "guarantee", "h": [...]}`` (``docs/formats.md`` §2b).

The construction is an equilibrium wherever the *arc condition* holds
(``proofs/NSOLVE.md``); ``dpp solve`` certifies every N-goal profile with the independent
checker before writing it and refuses (one line, nothing written) when it does not pass.
"""

from __future__ import annotations

import functools
import time
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from solver.coalitions.coalition_dp import Coalitions, balanced_collections, coalition_dp, cover_lp
from solver.coalitions.coalition_dp import subset_members as _members
from solver.coalitions.guarantee_rule import guarantee_step, priority_order
from solver.game.instance import Instance
from solver.game.profile_writing import per_goal_profile
from solver.game.walks import StrategyWalk

__all__ = ["CoalitionEquilibrium", "coalition_equilibrium"]

METHOD = ("coalition Attacker and guarantee-vector Defender (proofs/NSOLVE.md); coalition DP "
          "at H = inf; steps preferred to splits, lowest node index first")


@dataclass(frozen=True, eq=False)
class CoalitionEquilibrium:
    """The profile the coalition construction gives, with its exact values (any N >= 2).

    Attributes
    ----------
    instance : Instance
        The game (exact weights).
    h : tuple of Fraction
        The Defender's guarantee vector (the cover LP's canonical optimal dual).
    cover : dict
        Subset mask -> starting coalition mass ``c_S``.
    mixtures : tuple
        ``mixtures[θ]``: ``((walk as node indices, probability), …)``.
    costs : tuple of Fraction
        ``U^θ``: type θ's expected cost against the rule (exact).
    guarded, walked : tuple of Fraction
        Type θ's expected stage cost ``E[Σ_t w_t σ_t(θ)]`` (the weight the Defender puts on
        its goal) and expected walk length ``E[Σ_t w_t]``.
    U, U_bar, VoI, dp_value : Fraction
        ``Σ b_θ U^θ``; ``Σ b_θ d(s0, g^θ)``; ``(Ū − U)/Ū``; the coalition DP's value ``h·b``.
    feasible : bool
        Whether the rule's ``F`` was non-empty at every step of the profile's walks.
    seconds : float
        Solve time.
    """

    instance: Instance = field(repr=False)
    h: tuple[Fraction, ...]
    cover: dict[int, Fraction]
    mixtures: tuple[tuple[tuple[tuple[int, ...], Fraction], ...], ...]
    costs: tuple[Fraction, ...]
    guarded: tuple[Fraction, ...]
    walked: tuple[Fraction, ...]
    U: Fraction
    U_bar: Fraction
    VoI: Fraction
    dp_value: Fraction
    feasible: bool
    seconds: float

    @property
    def strategies(self) -> tuple[tuple[StrategyWalk, ...], ...]:
        """``strategies[θ]``: the mixed strategy of goal index θ, as walks with probabilities."""
        net = self.instance.network
        return tuple(tuple(StrategyWalk.along(net, walk, p) for walk, p in mix)
                     for mix in self.mixtures)

    def to_json(self) -> dict[str, Any]:
        """The ``dpp-ngoal-profile/1`` document with the guarantee rule (``docs/formats.md``
        §2b), written by :func:`~solver.game.profile_writing.per_goal_profile`.

        Examples
        --------
        >>> from solver.game.instance_reading import instance_from_json
        >>> doc = {"graph": {"nodes": [{"id": x} for x in "sab"],
        ...        "edges": [{"source": "s", "target": "a"}, {"source": "s", "target": "b"}]},
        ...        "start": "s", "goals": ["a", "b"], "prior": ["1/2", "1/2"]}
        >>> out = coalition_equilibrium(instance_from_json(doc)).to_json()
        >>> out["defender"], out["value"]["U"]
        ({'rule': 'guarantee', 'h': ['1', '1']}, '1')
        """
        return per_goal_profile(
            self.instance, self.strategies,
            defender={"rule": "guarantee", "h": [str(x) for x in self.h]},
            values={"U": str(self.U), "U_types": [str(x) for x in self.costs],
                    "U_bar": str(self.U_bar), "VoI": str(self.VoI)},
            method=METHOD,
            cover={"+".join(str(t + 1) for t in _members(s)): str(c)
                   for s, c in sorted(self.cover.items())})


def _m_at(dp: Coalitions, u: int, mask: int) -> Fraction | None:
    return dp.m(mask, u)


def _expand(dp: Coalitions, cover: dict[int, Fraction]
            ) -> list[tuple[tuple[int, ...], int, Fraction]]:
    """Follow every coalition's argmins from the start: ``(walk, mask, mass)`` at the goals."""
    game = dp.instance
    net = game.network
    goals = set(game.targets)
    scale_w = dp.scale // game.denominator  # arc numerators -> DP scale
    out: list[tuple[tuple[int, ...], int, Fraction]] = []
    stack: list[tuple[list[int], int, Fraction]] = [([game.s0], s, c)
                                                    for s, c in sorted(cover.items())]
    while stack:
        walk, mask, mass = stack.pop()
        v = walk[-1]
        while v not in goals:
            here = int(dp.cost[mask][v])
            lo, hi = int(net.indptr[v]), int(net.indptr[v + 1])
            nxt = None
            for k in range(lo, hi):
                u = int(net.indices[k])
                mu = int(dp.cost[mask][u])
                if mu >= 0 and int(net.weights[k]) * scale_w + mu == here:
                    nxt = u
                    break
            if nxt is not None:
                walk.append(nxt)
                v = nxt
                continue
            if int(dp.split[mask][v]) != here:  # pragma: no cover - the DP's definition
                raise AssertionError("coalition DP: no argmin at a node")
            elems = _members(mask)
            coll = balanced_collections(len(elems))[int(dp.split_choice[mask][v])]
            for t, lam in coll:
                sub = sum(1 << elems[i] for i in _members(t))
                stack.append((list(walk), sub, mass * lam))
            break
        else:
            out.append((tuple(walk), mask, mass))
    return out


def coalition_equilibrium(game: Instance) -> CoalitionEquilibrium:
    """The coalition construction on ``game`` (exact): the entry of the N-goal construction,
    which :func:`solver.solve` calls for ``N >= 3`` (for two goals it gives σ*'s values).

    Examples
    --------
    >>> from solver.game.instance_reading import instance_from_json
    >>> doc = {"graph": {"nodes": [{"id": x} for x in "smabc"],
    ...        "edges": [{"source": "s", "target": "m"}, {"source": "m", "target": "a"},
    ...                  {"source": "m", "target": "b"}, {"source": "m", "target": "c"},
    ...                  {"source": "s", "target": "a", "weight": 2}]},
    ...        "start": "s", "goals": ["a", "b", "c"], "prior": ["1/2", "1/3", "1/6"]}
    >>> eq = coalition_equilibrium(instance_from_json(doc))
    >>> str(eq.U), str(eq.dp_value), eq.feasible
    ('3/2', '3/2', True)
    """
    t0 = time.perf_counter()
    dp = coalition_dp(game)
    n = game.n_goals
    s0 = game.s0
    costs0 = {mask: dp.m(mask, s0) for mask in range(1, 1 << n)}
    order = priority_order(game.prior)
    finite = {k: v for k, v in costs0.items() if v is not None}
    root = cover_lp(finite, game.prior, order)  # h: the lexicographically largest optimal dual
    h0 = tuple(root.dual)
    leaves = _expand(dp, dict(root.cover))
    mix: list[dict[tuple[int, ...], Fraction]] = [{} for _ in range(n)]
    for walk, mask, mass in leaves:
        for t in _members(mask):
            mix[t][walk] = mix[t].get(walk, Fraction(0)) + mass / game.prior[t]
    # the rule along every walk (shared prefixes computed once)
    memo: dict[tuple[int, ...], tuple[tuple[Fraction, ...], tuple[Fraction, ...]]] = {}
    feasible = True
    type_cost = [Fraction(0)] * n
    guarded = [Fraction(0)] * n
    walked = [Fraction(0)] * n
    den = game.denominator
    for theta in range(n):
        for walk, prob in mix[theta].items():
            r = h0
            paid = Fraction(0)
            length = Fraction(0)
            for k in range(1, len(walk)):
                key = walk[:k + 1]
                if key not in memo:
                    v, u = walk[k - 1], walk[k]
                    w = Fraction(int(game.network.arc_weight(v, u) or 0), den)
                    sigma, ok = guarantee_step(r, functools.partial(_m_at, dp, u), w, order)
                    feasible &= ok
                    memo[key] = (sigma, tuple(x - w * s for x, s in zip(r, sigma, strict=True)))
                sigma, r_next = memo[key]
                w = Fraction(int(game.network.arc_weight(walk[k - 1], walk[k]) or 0), den)
                paid += w * sigma[theta]
                length += w
                r = r_next
            type_cost[theta] += prob * (paid + game.distance(theta, walk[-1]))
            guarded[theta] += prob * paid
            walked[theta] += prob * length
    u_val = sum((b * c for b, c in zip(game.prior, type_cost, strict=True)), Fraction(0))
    u_bar = sum((game.prior[t] * game.distance(t, s0) for t in range(n)), Fraction(0))
    mixtures = tuple(tuple(sorted(m.items(), key=lambda kv: (-kv[1], kv[0]))) for m in mix)
    return CoalitionEquilibrium(instance=game, h=h0, cover=dict(root.cover),
                        mixtures=mixtures, costs=tuple(type_cost), guarded=tuple(guarded),
                        walked=tuple(walked), U=u_val, U_bar=u_bar,
                        VoI=(u_bar - u_val) / u_bar if u_bar else Fraction(0),
                        dp_value=root.value, feasible=feasible,
                        seconds=time.perf_counter() - t0)
