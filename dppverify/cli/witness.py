"""``dpp certify``'s witness: the engine's ``dpp-witness/1`` (``docs/formats.md`` §5) for
``--witness W``, and the trusted kernel's verdict on it ("One verdict", ``docs/checker.md``):
``dpp certify`` says PASS only when the kernel accepts the engine's witness."""

from __future__ import annotations

import json
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from dppverify.cli.conventions import status
from dppverify.formats.files import write_files
from dppverify.game.instance import Instance
from dppverify.game.profile import profile_from_json
from dppverify.kernel import check
from dppverify.structured.witness import witness_document

__all__ = ["engine_witness", "kernel_record", "write_witness"]


def engine_witness(game: Instance, doc: Mapping[str, Any], provenance: Mapping[str, Any]
                   ) -> dict[str, Any] | str:
    """The engine's witness of ``doc`` on ``game``, tied to the hashes of ``provenance`` (the
    bytes certified); or why there is none (a profile that is not well formed, a float-mode
    game).

    Examples
    --------
    >>> from dppverify.game.examples import triangle, triangle_profile
    >>> prov = {"instance": {"sha256": "0" * 64}, "profile": {"sha256": "1" * 64}}
    >>> engine_witness(triangle(), triangle_profile(), prov)["denominator"]
    1
    """
    if not game.exact:
        return "the trusted kernel decides exact games only (this one is in float mode)"
    profile = profile_from_json(dict(doc), game)
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


def kernel_record(witness: dict[str, Any] | str, instance: bytes | None, profile: bytes | None,
                  base_dir: Path | None, horizon: int | None) -> dict[str, Any]:
    """The trusted kernel's verdict on the engine's witness, for the certificate's
    ``info.kernel``: ``{"status": pass | refuted | undecided | bad-input | not applicable,
    "message": …}``. Not applicable: a finite horizon (the kernel decides the untruncated
    game), no witness (and why), or inputs without bytes (objects given in Python).

    Examples
    --------
    >>> kernel_record("the profile is not well formed", b"", b"", None, None)["status"]
    'not applicable'
    """
    if horizon is not None:
        why = f"the game truncated at H = {horizon}; the kernel decides the untruncated game"
    elif isinstance(witness, str):
        why = witness
    elif instance is None or profile is None:
        why = "the inputs have no bytes to tie a witness to"
    else:
        v = check(instance, profile, witness, base_dir=base_dir)  # the document, not re-read
        return {"status": v.status, "message": v.message}
    return {"status": "not applicable", "message": why}
