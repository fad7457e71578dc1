"""Hypothesis strategies for DPP game instances, as JSON documents (``docs/formats.md`` §1).

Public strategies, in hypothesis' house style: plural names, keyword-only arguments, values
valid by construction (no filtering), :class:`hypothesis.errors.InvalidArgument` for
impossible arguments, and shrinking towards few nodes, few edges, unit weights and the
prior 1/2.

- :func:`weighted_graphs`: networkx node-link ``graph`` objects (directed or undirected;
  integer, fractional or float weights; strongly connected by default);
- :func:`priors`: ``[p, 1 - p]`` pairs of exact ``"p/q"`` strings, including exactly 1/2;
- :func:`instances`: instance documents on any graph strategy; the goals and the start are
  chosen so that ``d(s0,g1)``, ``d(s0,g2)``, ``d(g1,g2)`` and ``d(g2,g1)`` are finite;
- :func:`grid_worlds`: 4-connected grid instances with obstacles (the paper's Sec. VII), by
  default with each goal reachable from the start without passing the other goal;
- :func:`goal_priors` and :func:`many_goal_instances`: N-entry priors and N-goal instances
  (``N >= 2`` goals, exact weights) for the checker's N-goal routes.

They produce plain dicts (the checker never imports the solver), ready for
``json.dumps``, :func:`dppverify.certify` or any solver reading the instance format.

Examples
--------
>>> from hypothesis import find, settings
>>> doc = find(instances(), lambda d: True, settings=settings(database=None))
>>> doc["graph"]["nodes"], doc["start"], doc["goals"], doc["prior"]
([{'id': 0}, {'id': 1}], 0, [0, 1], ['1/2', '1/2'])
"""

from dppverify.strategies.graphs import WEIGHT_KINDS, weighted_graphs
from dppverify.strategies.grids import grid_worlds
from dppverify.strategies.instances import goal_priors, instances, many_goal_instances, priors

__all__ = ["WEIGHT_KINDS", "goal_priors", "grid_worlds", "instances", "many_goal_instances",
           "priors", "weighted_graphs"]
