"""The pinned CLI invocations: ``dpp`` (``dpp:main``) and ``python -m dppverify``.

Each case is one or more commands run in order in one fresh directory holding
``tests/pins/data/*`` and ``examples/`` (``runner.py``); its record (exit codes, stdout,
stderr, files written) is ``expected/<name>.txt``. A step's first word is the program: ``dpp``
(in this process, click's ``CliRunner``), ``dpp!`` (a subprocess: the certificate records the
real command line) or ``python -m dppverify`` (a subprocess).

The data (``pin_data.py``): the bundled two-goal examples (triangle, kite) and N-goal examples
(star3, hub4 directed and undirected: the instances of ``tests/data/ngoal_cases.json``), their
profiles in ``dpp-profile/1`` and ``dpp-ngoal-profile/1``, a profile that fails, a profile for
another instance, malformed files, and five instances of ``tests/data/conformance_cases.json``
(``conf_*.json``).
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["CASES", "Case"]


@dataclass(frozen=True)
class Case:
    """One pinned run: ``name`` (the expected file's stem) and its commands, in order."""

    name: str
    steps: tuple[tuple[str, ...], ...]


def _one(name: str, *argv: str) -> Case:
    """A case of one ``dpp`` command run in-process."""
    return Case(name, (("dpp", *argv),))


_PAPER10 = ("--map", "examples/paper10.map", "--start", "9,0", "--goals", "0,9", "0,0",
            "--prior", "0.6,0.4")
_PAPER10_N3 = ("--map", "examples/paper10.map", "--start", "9,0", "--goals", "0,9", "0,0",
               "9,9", "--prior", "1/2,1/3,1/6")
_TRI = ("triangle.json", "triangle_profile.json")
_STAR = ("star3.json", "star3_profile.json")

CASES: tuple[Case, ...] = (
    # --- dpp certify, two goals
    _one("certify_triangle", "certify", *_TRI),
    _one("certify_triangle_json", "certify", *_TRI, "--json"),
    Case("certify_triangle_json_process", (("dpp!", "certify", *_TRI, "--json"),)),
    _one("certify_triangle_h1", "certify", *_TRI, "--horizon", "1"),
    _one("certify_triangle_h2_tree", "certify", *_TRI, "--horizon", "2", "--route", "tree"),
    _one("certify_triangle_h2_json", "certify", *_TRI, "-H", "2", "--json"),
    _one("certify_triangle_h3_structured", "certify", *_TRI, "-H", "3", "--route",
         "structured"),
    _one("certify_triangle_h3_both", "certify", *_TRI, "-H", "3", "--route", "both"),
    _one("certify_triangle_hinf_auto", "certify", *_TRI, "-H", "inf", "--route", "auto"),
    _one("certify_triangle_tree_without_horizon", "certify", *_TRI, "--route", "tree"),
    _one("certify_triangle_output", "certify", *_TRI, "-o", "cert.json"),
    Case("certify_verify_provenance", (
        ("dpp", "certify", *_TRI, "-o", "cert.json"),
        ("dpp", "certify", "--verify-provenance", "cert.json", *_TRI),
        ("dpp", "certify", "--verify-provenance", "cert.json", "kite.json",
         "triangle_profile.json"))),
    _one("certify_triangle_bad", "certify", "triangle.json", "triangle_bad_profile.json"),
    _one("certify_triangle_bad_h2_both", "certify", "triangle.json",
         "triangle_bad_profile.json", "-H", "2", "--route", "both", "--json"),
    _one("certify_kite_naive", "certify", "kite.json", "kite_naive_profile.json"),
    _one("certify_kite_naive_h1", "certify", "kite.json", "kite_naive_profile.json", "-H", "1"),
    _one("certify_kite_naive_h1_structured", "certify", "kite.json", "kite_naive_profile.json",
         "-H", "1", "--route", "structured"),
    _one("certify_kite_naive_h1_both", "certify", "kite.json", "kite_naive_profile.json",
         "-H", "1", "--route", "both"),
    _one("certify_claim_for_other_prior", "certify", "triangle_other_prior.json",
         "triangle_profile.json"),
    Case("certify_solved_for_other_instance", (
        ("dpp", "solve", "triangle.json", "-o", "p.json"),
        ("dpp", "certify", "triangle_other_prior.json", "p.json"),
        ("dpp", "certify", "kite.json", "p.json"))),
    _one("certify_ngoal_profile_for_two_goals", "certify", "triangle.json",
         "triangle_ngoal_profile.json"),
    _one("certify_malformed_profile", "certify", "triangle.json", "malformed.json"),
    _one("certify_malformed_instance", "certify", "malformed.json", "triangle_profile.json"),
    _one("certify_profile_as_instance", "certify", "not_an_instance.json",
         "triangle_profile.json"),
    _one("certify_swapped", "certify", "triangle_profile.json", "triangle.json"),
    _one("certify_missing_file", "certify", "missing.json", "triangle_profile.json"),
    Case("certify_conformance_phases", (
        ("dpp", "solve", "conf_phases_I_II_III.json", "-o", "p.json"),
        ("dpp", "certify", "conf_phases_I_II_III.json", "p.json"),
        ("dpp", "certify", "conf_phases_I_II_III.json", "p.json", "-H", "4", "--route",
         "both"))),
    Case("certify_conformance_directed_rational", (
        ("dpp", "solve", "conf_directed_rational.json", "-o", "p.json"),
        ("dpp", "certify", "conf_directed_rational.json", "p.json", "-H", "3", "--json"))),
    Case("certify_paper10_map", (
        ("dpp", "solve", *_PAPER10, "-o", "p.json", "--save-instance", "i.json"),
        ("dpp", "certify", *_PAPER10, "p.json"),
        ("dpp", "certify", "i.json", "p.json", "-H", "17", "--route", "structured"),
        ("dpp", "certify", "i.json", "p.json", "-H", "24", "--route", "structured"))),
    # --- dpp certify, N goals
    _one("certify_star3", "certify", *_STAR),
    _one("certify_star3_h2", "certify", *_STAR, "-H", "2"),
    _one("certify_star3_h2_tree_json", "certify", *_STAR, "-H", "2", "--route", "tree",
         "--json"),
    _one("certify_star3_h2_structured", "certify", *_STAR, "-H", "2", "--route", "structured"),
    _one("certify_star3_h2_both", "certify", *_STAR, "-H", "2", "--route", "both"),
    Case("certify_star3_solved", (
        ("dpp", "solve", "star3.json", "-o", "p.json"),
        ("dpp", "certify", "star3.json", "p.json"),
        ("dpp", "certify", "star3.json", "p.json", "-H", "3", "--route", "both"),
        ("dpp", "certify", "star3.json", "p.json", "--json"))),
    _one("certify_star3_profile_for_triangle", "certify", "triangle.json", "star3_profile.json"),
    _one("certify_two_goal_profile_for_star3", "certify", "star3.json", "triangle_profile.json"),
    # --- dpp value
    _one("value_triangle", "value", "triangle.json"),
    _one("value_triangle_h1_tree", "value", "triangle.json", "--horizon", "1", "--route",
         "tree"),
    _one("value_triangle_h2_both_json", "value", "triangle.json", "-H", "2", "--route", "both",
         "--json"),
    _one("value_triangle_h3_structured", "value", "examples/triangle.json", "-H", "3",
         "--route", "structured"),
    _one("value_triangle_output", "value", "triangle.json", "-H", "2", "-o", "v.json"),
    _one("value_kite_json", "value", "kite.json", "--json"),
    _one("value_conformance_grid_weighted", "value", "conf_grid_weighted.json"),
    _one("value_conformance_directed_rational_h3", "value", "conf_directed_rational.json",
         "-H", "3"),
    _one("value_conformance_s0_is_g1_h1_both", "value", "conf_s0_is_g1.json", "-H", "1",
         "--route", "both"),
    _one("value_conformance_xi2_tie_h1_json", "value", "conf_xi2_tie.json", "-H", "1",
         "--json"),
    _one("value_paper10_map", "value", *_PAPER10),
    _one("value_paper10_map_8", "value", *_PAPER10, "--connectivity", "8", "--json"),
    _one("value_paper10_map_short_horizon", "value", *_PAPER10, "-H", "6"),
    _one("value_star3", "value", "star3.json"),
    _one("value_star3_json", "value", "star3.json", "--json"),
    _one("value_star3_h2_both", "value", "star3.json", "-H", "2", "--route", "both"),
    _one("value_star3_h2_tree_json", "value", "star3.json", "-H", "2", "--route", "tree",
         "--json"),
    _one("value_hub4", "value", "hub4.json"),
    _one("value_hub4_h4_both", "value", "hub4.json", "-H", "4", "--route", "both"),
    _one("value_hub4_h3_structured_json", "value", "hub4.json", "-H", "3", "--route",
         "structured", "--json"),
    _one("value_hub4_undirected", "value", "hub4_undirected.json"),
    _one("value_paper10_map_n3", "value", *_PAPER10_N3),
    _one("value_malformed", "value", "malformed.json"),
    Case("value_module", (("python -m dppverify", "value", "triangle.json", "-H", "2",
                           "--json"),)),
    # --- dpp export-efg
    _one("efg_triangle_h2", "export-efg", "triangle.json", "--horizon", "2", "-o", "t.efg"),
    _one("efg_kite_h2_forced_blind", "export-efg", "kite.json", "-H", "2", "-o", "k.efg",
         "--forced-moves", "--attacker-blind"),
    _one("efg_star3_h2", "export-efg", "star3.json", "-H", "2", "-o", "s.efg"),
    _one("efg_too_many_nodes", "export-efg", "star3.json", "-H", "2", "-o", "s.efg",
         "--max-nodes", "10"),
    Case("efg_module", (("python -m dppverify", "export-efg", "triangle.json", "-H", "1", "-o",
                         "t.efg"),)),
    # --- dpp solve
    _one("solve_triangle", "solve", "triangle.json"),
    _one("solve_triangle_json", "solve", "triangle.json", "--json"),
    _one("solve_triangle_output", "solve", "triangle.json", "-o", "p.json", "--save-instance",
         "i.json"),
    _one("solve_kite", "solve", "kite.json"),
    _one("solve_conformance_s0_is_g1_json", "solve", "conf_s0_is_g1.json", "--json"),
    _one("solve_conformance_xi2_tie", "solve", "conf_xi2_tie.json"),
    _one("solve_paper10_map", "solve", *_PAPER10),
    _one("solve_paper10_map_8", "solve", *_PAPER10, "--connectivity", "8"),
    _one("solve_star3", "solve", "star3.json"),
    _one("solve_star3_json", "solve", "star3.json", "--json"),
    _one("solve_star3_equal_prior", "solve", "star3_equal_prior.json"),
    _one("solve_paper10_map_n3", "solve", *_PAPER10_N3, "-o", "p3.json"),
    _one("solve_hub4", "solve", "hub4.json"),
    _one("solve_hub4_output", "solve", "hub4.json", "--json", "-o", "p.json"),
    _one("solve_malformed", "solve", "malformed.json"),
    _one("solve_profile_as_instance", "solve", "triangle_profile.json"),
)
