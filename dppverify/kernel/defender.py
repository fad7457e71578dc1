"""The Defender's check: greedy on the Bayes masses of the profile's walk trie (proofs/KERNEL.md
K.2 item 6; L3.1, NWALKBR NW.3), by comparisons of masses only (no division)."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from fractions import Fraction
from typing import Any

from dppverify.kernel.reading import Instance
from dppverify.kernel.verdict import Refuted


def check_greedy(inst: Instance, mixtures: Sequence[Sequence[tuple[tuple[int, ...], Fraction]]],
                 steps: Callable[[tuple[int, ...]], list[Any]]) -> int:
    """Refute unless σ is greedy at every reached prefix; return the number of reached prefixes.

    ``m_θ(p) = b_θ · Σ p_W`` over type θ's walks ``W`` through ``p``; at every prefix ``p`` of at
    least one step with positive total mass, ``σ_p(i) > 0`` must imply ``m_i(p) = max m(p)``.
    ``steps(W)`` gives each step's costs ``S·w·σ(i)``: positive exactly where ``σ(i)`` is.

    Examples
    --------
    >>> from dppverify.kernel.reading import read_instance
    >>> inst = read_instance(b'''{"graph": {"nodes": [{"id": "s"}, {"id": "a"}, {"id": "b"}],
    ...   "edges": [{"source": "s", "target": "a"}, {"source": "s", "target": "b"}]},
    ...   "start": "s", "goals": ["a", "b"], "prior": ["3/5", "2/5"]}''', None)
    >>> mix = [[((0, 1), Fraction(1))], [((0, 1), Fraction(1))]]
    >>> check_greedy(inst, mix, lambda w: [(2, 0)])
    1
    >>> check_greedy(inst, mix, lambda w: [(1, 1)])
    Traceback (most recent call last):
    dppverify.kernel.verdict.Refuted: Defender: not greedy at the reached prefix ["s", "a"]: \
sigma puts 1/2 on goal "b", whose Bayes mass 2/5 is below the largest, 3/5
    """
    n, ids = len(inst.goals), dict[tuple[int, int], int]()
    mass: list[list[Fraction]] = []
    sig: list[Any] = []  # per prefix: its costs and (walk, length) to name it
    for theta, mix in enumerate(mixtures):
        for w, p in mix:
            s, node = steps(w), -1
            for t in range(1, len(w)):
                node = ids.setdefault((node, w[t]), len(mass))
                if node == len(mass):
                    mass.append([Fraction(0)] * n)
                    sig.append((s[t - 1], w, t))
                mass[node][theta] += inst.prior[theta] * p
    for m, (s, w, t) in zip(mass, sig, strict=True):
        top = max(m)
        for i in range(n):
            if top > 0 and s[i] > 0 and m[i] < top:
                shown = ", ".join(inst.show(v) for v in w[:t + 1])
                raise Refuted(f"Defender: not greedy at the reached prefix [{shown}]: sigma puts "
                              f"{Fraction(s[i]) / sum(s)} on goal {inst.show(inst.goals[i])}, "
                              f"whose Bayes mass {m[i]} is below the largest, {top}")
    return len(mass)
