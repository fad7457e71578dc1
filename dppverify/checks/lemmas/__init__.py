"""Lemma certificates on the instance (proofs/TEL.md, L1.md, L2.md, XI2.md, L3.md, L4.md, L5.md).

One module per family: :mod:`~dppverify.checks.lemmas.sigma_star` (σ* on the walk tree: TEL,
L1, L2, XI2), :mod:`~dppverify.checks.lemmas.random_attackers` (L3, L4, against random
non-reacting attackers), :mod:`~dppverify.checks.lemmas.beliefs` (L5, the profile's beliefs).

All lemma checks use the paper's σ* (progress towards the profile's primary goal) on the
walk tree, whatever Defender the profile proposes, and exact arithmetic:

- ``lemma.TEL.telescoping``: along every walk, ``Σ w σ*(g1) = c_0 − c_t`` and σ* ∈ [0, 1].
- ``lemma.L1.lower_bound``: min over walks of U¹ against σ* is ``d(s0, g1)``; every walk
  ending at g1 costs exactly that; a walk ending at g2 costs ``d(s0,g1) − c_T + d(g2,g1)``.
- ``lemma.L2.no_revisits``: the secondary's best response over walks equals that over
  simple paths, and every minimising walk is simple.
- ``lemma.XI2.secondary_value``: that minimum is at least ``M − d(s0, g1)`` (proofs/XI2.md), with
  equality once the horizon admits an optimal path.
- ``lemma.L3.greedy``: for the profile's attacker and random non-reacting attackers, the
  Defender's LP optimum equals the exact greedy-on-belief value and is greedy wherever the
  belief is strict.
- ``lemma.L4.monotonicity``: with the secondary deterministic on a walk ξ, the belief in g1
  along ξ never increases, for the profile's and for random primary strategies.
- ``lemma.L5.induced_beliefs``: the profile induces beliefs ``b1`` / 1/2 / 0 on phases
  I / II / III of ξ². Lemma 5's belief 1 off ξ² is not checked: with one secondary walk the
  secondary puts no mass off ξ², so that belief is 1 by Bayes' rule whatever the profile
  (a check that cannot fail is no evidence); the message says so (:data:`OFF_XI2`).
"""

from dppverify.checks.lemmas.beliefs import OFF_XI2, l5_induced_beliefs
from dppverify.checks.lemmas.random_attackers import (
    GREEDY_COEFFICIENT,
    GREEDY_SIGMA_TOLERANCE,
    l3_greedy,
    l4_monotonicity,
    random_mixture,
)
from dppverify.checks.lemmas.sigma_star import (
    l1_lower_bound,
    l2_no_revisits,
    telescoping,
    xi2_secondary_value,
)

__all__ = ["GREEDY_COEFFICIENT", "GREEDY_SIGMA_TOLERANCE", "OFF_XI2", "l1_lower_bound",
           "l2_no_revisits", "l3_greedy", "l4_monotonicity", "l5_induced_beliefs",
           "random_mixture", "telescoping", "xi2_secondary_value"]
