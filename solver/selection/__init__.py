"""The goal-selection game: the Attacker chooses its goal (proofs/SELECT.md).

:mod:`~solver.selection.instance` reads the instance without a prior,
:mod:`~solver.selection.equilibrium` gives the value ``V_sel``, the choice ``q*``, the walks
and the Defender's rule (the guarantee rule, any N), :mod:`~solver.selection.mixture` the
two-goal Defender mixing the two progress rules.
"""
