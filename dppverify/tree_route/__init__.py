"""The tree route: the truncated game's walk tree, its LPs and exact best responses (any N >= 2).

Modules, bottom to top:

- :mod:`~dppverify.tree_route.tree`: the pruned walk tree (:class:`WalkTree`), its size count
  (``count_prefixes``, ``tree_fits``) and the flow constraints of realization plans;
- :mod:`~dppverify.tree_route.lp`: cvxpy + Clarabel with strict status checks;
  :mod:`~dppverify.tree_route.lp_exact`: the compact LP solved in rationals;
- :mod:`~dppverify.tree_route.players`: the Attacker's types and a Defender on the tree;
- :mod:`~dppverify.tree_route.best_response`: exact (and LP) best responses of a type and of
  the Defender, payoffs, Bayes beliefs;
- :mod:`~dppverify.tree_route.bracket`: exact bounds on ``V_H`` and the search that closes them;
- :mod:`~dppverify.tree_route.value_lp`: the compact value LP, its exact bracket, ``game_value``;
- :mod:`~dppverify.tree_route.context`: the two-goal checks' shared inputs on the tree;
- :mod:`~dppverify.tree_route.efg`: the Gambit ``.efg`` export.
"""
