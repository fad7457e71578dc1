"""The refinement's budget and the exception that says it ended (``dpp solve`` states both)."""

from __future__ import annotations

from dataclasses import dataclass


class BudgetExceeded(Exception):
    """The fixpoint or the normals were not found within the stated budget."""


@dataclass(frozen=True)
class Budget:
    """Limits of the refinement (``dpp solve`` states them when one is reached).

    Attributes
    ----------
    rounds : int
        Refinement rounds (each adds at least one facet normal).
    layers : int or None
        DP layers per run (None: ``20 · nodes + 200``).
    extra_normals : int
        Normals beyond the ``2^N - 1`` 0/1 vectors.
    bases : int
        Bases tried for one vertex table.
    """

    rounds: int = 12
    layers: int | None = None
    extra_normals: int = 80
    bases: int = 20_000_000

    def describe(self) -> str:
        """One phrase naming the limits.

        Examples
        --------
        >>> Budget().describe()
        '12 refinement rounds, 20·nodes + 200 layers, 80 extra normals, 20,000,000 bases'
        """
        layers = "20·nodes + 200" if self.layers is None else f"{self.layers:,}"
        return (f"{self.rounds} refinement rounds, {layers} layers, {self.extra_normals} extra "
                f"normals, {self.bases:,} bases")
