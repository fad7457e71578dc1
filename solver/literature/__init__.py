"""The literature's deceptive strategies, evaluated against the equilibrium: Dragan et al.'s
observer belief (paper eq. (17), :mod:`~solver.literature.dragan_belief`), the Defender σ′
greedy on it (:mod:`~solver.literature.greedy_defender`), their ambiguity and exaggeration
paths (eqs. (18a)/(18b), :mod:`~solver.literature.deceptive_paths`), and Masters & Sardina's
π_d1–π_d4 (:mod:`~solver.literature.masters_sardina`)."""
