"""The solver's front door: one :func:`solve` for any number of goals, one result type.

``solve(instance)`` takes an :class:`~solver.game.instance.Instance`, an instance document
(a dict, ``docs/formats.md`` §1) or the path of an instance file, for ``2 <= N <= 5`` goals,
and returns a frozen :class:`Solution`. Two goals are solved by the paper's construction
(σ*, :func:`~solver.twogoal.equilibrium.paper_equilibrium`, proved an equilibrium on every
instance: proofs/THM.md), reachable as :attr:`Solution.twogoal`; more goals by the coalition
construction (:func:`~solver.coalitions.construction.coalition_equilibrium`,
proofs/NSOLVE.md), reachable as :attr:`Solution.coalitions`, which is an equilibrium wherever
its arc condition holds: ``dpp solve`` certifies it with the independent checker before
writing it.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from solver.coalitions.construction import CoalitionEquilibrium, coalition_equilibrium
from solver.game.instance import Instance
from solver.game.instance_reading import as_instance
from solver.game.walks import StrategyWalk
from solver.numbers import DEFAULT_ABS_TOL, Number, format_value

if TYPE_CHECKING:
    import networkx as nx
from solver.twogoal.equilibrium import Equilibrium, paper_equilibrium
from solver.twogoal.report import summarize as summarize_two_goals


@dataclass(frozen=True, eq=False)
class Solution:
    """The solver's result for any number of goals: a strategy profile and its exact values.

    Attributes
    ----------
    instance : Instance
        The solved game.
    strategies : tuple
        ``strategies[θ]``: the mixed strategy of goal index θ (:class:`StrategyWalk` s, each
        with its probability).
    costs : tuple
        ``costs[θ]``: type θ's expected cost ``U^θ`` against the Defender.
    U, U_bar, VoI : Number
        The value ``Σ_θ b_θ U^θ``, the complete-information value ``Σ_θ b_θ d(s0, g^θ)`` and
        ``VoI = (Ū − U)/Ū`` (exact ``Fraction`` on rational instances).
    twogoal : Equilibrium or None
        For two goals: the paper's equilibrium (σ*, ξ², the phases, the primary's mixture).
    coalitions : CoalitionEquilibrium or None
        For three goals or more: the coalition construction (the guarantee rule's ``h``, the
        cover, the coalition DP's value).

    Examples
    --------
    >>> from solver.game.instance import triangle
    >>> sol = solve(triangle())
    >>> str(sol.U), [len(mix) for mix in sol.strategies], sol.twogoal.phases.T
    ('12/5', [2, 1], 1)
    """

    instance: Instance = field(repr=False)
    strategies: tuple[tuple[StrategyWalk, ...], ...] = field(repr=False)
    costs: tuple[Number, ...]
    U: Number
    U_bar: Number
    VoI: Number
    twogoal: Equilibrium | None = field(default=None, repr=False)
    coalitions: CoalitionEquilibrium | None = field(default=None, repr=False)

    @property
    def n_goals(self) -> int:
        """``N``, the number of goals."""
        return self.instance.n_goals

    @property
    def proved(self) -> bool:
        """True when the construction is proved an equilibrium on every instance (σ*, two
        goals: proofs/THM.md); the coalition construction is certified instance by instance."""
        return self.twogoal is not None

    def to_json(self) -> dict[str, Any]:
        """The profile document: ``dpp-profile/1`` for two goals (the paper's labelling),
        ``dpp-ngoal-profile/1`` with the guarantee rule for more (``docs/formats.md`` §2,
        §2b); the protocol through which ``dppverify.certify(instance, solution)`` takes it.

        Examples
        --------
        >>> from dppverify import certify
        >>> from solver.game.instance import triangle
        >>> sol = solve(triangle())
        >>> sol.to_json()["format"], certify(sol.instance.to_json(), sol.to_json()).verdict
        ('dpp-profile/1', 'pass')
        """
        if self.twogoal is not None:
            return self.twogoal.to_json()
        assert self.coalitions is not None
        return self.coalitions.to_json()


def solve(instance: Instance | Mapping[str, Any] | str | Path | nx.Graph, *,
          start: Any = None, goals: Any = None, prior: Any = None, weight: str = "weight",
          abs_tol: float = DEFAULT_ABS_TOL) -> Solution:
    """Solve a game with any number of goals (2 to 5).

    Parameters
    ----------
    instance : Instance, dict, str, Path or networkx.Graph
        The game: an :class:`Instance`, an instance document (``docs/formats.md`` §1, or a
        compact ``dpp-map-instance/1``), the path of an instance file, or a ``networkx``
        graph (``Graph`` or ``DiGraph``), converted once at the door
        (:func:`~solver.game.instance_reading.as_instance`).
    start, goals, prior
        With a graph only: the start node, the goal nodes and their prior (numbers,
        ``Fraction`` or ``"p/q"`` strings).
    weight : str
        With a graph: the edge attribute holding the weights (1 where absent).
    abs_tol : float
        Two goals with float weights only: the tolerance on distances, relative to the largest
        weight (:func:`~solver.twogoal.equilibrium.paper_equilibrium`).

    Returns
    -------
    Solution
        For two goals the paper's equilibrium (:attr:`Solution.twogoal`), for more the
        coalition construction (:attr:`Solution.coalitions`).

    Raises
    ------
    InvalidInstanceError, InstanceFormatError
        One line naming what is wrong with the instance.

    Examples
    --------
    >>> doc = {"graph": {"nodes": [{"id": x} for x in "smabc"],
    ...        "edges": [{"source": "s", "target": "m"}, {"source": "m", "target": "a"},
    ...                  {"source": "m", "target": "b"}, {"source": "m", "target": "c"},
    ...                  {"source": "s", "target": "a", "weight": 2}]},
    ...        "start": "s", "goals": ["a", "b", "c"], "prior": ["1/2", "1/3", "1/6"]}
    >>> sol = solve(doc)
    >>> str(sol.U), sol.to_json()["defender"]["rule"], sol.proved
    ('3/2', 'guarantee', False)
    >>> doc = {**doc, "goals": ["a", "b"], "prior": ["7/10", "3/10"]}
    >>> str(solve(doc).U), solve(doc).to_json()["format"]
    ('17/10', 'dpp-profile/1')
    >>> import networkx as nx
    >>> g = nx.Graph([("s", "g2", {"w": 2}), ("g2", "g1", {"w": 2}), ("s", "g1", {"w": 3})])
    >>> str(solve(g, start="s", goals=["g1", "g2"], prior=["7/10", "3/10"], weight="w").U)
    '12/5'
    """
    inst = as_instance(instance, start=start, goals=goals, prior=prior, weight=weight)
    if inst.n_goals == 2:
        eq = paper_equilibrium(inst, abs_tol=abs_tol)
        p = inst.primary_goal_index
        by_role = {p: (eq.primary_paths, eq.U1), 1 - p: ((eq.secondary,), eq.U2)}
        return Solution(inst, (by_role[0][0], by_role[1][0]), (by_role[0][1], by_role[1][1]),
                        eq.U, eq.U_bar, eq.VoI, twogoal=eq)
    ceq = coalition_equilibrium(inst)
    return Solution(inst, ceq.strategies, ceq.costs, ceq.U, ceq.U_bar, ceq.VoI, coalitions=ceq)


def summarize(result: Solution | Equilibrium, *, certified: str = "") -> str:
    """What ``dpp solve`` prints for a result: for two goals the paper's equilibrium (goals, ξ²
    with σ* per step and its phases, the primary's mixture, the values: several lines); for
    more, one line (value, VoI, type costs, the guarantee rule's ``h``; ``certified`` says how
    it was certified).

    Parameters
    ----------
    result : Solution or Equilibrium
        What :func:`solve` returned.
    certified : str
        How an N-goal result was certified, for its line.

    Returns
    -------
    str
        The text, without a final newline.

    Examples
    --------
    >>> from solver.game.instance import triangle
    >>> print(summarize(solve(triangle())).splitlines()[-3])
    U* (value)          = 12/5 (≈ 2.4)
    >>> import networkx as nx
    >>> star = nx.Graph([("s", "a"), ("s", "b"), ("s", "c", {"weight": 2})])
    >>> print(summarize(solve(Instance(star, "s", ("a", "b", "c"), ("1/2", "1/3", "1/6")))))
    N = 3 goals: U = 7/6 (≈ 1.167), VoI = 0, Ū = 7/6 (≈ 1.167); type costs (1, 1, 2); \
Defender: guarantee rule h = (1, 1, 2)
    """
    if isinstance(result, Equilibrium):
        return summarize_two_goals(result)
    if result.twogoal is not None:
        return summarize_two_goals(result.twogoal)
    ceq = result.coalitions
    assert ceq is not None
    note = f" ({certified})" if certified else ""
    return (f"N = {result.n_goals} goals: U = {format_value(ceq.U)}{note}, VoI = "
            f"{format_value(ceq.VoI)}, Ū = {format_value(ceq.U_bar)}; type costs "
            f"({', '.join(map(str, ceq.costs))}); Defender: guarantee rule h = "
            f"({', '.join(map(str, ceq.h))})"
            + (f" with {len(ceq.normals)} extra normals" if ceq.normals else ""))
