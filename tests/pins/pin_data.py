"""Write the pin cases' input files into ``tests/pins/data/`` (run ONCE, before the refactor).

This module imports the bundled examples (``dppverify.game.examples``, ``dppverify.game.examples``)
and the conformance files; those module paths moved in the refactor the pins guard, so neither
the pin test nor the default mode of ``make_pins.py`` imports it: the files it writes are
committed, and ``python tests/pins/make_pins.py --data`` regenerates them only on a commit that
still has the old layout.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
DATA = HERE / "data"
REPO = HERE.parent.parent

# Conformance cases (tests/data/conformance_cases.json) by their (unique) names: small, with
# all three phases, directed and rational weights, a tie, s0 a goal.
CONFORMANCE = {"conf_phases_I_II_III": "phases=I+II+III",
               "conf_directed_rational": "directed-rational#37",
               "conf_s0_is_g1": "s0_is_g1", "conf_xi2_tie": "xi2_tie",
               "conf_grid_weighted": "grid-weighted#21"}


def _write(name: str, doc: Any) -> None:
    (DATA / name).write_text(json.dumps(doc, indent=1, ensure_ascii=False) + "\n",
                             encoding="utf-8")


def write_data() -> list[str]:
    """Write every input file; return their names."""
    from dppverify.game import examples as ex2
    exn = ex2  # the N-goal examples live beside the two-goal ones (since that refactor)

    DATA.mkdir(parents=True, exist_ok=True)
    _write("triangle.json", ex2.triangle_document())
    _write("triangle_profile.json", ex2.triangle_profile(value={"U": "12/5"}))
    _write("triangle_bad_profile.json",
           ex2.triangle_profile(ex2.triangle_attacker("3/7", "4/7")))
    # the triangle's equilibrium in the N-goal format: the table Defender of σ* along the
    # profile's walks ([1/2, 1/2] on "s g2" is σ*(g1) = 1/2 there; "s g1" allocates to g1)
    _write("triangle_ngoal_profile.json",
           {"format": "dpp-ngoal-profile/1", "goals": ["g1", "g2"],
            "attacker": [[{"path": ["s", "g1"], "probability": "4/7"},
                          {"path": ["s", "g2"], "probability": "3/7"}],
                         [{"path": ["s", "g2"], "probability": 1}]],
            "defender": {"rule": "guarantee", "h": ["3", "1"]},
            "value": {"U": "12/5"}})
    _write("kite.json", ex2.kite_document())
    _write("kite_naive_profile.json", ex2.kite_naive_profile())
    _write("star3.json", exn.star3_document())
    _write("star3_profile.json", exn.star3_profile())
    _write("star3_equal_prior.json", exn.star3_document(("1/3", "1/3", "1/3")))
    _write("hub4.json", exn.hub4_document())
    _write("hub4_undirected.json", exn.hub4_document(directed=False))
    # another instance: the triangle at another prior (a solver profile records its prior)
    _write("triangle_other_prior.json", ex2.triangle_document(("1/2", "1/2")))
    (DATA / "malformed.json").write_text('{"graph": {"nodes": [}', encoding="utf-8")
    _write("not_an_instance.json", {"format": "dpp-profile/1", "start": 3})
    cases = json.loads((REPO / "tests/data/conformance_cases.json").read_text("utf-8"))
    by_name = {c["name"]: c for c in cases}
    for name, case in CONFORMANCE.items():
        _write(f"{name}.json", by_name[case]["instance"])
    return sorted(p.name for p in DATA.iterdir())
