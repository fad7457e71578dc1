"""``--witness W`` of ``dpp certify``: the engine's ``dpp-witness/1`` written beside the
certificate (``docs/formats.md`` §5), for ``dpp check`` and the trusted kernel."""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

from dppverify.cli.conventions import status
from dppverify.formats.files import write_files
from dppverify.game.instance import Instance
from dppverify.game.profile import profile_from_json
from dppverify.structured.witness import witness_document

__all__ = ["write_witness"]


def write_witness(path: str, game: Instance, doc: Mapping[str, Any],
                  provenance: Mapping[str, Any]) -> bool:
    """Write the witness of ``doc`` on ``game`` to ``path`` (atomically), tied to the hashes of
    ``provenance`` (the bytes certified); True when written. A profile that is not well formed
    has none: one ``note:`` line, nothing written.

    Examples
    --------
    >>> from dppverify.game.examples import triangle, triangle_profile
    >>> import tempfile, os
    >>> with tempfile.TemporaryDirectory() as d:
    ...     w = os.path.join(d, "w.json")
    ...     prov = {"instance": {"sha256": "0" * 64}, "profile": {"sha256": "1" * 64}}
    ...     write_witness(w, triangle(), triangle_profile(), prov), os.path.exists(w)
    (True, True)
    """
    profile = profile_from_json(dict(doc), game)
    if not profile.wellformed:
        status(f"note: no witness written to {path}: the profile is not well formed")
        return False
    try:
        wit = witness_document(game, profile,
                               instance_sha256=str(provenance["instance"]["sha256"]),
                               profile_sha256=str(provenance["profile"]["sha256"]))
    except ValueError as exc:
        status(f"note: no witness written to {path}: {exc}")
        return False
    write_files({path: json.dumps(wit, separators=(",", ":")) + "\n"})
    status(f"wrote {path}: the witness (dpp check verifies it with the trusted kernel)")
    return True
