"""N goals: the DPP game with N >= 2 candidate goals (the paper's future work).

The paper's game and construction are for two goals; this subpackage checks the game with
``N >= 2`` goals g^1 … g^N, an N-entry prior, type θ walking to g^θ, walks ending at the first
goal reached, terminal cost ``d(end, g^θ)`` and a Defender that puts each step's weight on one
goal (``docs/formats.md`` §1, "N goals"). Two routes:

- the *tree route* (the literal definition): the truncated game's walk tree, the compact value
  LP with N types (cvxpy + Clarabel) closed by an exact rational bracket, exact best responses
  of every type and of the Defender, Bayes beliefs and sequential rationality of a profile
  (:mod:`dppverify.tree_route.tree`, :mod:`dppverify.tree_route.value_lp`,
  :mod:`dppverify.tree_route.best_response`, :mod:`dppverify.ngoal.certify`);
- the *structured route*: the guarantee sets (:mod:`dppverify.ngoal.proved_value`), for any
  horizon and ``H = inf``: the coalition dynamic programme over the ``2^N - 1`` goal subsets
  (:mod:`dppverify.ngoal.coalition`) is an upper bound, the value for N <= 3 (proved in
  ``proofs/NGOAL.md``) and for N = 4, 5 where an exact certificate holds (refined with extra
  facet normals where it does not); otherwise an exact bracket. Its agreement with the tree
  route is property-tested.

Nothing here changes the two-goal code: two-goal instances keep their own parser, checker and
certificate.
"""

from __future__ import annotations
