"""The constructive PBNE of the paper (Sections IV-V) for two goals:
``paper_equilibrium(instance) -> Equilibrium``, the two-goal layer of :func:`solver.solve`."""

from __future__ import annotations

from collections.abc import Hashable
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import numpy as np

from solver.errors import InvalidInstanceError
from solver.game.instance import Instance
from solver.game.profile_writing import two_goal_profile
from solver.game.walks import StrategyWalk
from solver.graph.distances import distances_from, distances_to
from solver.numbers import DEFAULT_ABS_TOL, Number, NumberMode
from solver.twogoal.evaluation import Evaluation, Trajectory, evaluate
from solver.twogoal.phases import Phases, phases_of
from solver.twogoal.primary import primary_mixture
from solver.twogoal.progress import ProgressDefender
from solver.twogoal.secondary import TIE_BREAK, secondary_best_response

METHOD = "constructive PBNE (paper Sec. IV-V; secondary best response by proofs/XI2.md)"


@dataclass(frozen=True, eq=False)
class Equilibrium:
    """The weak PBNE ``(σ*, γ*)`` of an instance, with how it was made.

    Attributes
    ----------
    instance : Instance
        The solved game.
    defender : ProgressDefender
        σ*, eq. (7): allocate to ``g1`` with probability new-progress / step weight.
    secondary : StrategyWalk
        ξ², the secondary type's deterministic path (eq. (9), the argmin), probability 1.
    schedule : tuple
        σ*(g1) after each step of ξ².
    phases : Phases
        ``t_I``, ``t_II``, ``T`` of ξ² (eqs. (10)-(11)).
    primary_paths : tuple of StrategyWalk
        ξ^{1,I} and ξ^{1,II} with probabilities ``1 - b2/b1`` and ``b2/b1`` (eq. (15));
        merged into one path when identical, zero-probability paths dropped. Each keeps
        its node indices (``walk``) and node ids (``nodes``).
    U1, U2, U, U_bar, VoI : Number
        Type costs, the value ``U* = b1 U1 + b2 U2``, the complete-information value and
        ``VoI* = (Ū − U*)/Ū`` (Definition 6). Exact ``Fraction`` for rational instances.
    evaluation : Evaluation
        The exact evaluation of (σ*, γ*) the values come from.
    numbers : NumberMode
        How the numbers were computed: exact (every value a ``Fraction``), or float with
        the absolute tolerance ``numbers.abs_tol`` used for every comparison.
    method, tie_break : str
        Provenance: the construction and the deterministic tie-break among best responses.
    """

    instance: Instance
    defender: ProgressDefender = field(repr=False)
    secondary: StrategyWalk
    schedule: tuple[Number, ...]
    phases: Phases
    primary_paths: tuple[StrategyWalk, ...]
    U1: Number
    U2: Number
    U: Number
    U_bar: Number
    VoI: Number
    evaluation: Evaluation = field(repr=False)
    numbers: NumberMode
    method: str = METHOD
    tie_break: str = TIE_BREAK

    @property
    def secondary_path(self) -> tuple[Hashable, ...]:
        """ξ² as node ids (``secondary.nodes``)."""
        return self.secondary.nodes

    @property
    def trajectories(self) -> tuple[Trajectory, ...]:
        """Per path: σ*(g1), Bayes beliefs ``b^1_t`` and the cumulative expected allocation
        to the true goal at every step (computed on first access)."""
        return self.evaluation.trajectories

    def to_json(self) -> dict[str, Any]:
        """The ``dpp-profile/1`` document (docs/formats.md §2), written by
        :func:`~solver.game.profile_writing.two_goal_profile`: the protocol through which
        ``dppverify.certify(instance, equilibrium)`` takes the solver's objects.

        Examples
        --------
        The triangle's profile, certified by the independent checker:

        >>> from dppverify import certify
        >>> from solver.game.instance import triangle
        >>> inst = triangle()
        >>> doc = paper_equilibrium(inst).to_json()
        >>> [(p["path"], p["probability"]) for p in doc["attacker"]["primary"]]
        [(['s', 'g1'], '4/7'), (['s', 'g2'], '3/7')]
        >>> doc["value"]["U"], doc["phases"], doc["exact"]
        ('12/5', {'t_I': 0, 't_II': 1, 'T': 1}, True)
        >>> certify(inst.to_json(), doc).verdict
        'pass'
        """
        ph = self.phases
        return two_goal_profile(
            self.instance, self.primary_paths, (self.secondary,),
            phases={"t_I": ph.t_I, "t_II": ph.t_II, "T": ph.T},
            values={"U1": self.U1, "U2": self.U2, "U": self.U, "U_bar": self.U_bar,
                    "VoI": self.VoI},
            numbers=self.numbers, method=self.method, tie_break=self.tie_break)


def paper_equilibrium(instance: Instance, *, abs_tol: float = DEFAULT_ABS_TOL) -> Equilibrium:
    """Construct the paper's weak PBNE of ``instance``.

    Three Dijkstra runs (from ``s0``, to ``g1``, to ``g2``), a linear scan for ξ² (proofs/XI2.md),
    then work proportional to the length of the equilibrium paths.

    Parameters
    ----------
    instance : Instance
        The game. Rational weights give exact results.
    abs_tol : float
        Tolerance on distances, used only when some weight is a float: relative to the
        largest weight (scaled by it; the float-mode limit
        :data:`~dppio.limits.MAX_FLOAT_WEIGHT_RATIO` keeps every weight far above it).

    Returns
    -------
    Equilibrium

    Raises
    ------
    InvalidInstanceError
        If a goal cannot be reached from the start or from the other goal.

    Examples
    --------
    >>> from solver.game.instance import triangle
    >>> eq = paper_equilibrium(triangle())  # s -> g2 (2), g2 -> g1 (2), s -> g1 (3)
    >>> eq.secondary_path, eq.phases
    (('s', 'g2'), Phases(t_I=0, t_II=1, T=1))
    >>> [(p.nodes, str(p.probability)) for p in eq.primary_paths]
    [(('s', 'g1'), '4/7'), (('s', 'g2'), '3/7')]
    >>> str(eq.U), str(eq.VoI)
    ('12/5', '1/9')
    """
    net = instance.network
    if not net.numbers.exact and net.weights.size:  # float mode: relative to the largest weight
        abs_tol *= float(np.max(net.weights))
    numbers = net.numbers.with_abs_tol(abs_tol)
    s0 = _index(instance, instance.start)
    g1 = _index(instance, instance.primary)
    g2 = _index(instance, instance.secondary)
    d0 = distances_from(net, s0)
    d1 = distances_to(net, g1)
    d2 = distances_to(net, g2)
    _require_reachable(instance, d0, d1, d2, s0, g1, g2)

    defender = ProgressDefender(net, g1, d1, numbers)
    xi2 = secondary_best_response(net, s0, (g1, g2), d0, d1, d2, numbers)
    schedule = defender.schedule(xi2.walk)
    phases = phases_of(schedule)
    mixture = primary_mixture(net, xi2.walk, phases, g1, d1, instance.b1, instance.b2, numbers)
    secondary = StrategyWalk.along(net, xi2.walk, Fraction(1), "xi2")
    ev = evaluate(net, defender.schedule, mixture, (secondary,), prior=(instance.b1, instance.b2),
                  goals=(g1, g2), d_to=(d1, d2), d_from_start=d0)
    return Equilibrium(
        instance=instance,
        defender=defender,
        secondary=secondary,
        schedule=tuple(schedule),
        phases=phases,
        primary_paths=mixture,
        U1=ev.U1, U2=ev.U2, U=ev.U, U_bar=ev.U_bar, VoI=ev.VoI,
        evaluation=ev,
        numbers=numbers,
    )


def _index(instance: Instance, label: Hashable) -> int:
    i = instance.network.index_of(label)
    if i is None:  # Instance validated this already
        raise InvalidInstanceError(f"node {label!r} not found in graph")
    return i


def _require_reachable(instance: Instance, d0: np.ndarray, d1: np.ndarray, d2: np.ndarray,
                       s0: int, g1: int, g2: int) -> None:
    s, p, q = instance.start, instance.primary, instance.secondary
    for dist, what in ((d0[g1], f"goal {p!r} is unreachable from start {s!r}"),
                       (d0[g2], f"goal {q!r} is unreachable from start {s!r}"),
                       (d1[g2], f"goal {p!r} is unreachable from goal {q!r}"),
                       (d2[g1], f"goal {q!r} is unreachable from goal {p!r}")):
        if dist == np.inf:
            raise InvalidInstanceError(what + " (the game needs d(s0,g1), d(s0,g2), "
                                       "d(g1,g2), d(g2,g1) finite)")
