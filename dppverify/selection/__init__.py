"""The goal-selection game: the Attacker chooses its goal (proofs/SELECT.md)."""
