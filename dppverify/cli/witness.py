"""``dpp certify --witness W``: the engine's ``dpp-witness/1`` (``docs/formats.md`` §5), for
``dpp check`` and the trusted kernel (``dppverify.certify`` itself runs the kernel on it: its
certificate's ``info.kernel``)."""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

from dppio.cli.conventions import status
from dppverify.formats.files import write_files
from dppverify.game.instance import Instance
from dppverify.game.profile import Profile
from dppverify.structured.witness import witness_document


def engine_witness(game: Instance, profile: Profile, provenance: Mapping[str, Any]
                   ) -> dict[str, Any] | str:
    """The engine's witness of ``profile`` on ``game``, tied to the hashes of ``provenance``
    (the bytes certified); or why there is none (a profile that is not well formed, a
    float-mode game).

    Examples
    --------
    >>> from dppverify.game.examples import triangle, triangle_profile
    >>> from dppverify.game.profile import profile_from_json
    >>> prov = {"instance": {"sha256": "0" * 64}, "profile": {"sha256": "1" * 64}}
    >>> engine_witness(triangle(), profile_from_json(triangle_profile(), triangle()),
    ...                prov)["denominator"]
    1
    """
    if not game.exact:
        return "the trusted kernel decides exact games only (this one is in float mode)"
    if not profile.wellformed:
        return "the profile is not well formed"
    try:
        return witness_document(game, profile,
                                instance_sha256=str(provenance["instance"]["sha256"]),
                                profile_sha256=str(provenance["profile"]["sha256"]))
    except ValueError as exc:
        return str(exc)


def write_witness(path: str, witness: dict[str, Any] | str) -> bool:
    """Write ``witness`` to ``path`` (atomically); a reason instead of a witness is one
    ``note:`` line and nothing written. True when written.

    Examples
    --------
    >>> write_witness("w.json", "the profile is not well formed")
    False
    """
    if isinstance(witness, str):
        status(f"note: no witness written to {path}: {witness}")
        return False
    write_files({path: json.dumps(witness, separators=(",", ":")) + "\n"})
    status(f"wrote {path}: the witness (dpp check verifies it with the trusted kernel)")
    return True
