"""Shared fixtures for the solver tests."""

from __future__ import annotations

import networkx as nx
import pytest

from solver import Instance


@pytest.fixture
def triangle() -> Instance:
    """proofs/ERRATA.md E1's smallest instance: s–g2 (2), g2–g1 (2), s–g1 (3), b = (7/10, 3/10)."""
    g = nx.Graph()
    g.add_weighted_edges_from([("s", "g2", 2), ("g2", "g1", 2), ("s", "g1", 3)])
    return Instance(g, "s", ("g1", "g2"), ("7/10", "3/10"))
