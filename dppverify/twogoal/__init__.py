"""The two-goal mathematics (N = 2 only): the progress rule σ* (:mod:`~.progress`), the
phases of ξ² (:mod:`~.phases`), the best response over all walks against σ* or a table
(:mod:`~.progress_br`), and the fast three-field value DP (:mod:`~.value_dp`, its Dijkstra
fixpoint in :mod:`~.value_fixpoint`)."""
