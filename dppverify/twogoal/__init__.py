"""The two-goal mathematics (N = 2 only): the phases of xi2 and the fast value DP."""
