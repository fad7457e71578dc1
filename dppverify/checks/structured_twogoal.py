"""The structured route's two-goal layer (N = 2): the checks that only the two-goal mathematics
has — the phases of σ* along ξ² (proofs/L5.md), the telescoping identity (proofs/TEL.md), the
lemmas L1, L2, XI2 and L5 in their polynomial forms — on the profile's walk trie, used by
the two-goal structured runners (:class:`dppverify.checks.structured.TwoGoalStructured`). The
lemma checks that need the walk tree (L3's and L4's random attackers with their LPs) are not
run on this route.
"""

from __future__ import annotations

from fractions import Fraction

from dppio.text import count
from dppverify.certificate import CheckRecord, Status
from dppverify.checks.lemmas import OFF_XI2
from dppverify.checks.structured_shared import structured_record as _rec
from dppverify.exact import Number
from dppverify.game.defender import sigma_along
from dppverify.game.evaluation import walk_cost
from dppverify.game.instance import Instance, Roles
from dppverify.game.profile import Profile, ProgressRule
from dppverify.game.step_weights import step_weights
from dppverify.numbers import NumberMode
from dppverify.structured.trie import WalkTrie
from dppverify.text import show, show_walk
from dppverify.twogoal.phases import phases_of
from dppverify.twogoal.progress_br import WalkMinima, split_minimum

__all__ = ["HALF", "TRIE", "WALKBR", "evaluate_walk", "l1_check", "l2_check", "l5_check",
           "phases_check", "telescoping_check", "xi2_check"]

HALF = Fraction(1, 2)
WALKBR = "relies on proofs/WALKBR.md"
TRIE = "on the prefixes of the profile's walks (proofs/L3.md)"


def phases_check(instance: Instance, profile: Profile, roles: Roles,
                 mode: NumberMode) -> CheckRecord:
    """``profile.phases``: the phases of σ* along the secondary's walk ξ² (proofs/L5.md), against
    those the profile claims.

    Examples
    --------
    >>> from tests.dppverify.checks.doctest_inputs import triangle_inputs
    >>> inst, r, prof, t, mins = triangle_inputs()
    >>> phases_check(inst, prof, r, inst.numbers).message
    'no phases claimed; recomputed t_I = 0, t_II = 1, T = 1'
    """
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


def telescoping_check(instance: Instance, roles: Roles, trie: WalkTrie,
                      mode: NumberMode) -> CheckRecord:
    """``lemma.TEL.telescoping``: ``Σ w σ* = c_0 − c_t`` and ``σ* ∈ [0, 1]`` on every prefix of
    ``trie`` (proofs/TEL.md).

    Examples
    --------
    >>> from tests.dppverify.checks.doctest_inputs import triangle_inputs
    >>> inst, r, prof, t, mins = triangle_inputs()
    >>> telescoping_check(inst, r, t, inst.numbers).status
    'pass'
    """
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
                f"{count(bad, 'violation')} of the telescoping identity", numbers, "TEL",
                "the profile's prefixes (a consistency check of σ*)")


def l1_check(instance: Instance, roles: Roles, profile: Profile, mode: NumberMode,
        mins: WalkMinima) -> CheckRecord:
    """``lemma.L1.lower_bound``: against σ* the primary's minimum over all walks is
    ``d(s0, g1)`` (proofs/L1.md), and every profile walk costs at least that.

    Examples
    --------
    >>> from tests.dppverify.checks.doctest_inputs import triangle_inputs
    >>> inst, r, prof, t, mins = triangle_inputs()
    >>> l1_check(inst, r, prof, inst.numbers, mins).status
    'pass'
    """
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


def l2_check(instance: Instance, profile: Profile) -> CheckRecord:
    """``lemma.L2.no_revisits``: every secondary walk played is simple (proofs/L2.md).

    Examples
    --------
    >>> from tests.dppverify.checks.doctest_inputs import triangle_inputs
    >>> inst, r, prof, t, mins = triangle_inputs()
    >>> l2_check(inst, prof).message
    'every secondary walk played is simple'
    """
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


def xi2_check(instance: Instance, roles: Roles, mode: NumberMode, mins: WalkMinima) -> CheckRecord:
    """``lemma.XI2.secondary_value``: against σ* the secondary's minimum over all walks is
    ``M − d(s0, g1)`` (proofs/XI2.md).

    Examples
    --------
    >>> from tests.dppverify.checks.doctest_inputs import triangle_inputs
    >>> inst, r, prof, t, mins = triangle_inputs()
    >>> xi2_check(inst, r, inst.numbers, mins).status
    'pass'
    """
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


def l5_check(instance: Instance, profile: Profile, roles: Roles, trie: WalkTrie,
        beliefs: dict[int, Fraction], mode: NumberMode) -> CheckRecord:
    """``lemma.L5.induced_beliefs``: the Bayes beliefs along ξ² by phase (proofs/L5.md);
    ``beliefs`` maps each reached prefix id of ``trie`` to the belief in the primary type.

    Examples
    --------
    >>> from tests.dppverify.checks.doctest_inputs import triangle_inputs
    >>> inst, r, prof, t, mins = triangle_inputs()
    >>> b = {i: r.b1 * m[0] / (r.b1 * m[0] + r.b2 * m[1]) for i, m in enumerate(t.masses)}
    >>> l5_check(inst, prof, r, t, b, inst.numbers).status
    'pass'
    """
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
