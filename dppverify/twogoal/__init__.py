"""The two-goal mathematics (N = 2 only): the progress rule σ*
(:mod:`~dppverify.twogoal.progress`), the phases of ξ² (:mod:`~dppverify.twogoal.phases`),
the best response over all walks against σ* or a table (:mod:`~dppverify.twogoal.progress_br`),
and the fast three-field value DP (:mod:`~dppverify.twogoal.value_dp`, its Dijkstra fixpoint
in :mod:`~dppverify.twogoal.value_fixpoint`)."""
