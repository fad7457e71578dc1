"""Statistics of the density sweep and the paper's qualitative claims, checked on the data.

Claims (paper Sec. VII-D), each reported with its numbers and whether it holds here:

1. against σ*, the equilibrium Attacker has the highest mean VoI, then ambiguity, then
   exaggeration (``mean VoI(σ*,γ*) >= mean VoI(σ*,am) >= mean VoI(σ*,ex)``) at each density;
2. ``VoI(σ',γ*) = VoI(σ*,γ*)`` on the obstacle-free grid (exact equality, every sample);
3. the mean VoI of ``(σ*,γ*)`` and ``(σ',γ*)`` falls as the density grows (checked strictly,
   from each density to the next, and in the weaker form "last below first");
4. its spread grows with the density (checked for the standard deviation and for the range
   max − min separately, strictly from each density to the next).

Also reported: the sample-wise check ``VoI(σ*,γ) <= VoI(σ*,γ*)`` for the baselines γ (γ* is a
best response to σ*, so a violation would be a solver bug).
"""

from __future__ import annotations

import statistics
from collections import defaultdict
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from itertools import pairwise
from typing import Any

from dppio.text import decimal
from solver.literature.strategy_pairs import PAIRS, pair_label


@dataclass(frozen=True)
class Stats:
    """VoI statistics of one (density, pair) over its samples (floats of exact values)."""

    n: int
    mean: float
    median: float
    std: float
    q1: float
    q3: float
    min: float
    max: float

    @property
    def range(self) -> float:
        return self.max - self.min


@dataclass(frozen=True)
class Claim:
    """A claim of the paper, whether it holds on our data, and the numbers behind it."""

    text: str
    holds: bool
    evidence: str


@dataclass(frozen=True)
class DensitySummary:
    """Per-density, per-pair statistics and the claims."""

    densities: tuple[int, ...]
    stats: Mapping[tuple[int, tuple[str, str]], Stats]
    claims: tuple[Claim, ...]

    def text(self) -> str:
        """The summary as plain text (what ``dpp experiment density`` prints)."""
        lines = ["VoI by density and pair: mean / median / std / [min, max]  (n samples)"]
        for d in self.densities:
            lines.append(f"density {d:2d}%")
            for pair in PAIRS:
                s = self.stats.get((d, pair))
                if s is None:
                    continue
                lines.append(f"  {pair_label(*pair):<20s} {decimal(s.mean):>8} "
                             f"{decimal(s.median):>8} {decimal(s.std):>8} "
                             f"[{decimal(s.min):>7}, {decimal(s.max):>7}]  (n={s.n})")
        lines.append("")
        lines.append("Paper's claims on this data:")
        for c in self.claims:
            lines.append(f"  [{'HOLDS' if c.holds else 'FAILS'}] {c.text}")
            lines.extend(f"      {e}" for e in c.evidence.splitlines())
        return "\n".join(lines)

    def to_json(self) -> dict[str, Any]:
        return {
            "densities": list(self.densities),
            "stats": [{"density": d, "defender": p[0], "attacker": p[1], **vars(s)}
                      for (d, p), s in sorted(self.stats.items())],
            "claims": [vars(c) for c in self.claims],
        }


def summarize_density(rows: Iterable[Mapping[str, Any] | Any]) -> DensitySummary:
    """Statistics and claims from sweep rows (:class:`~solver.experiments.density.Row` or
    the dicts read back from the CSV).

    Examples
    --------
    >>> from solver.experiments.density import DensityConfig, run_density
    >>> rows = run_density(DensityConfig(size=8, start=(7, 0), goals=((0, 7), (0, 0)),
    ...                                  densities=(0, 20), samples=3), workers=1)
    >>> s = summarize_density(rows)
    >>> s.densities, s.stats[(0, ("sigma*", "gamma*"))].n
    ((0, 20), 3)
    """
    exact: dict[tuple[int, tuple[str, str]], dict[int, Fraction]] = defaultdict(dict)
    for r in rows:
        rec = r if isinstance(r, Mapping) else vars(r)
        key = (int(rec["density"]), (str(rec["defender"]), str(rec["attacker"])))
        exact[key][int(rec["sample"])] = Fraction(str(rec["VoI"]))
    densities = tuple(sorted({d for d, _ in exact}))
    stats = {key: _stats([float(v) for v in vals.values()]) for key, vals in exact.items()}
    return DensitySummary(densities, stats, _claims(densities, stats, exact))


def _stats(xs: Sequence[float]) -> Stats:
    xs = sorted(xs)
    q = statistics.quantiles(xs, n=4, method="inclusive") if len(xs) > 1 else [xs[0]] * 3
    return Stats(len(xs), statistics.fmean(xs), statistics.median(xs),
                 statistics.pstdev(xs), q[0], q[2], xs[0], xs[-1])


def _claims(densities: tuple[int, ...], stats: Mapping[tuple[int, tuple[str, str]], Stats],
            exact: Mapping[tuple[int, tuple[str, str]], Mapping[int, Fraction]]
            ) -> tuple[Claim, ...]:
    eq, alt = ("sigma*", "gamma*"), ("sigma'", "gamma*")
    am, ex = ("sigma*", "ambiguity"), ("sigma*", "exaggeration")
    out = []

    def mean(d: int, p: tuple[str, str]) -> float:
        return stats[(d, p)].mean

    have = [d for d in densities if all((d, p) in stats for p in (eq, am, ex))]
    if have:
        ok = [mean(d, eq) >= mean(d, am) >= mean(d, ex) for d in have]
        ev = "\n".join(f"{d:2d}%: {decimal(mean(d, eq))} >= {decimal(mean(d, am))} >= "
                       f"{decimal(mean(d, ex))}"
                       f"  {'yes' if o else 'NO'}" for d, o in zip(have, ok, strict=True))
        out.append(Claim("mean VoI: (σ*, γ*) >= (σ*, ambiguity) >= (σ*, exaggeration) at "
                         "every density", all(ok), ev))
        bad = sum(exact[(d, p)][k] > exact[(d, eq)][k]
                  for d in have for p in (am, ex) for k in exact[(d, p)])
        total = sum(len(exact[(d, p)]) for d in have for p in (am, ex))
        out.append(Claim("sample-wise VoI(σ*, baseline) <= VoI(σ*, γ*) "
                         "(γ* best-responds to σ*)", bad == 0,
                         f"{bad} violations in {total} comparisons"))
    if 0 in densities and (0, eq) in exact and (0, alt) in exact:
        a, b = exact[(0, eq)], exact[(0, alt)]
        same = sum(a[k] == b[k] for k in a if k in b)
        out.append(Claim("VoI(σ', γ*) = VoI(σ*, γ*) on the obstacle-free grid",
                         same == len(a) == len(b),
                         f"equal (exactly) on {same} of {len(a)} samples; values "
                         f"{sorted({str(v) for v in a.values()})} vs "
                         f"{sorted({str(v) for v in b.values()})}"))
    for p in (eq, alt):
        ds = [d for d in densities if (d, p) in stats]
        if len(ds) < 2:
            continue
        means = [stats[(d, p)].mean for d in ds]
        ranges = [stats[(d, p)].range for d in ds]
        stds = [stats[(d, p)].std for d in ds]
        falls = all(x > y for x, y in pairwise(means))
        name = pair_label(*p)
        out.append(Claim(f"mean VoI of {name} falls as the density grows (strictly, at "
                         "every step)", falls,
                         "means: " + ", ".join(f"{d}%: {decimal(m)}" for d, m in
                                               zip(ds, means, strict=True))))
        out.append(Claim(f"mean VoI of {name} is lower at the highest density than at the "
                         "lowest (weaker form)", means[-1] < means[0],
                         f"{ds[0]}%: {decimal(means[0])}, {ds[-1]}%: {decimal(means[-1])}"))
        for label, values in (("standard deviation", stds), ("range max-min", ranges)):
            grows = all(x < y for x, y in pairwise(values))
            out.append(Claim(f"spread of VoI of {name} grows with the density ({label})",
                             grows, ", ".join(f"{d}%: {decimal(x)}" for d, x in
                                              zip(ds, values, strict=True))))
    return tuple(out)
