"""The structured route of ``certify``: the untruncated game, without the walk tree.

For a profile whose Defender is a progress rule (σ* or the progress rule towards the other
goal) or a table with a ``default``: both Attacker types' exact regret over ALL walks of any
length (proofs/WALKBR.md, shortest paths only; for a table proofs/TABLEBR.md, backward
induction on the table's trie plus an exact Dijkstra off it); the Defender's exact regret,
sequential rationality and Bayes beliefs on the prefixes of the profile's own walks (the only
information sets that carry mass); payoffs walk by walk; the value by the three-field DP
(proofs/DP.md); the lemmas that have a polynomial form. The lemma checks that need the tree
(L3's and L4's random attackers with their LPs) are not run on this route; the certificate
says so.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from fractions import Fraction

from dppverify.certificate import CheckRecord, Status
from dppverify.checks.lemmas import OFF_XI2
from dppverify.checks.skipped import NOT_WELLFORMED
from dppverify.exact import Number
from dppverify.game.defender import sigma_along, step_weight, step_weights
from dppverify.game.distances import ArcRows
from dppverify.game.evaluation import Values, evaluate, walk_cost
from dppverify.game.instance import Instance, Roles
from dppverify.game.profile import DefenderRule, Profile, ProgressRule, StrategyPath, TableRule
from dppverify.numbers import NumberMode
from dppverify.structured.table_br_twogoal import table_minima
from dppverify.text import show, show_walk
from dppverify.twogoal.phases import phases_of
from dppverify.twogoal.progress_br import WalkMinima, split_minimum, walk_minima
from dppverify.twogoal.value_dp import structured_value

__all__ = ["Trie", "build_trie", "evaluate_walk", "structured_checks"]


HALF = Fraction(1, 2)
WALKBR = "relies on proofs/WALKBR.md"
TABLEBR = "relies on proofs/TABLEBR.md (a table Defender with a default)"
DP = "relies on proofs/DP.md"
TRIE = "on the prefixes of the profile's walks (proofs/L3.md)"


class _MassView(Mapping[tuple[int, ...], tuple[Fraction, Fraction]]):
    """``trie.mass``: prefix (a node-index tuple) -> ``(x1, x2)``, computed on demand from
    the trie's arrays (no tuple per prefix is stored)."""

    def __init__(self, trie: Trie) -> None:
        self._trie = trie

    def __getitem__(self, prefix: tuple[int, ...]) -> tuple[Fraction, Fraction]:
        i = self._trie.find(prefix)
        if i is None:
            raise KeyError(prefix)
        return self._trie.x1[i], self._trie.x2[i]

    def __iter__(self) -> Iterator[tuple[int, ...]]:
        return (self._trie.walk(i) for i in range(self._trie.size))

    def __len__(self) -> int:
        return self._trie.size


@dataclass(frozen=True, eq=False)
class Trie:
    """The prefixes of the profile's walks with each type's realization mass.

    Stored in memory linear in the total walk length: prefix ``i`` is its last node
    ``node[i]`` and its parent prefix ``parent[i]`` (``-1`` at a root); ``x1[i], x2[i]`` are
    the two types' realization masses. ``ids[k]`` lists the prefixes along the ``k``-th walk
    given (primary walks first, then secondary). ``mass`` keeps the tuple-keyed view:
    ``mass[p] = (x1(p), x2(p))`` for every prefix ``p`` (root included), each key built only
    when asked for.
    """

    node: tuple[int, ...]
    parent: tuple[int, ...]
    x1: tuple[Fraction, ...]
    x2: tuple[Fraction, ...]
    ids: tuple[tuple[int, ...], ...]
    _children: dict[tuple[int, int], int] = field(repr=False)

    @property
    def size(self) -> int:
        """Number of prefixes (roots included)."""
        return len(self.node)

    @property
    def mass(self) -> Mapping[tuple[int, ...], tuple[Fraction, Fraction]]:
        """Prefix tuple -> ``(x1, x2)`` (a view; see the class docstring)."""
        return _MassView(self)

    def find(self, prefix: Sequence[int]) -> int | None:
        """The id of the prefix ``prefix`` (node indices), or None when it is not in the trie."""
        i = -1
        for v in prefix:
            nxt = self._children.get((i, v))
            if nxt is None:
                return None
            i = nxt
        return i if prefix else None

    def find_along(self, walk: Sequence[int]) -> list[int]:
        """The prefix ids along ``walk`` (one per node), which must be in the trie."""
        out, i = [], -1
        for v in walk:
            i = self._children[(i, v)]
            out.append(i)
        return out

    def walk(self, i: int) -> tuple[int, ...]:
        """The node-index tuple of prefix ``i``."""
        out = []
        while i >= 0:
            out.append(self.node[i])
            i = self.parent[i]
        return tuple(reversed(out))


def build_trie(primary: Iterable[StrategyPath], secondary: Iterable[StrategyPath]) -> Trie:
    """Realization masses of both types on the prefixes of their walks, in memory linear in
    the total walk length.

    Examples
    --------
    >>> from dppverify.game.profile import StrategyPath
    >>> t = build_trie([StrategyPath((0, 1), Fraction(4, 7)), StrategyPath((0, 2), Fraction(3, 7))],
    ...                [StrategyPath((0, 2), Fraction(1))])
    >>> t.mass[(0,)], t.mass[(0, 2)]
    ((Fraction(1, 1), Fraction(1, 1)), (Fraction(3, 7), Fraction(1, 1)))
    >>> t.size, t.ids, t.walk(2)
    (3, ((0, 1), (0, 2), (0, 2)), (0, 2))
    """
    children: dict[tuple[int, int], int] = {}
    node: list[int] = []
    parent: list[int] = []
    mass: list[list[Fraction]] = []
    ids: list[tuple[int, ...]] = []
    for theta, walks in ((0, primary), (1, secondary)):
        for mw in walks:
            i = -1
            along = []
            for v in mw.walk:
                nxt = children.get((i, v))
                if nxt is None:
                    nxt = children[(i, v)] = len(node)
                    node.append(v)
                    parent.append(i)
                    mass.append([Fraction(0), Fraction(0)])
                mass[nxt][theta] += mw.probability
                along.append(nxt)
                i = nxt
            ids.append(tuple(along))
    return Trie(tuple(node), tuple(parent), tuple(m[0] for m in mass),
                tuple(m[1] for m in mass), tuple(ids), children)


def _rec(cid: str, status: Status, message: str, numbers: dict[str, Number | None] | None,
         proof: str | None, relies_on: str | None) -> CheckRecord:
    return CheckRecord(cid, status, message, numbers or {}, proof, route="structured",
                       relies_on=relies_on)


def structured_checks(instance: Instance, profile: Profile,
                      horizon: int | None) -> list[CheckRecord]:
    """Every check of the structured route, in certificate order.

    Parameters
    ----------
    instance : Instance
        The game.
    profile : Profile
        The resolved profile; its Defender must be a progress rule or a table with a default
        (or the profile ill-formed).
    horizon : int or None
        ``H`` of the truncated game for ``game.value``; None for the untruncated game.

    Returns
    -------
    list of CheckRecord

    Examples
    --------
    >>> from dppverify.game.examples import triangle, triangle_profile
    >>> from dppverify.game.profile import profile_from_json
    >>> inst = triangle()
    >>> recs = structured_checks(inst, profile_from_json(triangle_profile(), inst),
    ...                          None)
    >>> [r.status for r in recs] == ["pass"] * len(recs), len(recs)
    (True, 17)
    """
    roles = instance.roles(profile.primary_slot)
    mode = instance.numbers
    missing = _unlisted_profile_prefix(profile)
    out: list[CheckRecord] = [_wellformed(instance, profile, roles, missing)]
    usable = profile.wellformed and missing is None and isinstance(
        profile.defender, ProgressRule | TableRule)
    if not usable:
        ids = ("value.U1", "value.U2", "value.U", "value.VoI", "profile.phases",
               "pbne.attacker_br.primary", "pbne.attacker_br.secondary", "pbne.defender_br",
               "pbne.sequential_rationality", "pbne.belief_consistency", "game.value",
               "lemma.TEL.telescoping", "lemma.L1.lower_bound", "lemma.L2.no_revisits")
        out += [_rec(i, "skipped", NOT_WELLFORMED, None, None, None) for i in ids]
        out.append(_xi2(instance, roles, mode, walk_minima(instance, roles.g1)))
        out.append(_rec("lemma.L5.induced_beliefs", "skipped", NOT_WELLFORMED, None, "L5", None))
        return out
    rule = profile.defender
    assert rule is not None
    v = evaluate(instance, roles, rule, profile.primary, profile.secondary)
    trie = build_trie(profile.primary, profile.secondary)
    sigma = _sigma_on_trie(instance, roles, rule, trie)
    defender_max, u_trie = _defender_payoffs(instance, roles, trie, sigma)
    out += _values(profile, v, u_trie, mode)
    out.append(_phases(instance, profile, roles, mode))
    star = walk_minima(instance, roles.g1)  # shared by the Attacker, L1 and XI2 checks
    if isinstance(rule, ProgressRule):
        mins = star if rule.goal == roles.g1 else walk_minima(instance, rule.goal)
        same = roles.g1 == rule.goal
        best = {1: mins.same if same else mins.other, 2: mins.other if same else mins.same}
        relies = WALKBR
    else:
        tm = table_minima(instance, roles, rule)
        best = {1: tm.primary, 2: tm.secondary}
        relies = TABLEBR
    out += _attacker(v, mode, best, relies)
    out.append(_defender(v, defender_max, mode))
    beliefs = _beliefs(roles, trie)
    out.append(_sequential(instance, trie, sigma, beliefs, mode))
    out.append(_belief_consistency(instance, profile, roles, trie, beliefs))
    out.append(_game_value(instance, v, mode, horizon))
    out.append(_telescoping(instance, roles, trie, mode))
    out.append(_l1(instance, roles, profile, mode, star))
    out.append(_l2(instance, profile))
    out.append(_xi2(instance, roles, mode, star))
    out.append(_l5(instance, profile, roles, trie, beliefs, mode))
    return out


def _unlisted_profile_prefix(profile: Profile) -> tuple[int, ...] | None:
    """The shortest prefix of a profile walk where a table Defender without default is
    undefined (None when there is none, or the Defender is not such a table)."""
    rule = profile.defender
    if not isinstance(rule, TableRule) or rule.default is not None:
        return None
    best: tuple[int, ...] | None = None
    for mw in (*profile.primary, *profile.secondary):
        for t in range(2, len(mw.walk) + 1):
            if mw.walk[:t] not in rule.entries:
                if best is None or t < len(best):
                    best = mw.walk[:t]
                break
    return best


def _wellformed(instance: Instance, profile: Profile, roles: Roles,
                missing: tuple[int, ...] | None = None) -> CheckRecord:
    defects = [str(d) for d in profile.defects]
    if missing is not None:
        defects.append(f"the Defender's table has no entry for walk "
                       f"{show_walk(instance, missing)}, which the profile plays, and no "
                       f"default")
    numbers: dict[str, Number | None] = {"defects": len(defects),
                                         "primary_walks": len(profile.primary),
                                         "secondary_walks": len(profile.secondary)}
    if defects:
        more = f"; and {len(defects) - 5} more" if len(defects) > 5 else ""
        return _rec("profile.wellformed", "fail", "; ".join(defects[:5]) + more, numbers, None,
                    "the profile document alone")
    return _rec("profile.wellformed", "pass",
                f"well-formed: {len(profile.primary)} primary and {len(profile.secondary)} "
                f"secondary walk(s), primary goal {instance.nodes[roles.g1]!r}", numbers, None,
                "the profile document alone")


def _sigma_on_trie(instance: Instance, roles: Roles, rule: DefenderRule,
                   trie: Trie) -> list[Number | None]:
    """σ(g1 | p) at every prefix id of the trie (None at a root): along each walk once."""
    out: list[Number | None] = [None] * trie.size
    done = [False] * trie.size
    for along in sorted(trie.ids, key=len, reverse=True):  # longest first: O(total length)
        if len(along) > 1 and not done[along[-1]]:
            walk = [trie.node[i] for i in along]
            for t, sv in enumerate(sigma_along(instance, roles, rule, walk), start=1):
                out[along[t]] = sv
                done[along[t]] = True
    return out


def _defender_payoffs(instance: Instance, roles: Roles, trie: Trie,
                      sigma: list[Number | None]) -> tuple[Number, Number]:
    """``max_σ U(σ, γ)`` (greedy per prefix) and ``U`` at the profile's σ, on the trie.

    Exact mode sums ``w`` and ``w σ`` per realization-mass pair (the prefixes of one walk
    share few of them) and multiplies by the masses once per pair: ``Σ_p w_p max(y1, y2)``
    and ``Σ_p w_p (σ_p y1 + (1 - σ_p) y2)`` regrouped, the same rationals exactly.
    """
    best: Number = 0
    at_sigma: Number = 0
    mode = instance.numbers
    steps = [i for i in range(trie.size) if trie.parent[i] >= 0]
    weights = _last_step_weights(instance, trie, steps)
    weight_of = dict(zip(steps, weights, strict=True))
    if mode.exact:
        groups: dict[tuple[int, int, int, int], list[Number]] = {}
        masses = {}
        for i, w in zip(steps, weights, strict=True):
            mass = (trie.x1[i], trie.x2[i])
            key = _mass_key(mass)
            acc = groups.get(key)
            if acc is None:
                acc = groups[key] = [0, 0]
                masses[key] = mass
            s = sigma[i]
            assert s is not None  # every non-root prefix lies on a walk (_sigma_on_trie)
            acc[0] += w
            acc[1] += w * s
        for key, (w_sum, ws_sum) in groups.items():
            x1, x2 = masses[key]
            y1, y2 = roles.b1 * x1, roles.b2 * x2
            best += w_sum * max(y1, y2)
            at_sigma += ws_sum * y1 + (w_sum - ws_sum) * y2
    for i in range(trie.size):  # float mode: the order of the sums as before
        last = trie.node[i]
        on_step = trie.parent[i] >= 0 and not mode.exact
        if not (on_step or instance.is_goal(last)):
            continue
        y1, y2 = roles.b1 * trie.x1[i], roles.b2 * trie.x2[i]
        if on_step:
            w = weight_of[i]
            s = sigma[i]
            assert s is not None
            best += float(w) * float(max(y1, y2))
            at_sigma += float(w) * (float(s) * float(y1) + (1 - float(s)) * float(y2))
        if instance.is_goal(last):
            term = y1 * roles.d1[last] + y2 * roles.d2[last]
            best += mode.convert(term)
            at_sigma += mode.convert(term)
    return mode.convert(best), mode.convert(at_sigma)


def _mass_key(mass: tuple[Fraction, Fraction]) -> tuple[int, int, int, int]:
    """A realization-mass pair as integers (hashed far faster than two Fractions)."""
    x1, x2 = mass
    return (x1.numerator, x1.denominator, x2.numerator, x2.denominator)


def _last_step_weights(instance: Instance, trie: Trie, ids: list[int]) -> list[Number]:
    """The weight of the last step of each prefix id (not a root), in one pass."""
    tails = [trie.node[trie.parent[i]] for i in ids]
    heads = [trie.node[i] for i in ids]
    if isinstance(instance.succ, ArcRows):
        found = instance.succ.find_many(tails, heads)
    else:
        found = [instance.weight(u, v) for u, v in zip(tails, heads, strict=True)]
    out: list[Number] = []
    for u, v, w in zip(tails, heads, found, strict=True):
        out.append(step_weight(instance, (u, v), 1) if w is None else w)  # raises
    return out


def _values(profile: Profile, v: Values, u_trie: Number, mode: NumberMode) -> list[CheckRecord]:
    claims = profile.claimed_values
    out = []
    for cid, key, exact in (("value.U1", "U1", v.U1), ("value.U2", "U2", v.U2),
                            ("value.U", "U", v.U)):
        numbers: dict[str, Number | None] = {key: exact, f"{key}_profile": claims.get(key)}
        status: Status = "pass"
        problems = []
        if key in claims and not mode.equal(claims[key], exact):
            status = "fail"
            problems.append(f"the profile claims {key} = {show(claims[key])}")
        if key == "U":
            numbers["U_trie"] = u_trie
            if not mode.equal(u_trie, exact):
                status = "error" if status == "pass" else status
                problems.append(f"the realization-mass route gives {show(u_trie)}")
        msg = f"{key} = {show(exact)} walk by walk"
        if problems:
            msg = f"{key} = {show(exact)} exactly, but " + "; ".join(problems)
        out.append(_rec(cid, status, msg, numbers, "TEL", "the profile's walks, walk by walk"))
    bad = [k for k, x in (("U_bar", v.U_bar), ("VoI", v.VoI))
           if k in claims and not mode.equal(claims[k], x)]
    msg = f"U_bar = {show(v.U_bar)}, VoI = {show(v.VoI)}"
    if bad:
        msg += "; the profile claims " + ", ".join(f"{k} = {show(claims[k])}" for k in bad)
    out.append(_rec("value.VoI", "fail" if bad else "pass", msg,
                    {"U_bar": v.U_bar, "VoI": v.VoI}, "THM", "the profile's walks"))
    return out


def _phases(instance: Instance, profile: Profile, roles: Roles, mode: NumberMode) -> CheckRecord:
    claim = profile.claimed_phases
    sec = [w for w in profile.secondary if w.probability > 0]
    how = "σ* along the profile's secondary walk"
    if len(sec) != 1:
        if claim is None:
            return _rec("profile.phases", "pass", "no phases claimed (the secondary mixes "
                        "several walks)", None, "L5", how)
        return _rec("profile.phases", "fail", "phases are claimed but the secondary type mixes "
                    "several walks (phases are defined on one path ξ²)", None, "L5", how)
    got = phases_of(sigma_along(instance, roles, ProgressRule(roles.g1), sec[0].walk), mode)
    numbers: dict[str, Number | None] = {"t_I": got.t_I, "t_II": got.t_II, "T": got.T}
    if claim is None:
        return _rec("profile.phases", "pass", f"no phases claimed; recomputed t_I = {got.t_I}, "
                    f"t_II = {got.t_II}, T = {got.T}", numbers, "L5", how)
    ok = tuple(claim) == got.as_tuple()
    return _rec("profile.phases", "pass" if ok else "fail", f"t_I, t_II, T = {got.as_tuple()} "
                f"from σ* along ξ²" + ("" if ok else f"; the profile claims {tuple(claim)}"),
                numbers, "L5", how)


def _attacker(v: Values, mode: NumberMode, minima: dict[int, Number],
              relies: str) -> list[CheckRecord]:
    out = []
    for theta, cid, proof in ((1, "pbne.attacker_br.primary", "L1"),
                              (2, "pbne.attacker_br.secondary", "XI2")):
        best = minima[theta]
        u = v.U1 if theta == 1 else v.U2
        regret = mode.difference(u, best)
        numbers: dict[str, Number | None] = {"U": u, "min_over_walks": best, "regret": regret}
        kind = "primary" if theta == 1 else "secondary"
        if mode.less_than(u, best):
            out.append(_rec(cid, "error", f"the {kind} type's cost {show(u)} is below the "
                            f"minimum over all walks {show(best)}: the routes disagree",
                            numbers, proof, relies))
        elif mode.equal(regret, 0):
            out.append(_rec(cid, "pass", f"{kind} regret 0 over all walks of any length: "
                            f"U = min = {show(best)}", numbers, proof, relies))
        else:
            out.append(_rec(cid, "fail", f"{kind} regret {show(regret)} > 0: some walk costs "
                            f"{show(best)} < U = {show(u)} against the profile's Defender",
                            numbers, proof, relies))
    return out


def _defender(v: Values, best: Number, mode: NumberMode) -> CheckRecord:
    regret = best - v.U
    numbers: dict[str, Number | None] = {"U": v.U, "max_sigma_U": best, "regret": regret}
    if mode.equal(regret, 0):
        return _rec("pbne.defender_br", "pass", f"Defender regret 0: greedy value "
                    f"{show(best)} = U on the profile's prefixes", numbers, "L3", TRIE)
    status: Status = "fail" if mode.less_than(0, regret) else "error"
    return _rec("pbne.defender_br", status, f"Defender regret {show(regret)}: greedy value "
                f"{show(best)} vs U = {show(v.U)}", numbers, "L3", TRIE)


def _beliefs(roles: Roles, trie: Trie) -> dict[int, Fraction]:
    """The Bayes belief in the primary type at every reached prefix id."""
    out = {}
    by_mass: dict[tuple[int, int, int, int], Fraction | None] = {}  # once per mass pair
    for i in range(trie.size):
        mass = (trie.x1[i], trie.x2[i])
        key = _mass_key(mass)
        if key in by_mass:
            b = by_mass[key]
        else:
            x1, x2 = mass
            y1, y2 = roles.b1 * x1, roles.b2 * x2
            b = by_mass[key] = y1 / (y1 + y2) if y1 + y2 > 0 else None
        if b is not None:
            out[i] = b
    return out


def _sequential(instance: Instance, trie: Trie, sigma: list[Number | None],
                beliefs: dict[int, Fraction], mode: NumberMode) -> CheckRecord:
    bad = []
    side: dict[tuple[int, int], int] = {}  # the sign of b - 1/2, once per belief value
    for i, b in beliefs.items():
        if trie.parent[i] < 0:
            continue
        s = sigma[i]
        assert s is not None  # every non-root prefix lies on a walk (_sigma_on_trie)
        key = (b.numerator, b.denominator)
        c = side.get(key)
        if c is None:
            c = side[key] = (b > HALF) - (b < HALF)
        if (c > 0 and not mode.equal(s, 1)) or (c < 0 and not mode.equal(s, 0)):
            bad.append((i, b, s))
    numbers: dict[str, Number | None] = {"reached": len(beliefs) - 1, "violations": len(bad)}
    if bad:
        i, b, s = bad[0]
        return _rec("pbne.sequential_rationality", "fail", f"{len(bad)} reached information "
                    f"set(s) where the Defender is not greedy, e.g. after "
                    f"{show_walk(instance, trie.walk(i))} the belief is {show(b)} but σ(g1) = "
                    f"{show(s)}", numbers, "THM", TRIE)
    return _rec("pbne.sequential_rationality", "pass", f"greedy on the Bayes belief at all "
                f"{len(beliefs) - 1} reached information sets", numbers, "THM", TRIE)


def _belief_consistency(instance: Instance, profile: Profile, roles: Roles, trie: Trie,
                        beliefs: dict[int, Fraction]) -> CheckRecord:
    problems = []
    if profile.claimed_prior is not None and profile.claimed_prior != (roles.b1, roles.b2):
        c1, c2 = profile.claimed_prior
        problems.append(f"the profile states the prior ({show(c1)}, {show(c2)}) but the "
                        f"instance's is ({show(roles.b1)}, {show(roles.b2)})")
    steps: dict[tuple[int, ...], Fraction] = {}
    for i, b in beliefs.items():
        q = trie.parent[i]
        if q < 0:
            if b != roles.b1:
                problems.append(f"root belief {show(b)} is not the prior")
            continue
        mq, mp, prev = (trie.x1[q], trie.x2[q]), (trie.x1[i], trie.x2[i]), beliefs[q]
        key = (prev.numerator, prev.denominator, *_mass_key(mq), *_mass_key(mp))
        bayes = steps.get(key)  # Bayes' step: once per (belief, masses) triple
        if bayes is None:
            (a1, a2), (c1, c2) = mq, mp
            l1 = c1 / a1 if a1 else Fraction(0)  # P(step | type), eq. (2)
            l2 = c2 / a2 if a2 else Fraction(0)
            bayes = steps[key] = prev * l1 / (prev * l1 + (1 - prev) * l2)
        if bayes != b and len(problems) < 3:
            problems.append(f"after {show_walk(instance, trie.walk(i))}: Bayes' rule gives "
                            f"{show(bayes)}, the closed form {show(b)}")
        elif bayes != b:
            problems.append("")
    numbers: dict[str, Number | None] = {"reached": len(beliefs)}
    if problems:
        return _rec("pbne.belief_consistency", "fail", "; ".join(problems[:3]), numbers, "THM",
                    TRIE)
    return _rec("pbne.belief_consistency", "pass", f"Bayes' rule step by step equals the "
                f"closed form at all {len(beliefs)} reached information sets", numbers, "THM",
                TRIE)


def _game_value(instance: Instance, v: Values, mode: NumberMode,
                horizon: int | None) -> CheckRecord:
    sv = structured_value(instance, horizon)
    h = "inf" if horizon is None else str(horizon)
    numbers: dict[str, Number | None] = {"V_H": sv.value, "U": v.U, "dp_steps": sv.steps}
    if mode.equal(sv.value, v.U):
        return _rec("game.value", "pass", f"V_H (H = {h}) = {show(sv.value)} = U by the "
                    f"three-field DP ({sv.steps} steps, {sv.arithmetic})", numbers, "DP", DP)
    return _rec("game.value", "fail", f"V_H (H = {h}) = {show(sv.value)} but U = {show(v.U)}",
                numbers, "DP", DP)


def _telescoping(instance: Instance, roles: Roles, trie: Trie, mode: NumberMode) -> CheckRecord:
    c_of = roles.d1
    bad = 0
    done = [False] * trie.size
    for along in sorted(trie.ids, key=len, reverse=True):  # each prefix along a longest walk
        if len(along) < 2 or done[along[-1]]:
            continue
        p = [trie.node[i] for i in along]
        sig = sigma_along(instance, roles, ProgressRule(roles.g1), p)
        total: Number = 0
        c0 = c = c_of[p[0]]
        steps = zip(step_weights(instance, p), sig, strict=True)
        if mode.exact:  # EXACT's at_most / equal are <= / ==: the comparisons inline
            for t, (w, s) in enumerate(steps, start=1):
                total += w * s
                c = min(c, c_of[p[t]])
                done[along[t]] = True
                bad += (not 0 <= s <= 1) + (total != c0 - c)
            continue
        for t, (w, s) in enumerate(steps, start=1):
            total += w * s
            c = min(c, c_of[p[t]])
            done[along[t]] = True
            if not (mode.at_most(0, s) and mode.at_most(s, 1)):
                bad += 1
            if not mode.equal(total, c_of[p[0]] - c):
                bad += 1
    numbers: dict[str, Number | None] = {"prefixes": trie.size, "violations": bad}
    status: Status = "fail" if bad else "pass"
    return _rec("lemma.TEL.telescoping", status, f"Σ w σ* = c_0 − c_t and σ* ∈ [0, 1] on all "
                f"{trie.size} prefixes of the profile's walks" if not bad else
                f"{bad} violation(s) of the telescoping identity", numbers, "TEL",
                "the profile's prefixes (a consistency check of σ*)")


def _l1(instance: Instance, roles: Roles, profile: Profile, mode: NumberMode,
        mins: WalkMinima) -> CheckRecord:
    sigma_star = ProgressRule(roles.g1)
    c0 = roles.d1[instance.start]
    problems = []
    for mw in (*profile.primary, *profile.secondary):
        cost = evaluate_walk(instance, roles, sigma_star, mw.walk)
        if mode.less_than(cost, c0):
            problems.append(f"{show_walk(instance, mw.walk)} costs {show(cost)} < d(s0,g1)")
        if mw.walk[-1] == roles.g1 and not mode.equal(cost, c0):
            problems.append(f"{show_walk(instance, mw.walk)} ends at g1 but costs {show(cost)}")
    if not mode.equal(mins.same, c0):
        problems.append(f"the minimum over all walks is {show(mins.same)}")
    numbers: dict[str, Number | None] = {"d_s0_g1": c0, "min_over_walks": mins.same}
    if problems:
        return _rec("lemma.L1.lower_bound", "fail", "; ".join(problems[:3]), numbers, "L1",
                    WALKBR)
    return _rec("lemma.L1.lower_bound", "pass", f"against σ* the primary's minimum over all "
                f"walks is d(s0,g1) = {show(c0)}; every profile walk costs ≥ it, exactly it "
                f"when ending at g1", numbers, "L1", WALKBR)


def evaluate_walk(instance: Instance, roles: Roles, rule: ProgressRule,
                  walk: tuple[int, ...]) -> Number:
    """The primary type's cost of ``walk`` against ``rule``.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> inst = triangle()
    >>> r = inst.roles()
    >>> evaluate_walk(inst, r, ProgressRule(r.g1), (0, 2))    # s -> g2: 2·(1/2) + d(g2,g1)
    3
    """
    return walk_cost(instance, roles, rule, walk, 1)


def _l2(instance: Instance, profile: Profile) -> CheckRecord:
    loops = [mw for mw in profile.secondary
             if mw.probability > 0 and len(set(mw.walk)) < len(mw.walk)]
    numbers: dict[str, Number | None] = {"revisiting_walks": len(loops)}
    if loops:
        return _rec("lemma.L2.no_revisits", "fail", f"the secondary plays "
                    f"{show_walk(instance, loops[0].walk)}, which revisits a node (Lemma 2: "
                    f"removing the loop is strictly cheaper)", numbers, "L2",
                    "the profile's secondary walks")
    return _rec("lemma.L2.no_revisits", "pass", "every secondary walk played is simple",
                numbers, "L2", "the profile's secondary walks")


def _xi2(instance: Instance, roles: Roles, mode: NumberMode, mins: WalkMinima) -> CheckRecord:
    s0 = instance.start
    m = split_minimum(instance, roles.g1, roles.g2)
    expect = m - roles.d1[s0]
    numbers: dict[str, Number | None] = {"M": m, "M_minus_d": expect,
                                         "min_over_walks": mins.other}
    if mode.equal(expect, mins.other):
        return _rec("lemma.XI2.secondary_value", "pass", f"against σ* the secondary's minimum "
                    f"over all walks (goal-avoiding distances) = M − d(s0,g1) = {show(expect)} "
                    f"(plain distances)", numbers, "XI2", WALKBR)
    return _rec("lemma.XI2.secondary_value", "fail", f"minimum over all walks "
                f"{show(mins.other)} ≠ M − d(s0,g1) = {show(expect)}", numbers, "XI2", WALKBR)


def _l5(instance: Instance, profile: Profile, roles: Roles, trie: Trie,
        beliefs: dict[int, Fraction], mode: NumberMode) -> CheckRecord:
    cid = "lemma.L5.induced_beliefs"
    sec = [w for w in profile.secondary if w.probability > 0]
    if len(sec) != 1:
        return _rec(cid, "skipped", "not applicable: the secondary type mixes several walks, "
                    "Lemma 5 is about the paper's deterministic ξ²", None, "L5", TRIE)
    xi2 = sec[0].walk
    t1, t2, T = phases_of(sigma_along(instance, roles, ProgressRule(roles.g1), xi2),
                          mode).as_tuple()
    problems = []
    ids = trie.find_along(xi2)
    along = set(ids)
    for t in range(len(xi2)):
        want = roles.b1 if t <= t1 else (HALF if t <= t2 else Fraction(0))
        got = beliefs[ids[t]]
        if got != want:
            phase = "I" if t <= t1 else ("II" if t <= t2 else "III")
            problems.append(f"at step {t} of ξ² (phase {phase}) the belief is {show(got)}, "
                            f"not {show(want)}")
    off = [p for p in beliefs if p not in along]
    numbers: dict[str, Number | None] = {"t_I": t1, "t_II": t2, "T": T, "b1": roles.b1,
                                         "off_path_prefixes": len(off)}
    if problems:
        return _rec(cid, "fail", "; ".join(problems[:3]), numbers, "L5", TRIE)
    return _rec(cid, "pass", f"beliefs along ξ² are {show(roles.b1)} on phase I (t <= {t1}), "
                f"1/2 on phase II (t <= {t2}), 0 on phase III (t <= {T}); {OFF_XI2}", numbers,
                "L5", TRIE)
