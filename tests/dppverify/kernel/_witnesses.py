"""Helpers of the kernel's tests: documents as bytes, the engine's witness, the kernel's verdict."""

from __future__ import annotations

import json
from typing import Any

from dppverify.game.instance import instance_from_json
from dppverify.game.profile import profile_from_json
from dppverify.kernel import Verdict, check
from dppverify.kernel.reading import sha256
from dppverify.structured.witness import witness_document

__all__ = ["as_bytes", "engine_witness", "kernel_verdict"]


def as_bytes(doc: Any) -> bytes:
    """A document's bytes (documents are hashed as written)."""
    return doc if isinstance(doc, bytes) else json.dumps(doc).encode()


def engine_witness(instance: Any, profile: Any) -> dict[str, Any]:
    """``dppverify.structured.witness`` for the two documents (bytes or JSON values)."""
    ib, pb = as_bytes(instance), as_bytes(profile)
    inst = instance_from_json(json.loads(ib))
    prof = profile_from_json(json.loads(pb), inst)
    assert prof.wellformed, prof.defects
    return witness_document(inst, prof, instance_sha256=sha256(ib), profile_sha256=sha256(pb))


def kernel_verdict(instance: Any, profile: Any, witness: Any | None = None) -> Verdict:
    """The kernel's verdict, on the engine's witness unless one is given."""
    w = engine_witness(instance, profile) if witness is None else witness
    return check(as_bytes(instance), as_bytes(profile), as_bytes(w))
