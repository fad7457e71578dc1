"""The paper's Section VII experiments (the comparison table, the obstacle-density sweep), the
literature's Attackers against the equilibrium, the N-goal experiment and ``.scen`` batches:
one module each (docs/architecture.md)."""
