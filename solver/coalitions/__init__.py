"""The construction for any number of goals (proofs/NSOLVE.md, proofs/NEXACT.md): exact vertex
tables (:mod:`~.vertex_tables`), the cover LP over integer normals (:mod:`~.normal_cover`), the
normal-restricted DP and its certified fixpoint (:mod:`~.guarantee_sets`,
:mod:`~.block_fixpoint`), the Defender's guarantee rule (:mod:`~.guarantee_rule`), the Attacker
(:mod:`~.normal_attacker`) and the construction with its ``dpp-ngoal-profile/1`` document
(:mod:`~.construction`). For two goals it gives the paper's σ*."""
