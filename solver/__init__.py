"""solver: the constructive Perfect Bayesian Nash equilibrium of the DPP game.

>>> import networkx as nx
>>> from solver import Instance, solve
>>> g = nx.Graph()
>>> g.add_weighted_edges_from([("s", "g2", 2), ("g2", "g1", 2), ("s", "g1", 3)])
>>> str(solve(Instance(g, "s", ("g1", "g2"), ("7/10", "3/10"))).U)
'12/5'
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from solver.version import __version__

_LAZY = {"Equilibrium": "solver.twogoal.equilibrium", "solve": "solver.twogoal.equilibrium",
         "DPPError": "solver.errors", "InstanceFormatError": "solver.errors",
         "InvalidInstanceError": "solver.errors", "Instance": "solver.game.instance",
         "instance_from_json": "solver.game.instance_reading",
         "instance_to_json": "solver.game.instance_writing",
         "load_instance": "solver.game.instance_reading",
         "equilibrium_to_json": "solver.twogoal.profile_json",
         "summarize": "solver.twogoal.report", "StrategyPath": "solver.game.walks"}
"""The public names, each imported on first use (``import solver`` stays cheap)."""

if TYPE_CHECKING:
    from solver.errors import DPPError, InstanceFormatError, InvalidInstanceError
    from solver.game.instance import Instance
    from solver.game.instance_reading import instance_from_json, load_instance
    from solver.game.instance_writing import instance_to_json
    from solver.game.walks import StrategyPath
    from solver.twogoal.equilibrium import Equilibrium, solve
    from solver.twogoal.profile_json import equilibrium_to_json
    from solver.twogoal.report import summarize

__all__ = ["DPPError", "Equilibrium", "Instance", "InstanceFormatError",
           "InvalidInstanceError", "StrategyPath", "__version__", "equilibrium_to_json",
           "instance_from_json", "instance_to_json", "load_instance", "solve", "summarize"]


def __getattr__(name: str) -> Any:
    """Import a public name from its module on first use."""
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    import importlib

    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value
