"""The profile checks, one module per family (ids and order: :mod:`dppverify.registry`).

- :mod:`~dppverify.checks.wellformed`: the profile document (``profile.wellformed``,
  ``profile.phases``);
- :mod:`~dppverify.checks.payoffs`: the profile's payoffs and the game value (``value.*``,
  ``game.value``);
- :mod:`~dppverify.checks.attacker`: the Attacker types' regrets (``pbne.attacker_br.*``);
- :mod:`~dppverify.checks.defender`: the Defender's regret and sequential rationality
  (``pbne.defender_br``, ``pbne.sequential_rationality``);
- :mod:`~dppverify.checks.beliefs`: Bayes beliefs (``pbne.belief_consistency``);
- :mod:`dppverify.checks.lemmas`: the paper's lemmas on the instance (``lemma.*``), one
  module per family;
- :mod:`~dppverify.checks.runners`: for every tree check id, the function computing it.

Each check takes the shared :class:`~dppverify.tree_route.context.Context` (built by
:func:`~dppverify.tree_route.context.make_context`) and returns its
:class:`~dppverify.certificate.CheckRecord` (ids in ``dppverify/checks.md``). Exact numbers
decide every pass/fail; LP numbers are reported beside them and must agree within
:data:`~dppverify.tree_route.lp.LP_TOLERANCE` (a disagreement is an ``error``: the checker's two
routes
contradict each other, which is not the profile's fault).
"""
