"""dppverify: an independent checker for deceptive-path-planning (DPP) game profiles.

It never imports ``solver``: it reads instances and strategy profiles as JSON
(``docs/formats.md``) and certifies them against the paper's game.

>>> from dppverify import certify
>>> doc = {"graph": {"nodes": [{"id": "s"}, {"id": "g1"}, {"id": "g2"}],
...        "edges": [{"source": "s", "target": "g2", "weight": 2},
...                  {"source": "g2", "target": "g1", "weight": 2},
...                  {"source": "s", "target": "g1", "weight": 3}]},
...        "start": "s", "goals": ["g1", "g2"], "prior": ["7/10", "3/10"]}
>>> profile = {"format": "dpp-profile/1", "goals": {"primary": "g1", "secondary": "g2"},
...     "defender": {"rule": "progress", "goal": "g1"},
...     "attacker": {"primary": [{"path": ["s", "g1"], "probability": "4/7"},
...                              {"path": ["s", "g2"], "probability": "3/7"}],
...                  "secondary": [{"path": ["s", "g2"], "probability": "1"}]}}
>>> certify(doc, profile).verdict
'pass'
"""

from __future__ import annotations

import sys
import types
from typing import TYPE_CHECKING, Any

from dppverify.version import __version__

if TYPE_CHECKING:
    from dppverify.certificate import Certificate, CheckRecord
    from dppverify.certify import certify
    from dppverify.errors import (
        CertificateError,
        CheckerError,
        HorizonError,
        InvalidInstanceError,
        LPError,
        ProfileError,
        TreeTooLargeError,
        UndecidedError,
    )
    from dppverify.game.instance import Instance, instance_from_json, load_instance
    from dppverify.registry import CHECK_IDS
    from dppverify.tree_route.tree import WalkTree, build_tree, count_prefixes
    from dppverify.tree_route.value_lp import GameValue, game_value
    from dppverify.valuation import value

__all__ = ["CHECK_IDS", "Certificate", "CertificateError", "CheckRecord", "CheckerError",
           "GameValue", "HorizonError", "Instance", "InvalidInstanceError", "LPError",
           "ProfileError", "TreeTooLargeError", "UndecidedError", "WalkTree", "__version__",
           "build_tree", "certify", "count_prefixes", "game_value", "instance_from_json",
           "load_instance", "value"]

_LAZY = {"certify": "dppverify.certify", "value": "dppverify.valuation",
         "Certificate": "dppverify.certificate", "CheckRecord": "dppverify.certificate",
         "CertificateError": "dppverify.errors", "CheckerError": "dppverify.errors",
         "HorizonError": "dppverify.errors", "InvalidInstanceError": "dppverify.errors",
         "LPError": "dppverify.errors", "ProfileError": "dppverify.errors",
         "TreeTooLargeError": "dppverify.errors", "UndecidedError": "dppverify.errors",
         "Instance": "dppverify.game.instance", "instance_from_json": "dppverify.game.instance",
         "load_instance": "dppverify.game.instance", "CHECK_IDS": "dppverify.registry",
         "WalkTree": "dppverify.tree_route.tree", "build_tree": "dppverify.tree_route.tree",
         "count_prefixes": "dppverify.tree_route.tree",
         "GameValue": "dppverify.tree_route.value_lp",
         "game_value": "dppverify.tree_route.value_lp"}
"""The public names, each imported on first use (``import dppverify`` and every ``dpp``
command's start-up stay cheap: a command that refuses its input never loads the checks)."""


def __getattr__(name: str) -> Any:
    """Import a public name from its module on first use."""
    import importlib

    home = _LAZY.get(name)
    if home is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(home), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_LAZY})


class _Package(types.ModuleType):
    """The package's module type: ``dppverify.certify`` stays the function when its module
    of the same name is imported (the import system sets the submodule as the package's
    attribute; the eager ``from dppverify.certify import certify`` used to set it back)."""

    def __setattr__(self, name: str, value: Any) -> None:
        if name == "certify" and isinstance(value, types.ModuleType):
            value = value.certify
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Package
