"""What the structured route's checks share for any number of goals: the record, and the
Defender's greedy sums on the profile's walk trie (:class:`~dppverify.structured.trie.WalkTrie`;
proofs/L3.md L3.1 for two goals, proofs/NWALKBR.md NW.3 for N): ``max_σ`` of the Defender's
step payoff and its value at the profile's σ, over the prefixes that carry mass.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from fractions import Fraction

from dppverify.certificate import CheckRecord, Status
from dppverify.exact import Number


def structured_record(cid: str, status: Status, message: str,
                      numbers: dict[str, Number | None] | None, proof: str | None,
                      relies_on: str | None) -> CheckRecord:
    """A check record of the structured route.

    Examples
    --------
    >>> structured_record("value.U", "pass", "U = 1", None, "TEL", "the profile's walks").route
    'structured'
    """
    return CheckRecord(cid, status, message, numbers or {}, proof, route="structured",
                       relies_on=relies_on)


def mass_key(mass: Sequence[Fraction]) -> tuple[int, ...]:
    """Each type's realization mass as integers (hashed far faster than Fractions).

    Examples
    --------
    >>> mass_key([Fraction(1, 2), Fraction(1)])
    (1, 2, 1, 1)
    """
    if len(mass) == 2:  # the two-goal route's hot path
        x1, x2 = mass
        return (x1.numerator, x1.denominator, x2.numerator, x2.denominator)
    return tuple(v for x in mass for v in (x.numerator, x.denominator))


Masses = Sequence[Sequence[Fraction]] | Mapping[int, Sequence[Fraction]]
"""``masses[p][θ]``: type θ's realization mass at prefix ``p`` (:attr:`WalkTrie.masses`)."""


def greedy_sums(masses: Masses, prior: Sequence[Fraction],
                steps: Iterable[tuple[int, Number, Sequence[Number]]]) -> tuple[Number, Number]:
    """``(Σ_p w_p max_θ y_θ(p), Σ_p w_p Σ_θ σ_p(θ) y_θ(p))`` with ``y_θ = b_θ x_θ(p)``, exact.

    ``steps`` lists ``(p, w_p, σ_p)``: a prefix (with its ``masses[p]``), the weight of its
    last step and the Defender's distribution there (by goal index θ). The Defender's step
    payoff at its best response and at ``σ``: their difference is its regret on the prefixes
    given. ``w`` and ``w σ`` are summed per realization-mass vector (the prefixes of one walk
    share few) and multiplied by the masses once per vector: the same rationals exactly.

    Examples
    --------
    >>> from dppverify.structured.trie import mass_trie
    >>> from dppverify.game.profile import StrategyWalk
    >>> t = mass_trie([[StrategyWalk((0, 1), Fraction(1))], [StrategyWalk((0, 1), Fraction(1))]])
    >>> greedy_sums(t.masses, (Fraction(3, 4), Fraction(1, 4)),
    ...             [(1, 2, (Fraction(0), Fraction(1)))])
    (Fraction(3, 2), Fraction(1, 2))
    """
    groups: dict[tuple[int, ...], list[Number]] = {}
    of_key: dict[tuple[int, ...], Sequence[Fraction]] = {}
    for p, w, row in steps:
        mass = masses[p]
        key = mass_key(mass)
        acc = groups.get(key)
        if acc is None:
            acc = groups[key] = [0] * (len(row) + 1)
            of_key[key] = mass
        acc[0] += w
        for k, s in enumerate(row, start=1):
            acc[k] += w * s
    best: Number = 0
    at_sigma: Number = 0
    for key, acc in groups.items():
        y = [b * x for b, x in zip(prior, of_key[key], strict=True)]
        best += acc[0] * max(y)
        at_sigma += sum((a * yt for a, yt in zip(acc[1:], y, strict=True)), Fraction(0))
    return best, at_sigma
