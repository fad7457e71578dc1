"""The record of a check that cannot run because the profile is not well-formed."""

from __future__ import annotations

from collections.abc import Mapping

from dppverify.certificate import CheckRecord
from dppverify.exact import Number

NOT_WELLFORMED = "not evaluated: the profile is not well-formed (see profile.wellformed)"


def skipped(check_id: str, proof: str | None = None,
            numbers: Mapping[str, Number | None] | None = None) -> CheckRecord:
    """A ``skipped`` record of ``check_id`` saying the profile is not well-formed.

    Examples
    --------
    >>> r = skipped("pbne.defender_br", "L3")
    >>> r.status, r.message == NOT_WELLFORMED
    ('skipped', True)
    """
    return CheckRecord(check_id, "skipped", NOT_WELLFORMED, numbers or {}, proof)
