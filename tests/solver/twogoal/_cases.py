"""Access to the conformance cases (copied from shared/conformance/cases.json)."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

DATA = Path(__file__).resolve().parents[2] / "data"


def load_cases() -> list[dict[str, Any]]:
    """The conformance cases: instances with independently computed exact U*, VoI*, d1, V_H."""
    return json.loads((DATA / "conformance_cases.json").read_text())  # type: ignore[no-any-return]
