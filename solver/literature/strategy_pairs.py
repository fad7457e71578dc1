"""One exact evaluation for any (Defender, Attacker) pair: U¹, U², U and VoI.

Defenders: ``"sigma*"`` (the equilibrium σ*, eq. (7)) and ``"sigma'"`` (greedy on Dragan's
belief, :mod:`solver.literature.greedy_defender`), or any schedule function (walk -> σ(g1) per
step).
Attackers: ``"gamma*"`` (the equilibrium mixture, eqs. (9) and (15)), ``"ambiguity"`` and
``"exaggeration"`` (each type deterministically takes its ξ^{θ,am} / ξ^{θ,ex}, eq. (18)), or
any :class:`Attacker`. Values come from :func:`solver.twogoal.evaluation.evaluate` (eqs. (3),
(4) and Definition 6): exact ``Fraction`` on rational instances, since every allocation is a
``Fraction`` (σ*) or 0/1 (σ').
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from functools import cached_property

import numpy as np

from solver.errors import InvalidInstanceError
from solver.game.instance import Instance
from solver.game.walks import StrategyWalk
from solver.graph.distances import distances_from, distances_to
from solver.literature.deceptive_paths import Kind, deceptive_path
from solver.literature.dragan_belief import DraganObserver
from solver.literature.greedy_defender import DraganDefender
from solver.literature.masters_sardina import LABELS as MS_LABELS
from solver.literature.masters_sardina import STRATEGIES as MS_STRATEGIES
from solver.literature.masters_sardina import plan_all
from solver.numbers import Number
from solver.twogoal.equilibrium import Equilibrium, paper_equilibrium
from solver.twogoal.evaluation import Evaluation, Schedule, evaluate

DEFENDERS = ("sigma*", "sigma'")
ATTACKERS = ("gamma*", "ambiguity", "exaggeration")
PAIRS: tuple[tuple[str, str], ...] = (
    ("sigma*", "gamma*"), ("sigma'", "gamma*"), ("sigma*", "ambiguity"),
    ("sigma*", "exaggeration"), ("sigma'", "ambiguity"), ("sigma'", "exaggeration"),
)
"""The six pairs of the paper's comparison (Sec. VII), equilibrium first."""

MS_PAIRS: tuple[tuple[str, str], ...] = tuple(
    (d, a) for a in MS_STRATEGIES for d in DEFENDERS)
"""Masters & Sardina's π_d1–π_d4 (:mod:`solver.literature.masters_sardina`) against σ* and σ'."""

COMPARE_PAIRS = PAIRS + MS_PAIRS
"""What ``dpp experiment compare`` evaluates: the paper's six pairs, then :data:`MS_PAIRS`."""

LABELS = {"sigma*": "σ*", "sigma'": "σ'", "gamma*": "γ*", "ambiguity": "ambiguity",
          "exaggeration": "exaggeration", **MS_LABELS}
"""How every text output and table spells the strategies; the ASCII names (the keys) are the
spelling of CSV and JSON files, Python arguments and command-line choices."""

FIGURE_LABELS = {key: (rf"$\pi_{{{key[3:]}}}$" if key.startswith("pi_") else label)
                 for key, label in LABELS.items()}
"""How figures spell them: :data:`LABELS`, with Masters & Sardina's π_d1 … π_d4 in mathtext
(the subscript typeset, never a literal underscore)."""


def pair_label(defender: str, attacker: str) -> str:
    """``(σ*, γ*)``: a (Defender, Attacker) pair as text outputs and figures show it.

    Examples
    --------
    >>> pair_label("sigma'", "exaggeration")
    "(σ', exaggeration)"
    """
    return f"({LABELS.get(defender, defender)}, {LABELS.get(attacker, attacker)})"


@dataclass(frozen=True)
class Attacker:
    """A mixed Attacker: per type, walks (node indices) with probabilities summing to 1."""

    name: str
    primary: tuple[StrategyWalk, ...]
    secondary: tuple[StrategyWalk, ...]


@dataclass(frozen=True)
class PairResult:
    """U¹, U², U = b1 U¹ + b2 U², Ū and VoI = (Ū − U)/Ū of one (Defender, Attacker) pair."""

    defender: str
    attacker: str
    U1: Number
    U2: Number
    U: Number
    U_bar: Number
    VoI: Number


@dataclass(frozen=True, eq=False)
class PairEvaluator:
    """Evaluates (Defender, Attacker) pairs on one instance: the distance fields, the
    equilibrium, Dragan's observer and the named strategies are computed once and cached.

    Examples
    --------
    >>> from solver.game.instance import triangle
    >>> game = PairEvaluator.of(triangle())
    >>> r = game.pair("sigma*", "gamma*")
    >>> str(r.U), str(r.VoI)
    ('12/5', '1/9')
    >>> [(p.defender, p.attacker, str(p.U)) for p in game.compare()][:2]
    [('sigma*', 'gamma*', '12/5'), ("sigma'", 'gamma*', '12/5')]
    """

    instance: Instance
    start: int
    g1: int
    g2: int
    d_from_start: np.ndarray
    d_to_g1: np.ndarray
    d_to_g2: np.ndarray

    @classmethod
    def of(cls, instance: Instance) -> PairEvaluator:
        """Index the instance and compute the three distance fields."""
        net = instance.network
        idx = [net.index_of(x) for x in (instance.start, instance.primary, instance.secondary)]
        s0, g1, g2 = (int(i) for i in idx if i is not None)
        return cls(instance, s0, g1, g2, distances_from(net, s0), distances_to(net, g1),
                   distances_to(net, g2))

    # ------------------------------------------------------------------ strategies
    @cached_property
    def equilibrium(self) -> Equilibrium:
        """(σ*, γ*) from :func:`solver.solve`."""
        return paper_equilibrium(self.instance)

    @cached_property
    def observer(self) -> DraganObserver:
        """Dragan's observer (eq. (17)) on this instance."""
        return DraganObserver(self.instance.network, self.start, self.g1, self.g2,
                              self.d_to_g1, self.d_to_g2, self.instance.b1, self.instance.b2)

    def defender(self, name: str) -> Schedule:
        """The schedule of ``"sigma*"`` or ``"sigma'"``."""
        if name == "sigma*":
            return self.equilibrium.defender.schedule
        if name == "sigma'":
            alt = self._alt_defender
            return lambda walk: list[Number](alt.schedule(walk))
        raise InvalidInstanceError(f"unknown Defender {name!r}; expected one of {DEFENDERS}")

    @cached_property
    def _alt_defender(self) -> DraganDefender:
        return DraganDefender(self.observer)

    def attacker(self, name: str) -> Attacker:
        """``"gamma*"``, ``"ambiguity"`` or ``"exaggeration"``."""
        if name == "gamma*":
            return self._gamma_star
        if name in ("ambiguity", "exaggeration"):
            kind: Kind = "ambiguity" if name == "ambiguity" else "exaggeration"
            return self._deceptive(kind)
        if name in MS_STRATEGIES:
            return self._masters_sardina[name]
        raise InvalidInstanceError(f"unknown Attacker {name!r}; expected one of "
                                   f"{ATTACKERS + MS_STRATEGIES}")

    @cached_property
    def _masters_sardina(self) -> dict[str, Attacker]:
        """π_d1–π_d4 (:mod:`solver.literature.masters_sardina`): one deterministic walk per type."""
        net, out = self.instance.network, {}
        for name, (p1, p2) in plan_all(self.instance).items():
            out[name] = Attacker(name, (StrategyWalk.along(net, p1.walk, Fraction(1),
                                                           f"xi1_{name}"),),
                                 (StrategyWalk.along(net, p2.walk, Fraction(1),
                                                     f"xi2_{name}"),))
        return out

    @cached_property
    def _gamma_star(self) -> Attacker:
        eq = self.equilibrium
        return Attacker("gamma*", eq.primary_paths, (eq.secondary,))

    def _deceptive(self, kind: Kind) -> Attacker:
        cache = self.__dict__.setdefault("_deceptive_cache", {})
        if kind not in cache:
            tag = "am" if kind == "ambiguity" else "ex"
            paths = []
            for theta in (1, 2):
                try:
                    dp = deceptive_path(self.observer, theta, kind)
                except ValueError as exc:
                    raise InvalidInstanceError(str(exc)) from None
                paths.append(StrategyWalk.along(self.instance.network, dp.walk, Fraction(1),
                                                f"xi{theta}_{tag}"))
            cache[kind] = Attacker(kind, (paths[0],), (paths[1],))
        result: Attacker = cache[kind]
        return result

    # ------------------------------------------------------------------ evaluation
    def evaluate(self, defender: str | Schedule, attacker: str | Attacker) -> Evaluation:
        """The exact :class:`~solver.twogoal.evaluation.Evaluation` of a pair (with
        trajectories)."""
        schedule: Callable[..., list[Number]] = (
            self.defender(defender) if isinstance(defender, str) else defender)
        att = self.attacker(attacker) if isinstance(attacker, str) else attacker
        inst = self.instance
        return evaluate(inst.network, schedule, att.primary, att.secondary,
                        prior=(inst.b1, inst.b2), goals=(self.g1, self.g2),
                        d_to=(self.d_to_g1, self.d_to_g2), d_from_start=self.d_from_start)

    def pair(self, defender: str, attacker: str) -> PairResult:
        """U¹, U², U, Ū, VoI of a named pair."""
        ev = self.evaluate(defender, attacker)
        return PairResult(defender, attacker, ev.U1, ev.U2, ev.U, ev.U_bar, ev.VoI)

    def compare(self, pairs: tuple[tuple[str, str], ...] = PAIRS) -> tuple[PairResult, ...]:
        """:meth:`pair` for each of ``pairs`` (default: the six of :data:`PAIRS`)."""
        return tuple(self.pair(d, a) for d, a in pairs)
