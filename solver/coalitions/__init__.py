"""The construction for any number of goals (proofs/NSOLVE.md): the coalition DP and the cover LP
(:mod:`~.coalition_dp`), the Defender's guarantee rule (:mod:`~.guarantee_rule`) and the
construction with its ``dpp-ngoal-profile/1`` document (:mod:`~.construction`). For two goals
it gives the paper's σ*."""
