"""Transitional: the N-goal profile reader is :mod:`dppverify.game.profile`."""

from __future__ import annotations

from dppverify.game.profile import (
    NGOAL_PROFILE_FORMAT,
    NProfile,
    load_nprofile_document,
    nprofile_from_json,
)

__all__ = ["NGOAL_PROFILE_FORMAT", "NProfile", "load_nprofile_document", "nprofile_from_json"]
