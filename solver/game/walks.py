"""One walk of a type's mixed strategy, kept both as node indices and as node ids.

Naming, the same across the solver and the checker: a *walk* is the sequence of nodes an
Attacker type takes (the paper's path ξ; the JSON formats keep the key ``"path"``); *path*
is kept for shortest paths (:mod:`solver.graph.shortest_paths`) and for the paper's names of the
equilibrium's walks (``secondary_path`` ξ², ``primary_paths`` ξ^{1,α}, public attributes of
:class:`~solver.twogoal.equilibrium.Equilibrium`). In code, ``walk`` holds node *indices* of
the :class:`~solver.graph.network.Network` (what the algorithms work on), ``nodes`` the same
sequence as node *ids* (what users and the JSON formats see). A walk with its probability in a
mixed strategy is a :class:`StrategyWalk`, as in the checker.
"""

from __future__ import annotations

from collections.abc import Hashable, Sequence
from dataclasses import dataclass
from fractions import Fraction

from solver.graph.network import Network


@dataclass(frozen=True)
class StrategyWalk:
    """A walk of a type's mixed strategy (Γ_mix), its probability and its label.

    Attributes
    ----------
    walk : tuple of int
        Node indices ``s_0 .. s_T``.
    nodes : tuple
        The same walk as node ids.
    probability : Fraction
        Probability that the type takes this walk.
    label : str
        Its name (``xi2``, ``xi1_I``, ``xi1_II``, ``xi1``, ``xi1_am``, ...), or ``""``.

    Examples
    --------
    >>> import networkx as nx
    >>> net = Network.from_networkx(nx.Graph([("s", "a"), ("a", "g")]))
    >>> p = StrategyWalk.along(net, [0, 1, 2], Fraction(1), "xi2")
    >>> p.walk, p.nodes
    ((0, 1, 2), ('s', 'a', 'g'))
    """

    walk: tuple[int, ...]
    nodes: tuple[Hashable, ...]
    probability: Fraction
    label: str = ""

    @classmethod
    def along(cls, net: Network, walk: Sequence[int], probability: Fraction,
              label: str = "") -> StrategyWalk:
        """The walk of node indices ``walk`` of ``net``, its node ids looked up."""
        return cls(tuple(int(i) for i in walk), net.labels_of(walk), probability, label)
