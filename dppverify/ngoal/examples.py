"""Transitional: the bundled N-goal games are in :mod:`dppverify.game.examples`."""

from __future__ import annotations

from dppverify.game.examples import hub4, hub4_document, star3, star3_document, star3_profile

__all__ = ["hub4", "hub4_document", "star3", "star3_document", "star3_profile"]
