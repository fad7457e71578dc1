"""Transitional: the N-goal instance is :class:`dppverify.game.instance.Instance` (any N)."""

from __future__ import annotations

from dppverify.game.instance import (
    NInstance,
    goal_count,
    load_ninstance,
    ninstance_from_json,
    read_instance_document,
)

__all__ = ["NInstance", "goal_count", "load_ninstance", "ninstance_from_json",
           "read_instance_document"]
