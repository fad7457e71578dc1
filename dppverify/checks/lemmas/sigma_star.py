"""The lemmas about σ* on the walk tree: ``lemma.TEL.telescoping``, ``lemma.L1.lower_bound``,
``lemma.L2.no_revisits``, ``lemma.XI2.secondary_value`` (proofs/TEL.md, L1.md, L2.md, XI2.md).

See :mod:`dppverify.checks.lemmas` for what each checks.
"""

from __future__ import annotations

from collections.abc import Sequence

from dppverify.certificate import CheckRecord
from dppverify.exact import Number
from dppverify.game.distances import dijkstra
from dppverify.text import show, show_walk
from dppverify.tree_route.best_response import attacker_best_response, leaf_totals
from dppverify.tree_route.context import Context
from dppverify.tree_route.tree import WalkTree, simple_mask


def telescoping(ctx: Context) -> CheckRecord:
    """``lemma.TEL.telescoping`` (proofs/TEL.md) on every prefix of the tree.

    Examples
    --------
    >>> from tests.dppverify.checks.doctest_inputs import triangle_context as context
    >>> r = telescoping(context())
    >>> r.status, dict(r.numbers)
    ('pass', {'prefixes': 3, 'sum_violations': 0, 'range_violations': 0})
    """
    tree, roles, mode = ctx.tree, ctx.roles, ctx.numbers
    d1 = roles.d1
    node = tree.node.tolist()
    parent = tree.parent.tolist()
    s1, weight = ctx.sigma_star.sigma1, tree.weight
    c: list[Number] = [d1[node[0]]] * tree.n_prefixes
    acc: list[Number] = [0] * tree.n_prefixes
    bad_sum = bad_range = 0
    for p in range(1, tree.n_prefixes):
        q = parent[p]
        c[p] = min(c[q], d1[node[p]])
        # the probability σ*(g1) times the step's weight, not σ*'s stored increment c_{t-1} − c_t
        taken = mode.product(weight[p], s1[p])
        acc[p] = acc[q] + taken
        if not mode.equal(acc[p], c[0] - c[p]):
            bad_sum += 1
        if not (mode.at_most(0, s1[p]) and mode.at_most(s1[p], 1)):
            bad_range += 1
    numbers: dict[str, Number | None] = {"prefixes": tree.n_prefixes,
                                         "sum_violations": bad_sum,
                                         "range_violations": bad_range}
    ok = bad_sum == 0 and bad_range == 0
    msg = (f"Σ w σ*(g1) = c_0 − c_t and σ* ∈ [0, 1] on all {tree.n_prefixes} prefixes"
           if ok else f"{bad_sum} prefixes break Σ w σ* = c_0 − c_t, {bad_range} have σ* "
                      f"outside [0, 1]")
    return CheckRecord("lemma.TEL.telescoping", "pass" if ok else "fail", msg, numbers, "TEL")


def _c_at_leaves(tree: WalkTree, d: Sequence[Number]) -> dict[int, tuple[Number, Number]]:
    """``(c_{T-1}, c_T)`` (running minimum of ``d`` before and at the last step) per leaf."""
    out = {}
    for p in tree.leaves().tolist():
        walk = tree.walk(p)
        before = min(d[v] for v in walk[:-1]) if len(walk) > 1 else d[walk[0]]
        out[p] = (before, min(before, d[walk[-1]]))
    return out


def l1_lower_bound(ctx: Context) -> CheckRecord:
    """``lemma.L1.lower_bound``: Lemma 1 and its equality case, over all walks of the tree.

    Examples
    --------
    On the triangle the primary pays ``d(s, g1) = 3`` against σ* on both walks: ``s -> g2``
    costs it 1 (σ* = 1/2 on a step of weight 2) plus ``d(g2, g1) = 2``.

    >>> from tests.dppverify.checks.doctest_inputs import triangle_context as context
    >>> r = l1_lower_bound(context())
    >>> r.status, r.numbers["d_s0_g1"], r.numbers["min_U1"], r.numbers["walks_to_g2_attaining"]
    ('pass', 3, 3, 1)
    """
    tree, roles, mode = ctx.tree, ctx.roles, ctx.numbers
    inst = ctx.instance
    d0 = roles.d1[inst.start]
    totals = leaf_totals(tree, roles, ctx.sigma_star, 1)
    br = ctx.best_response(ctx.sigma_star, 1)
    leaves = tree.leaves().tolist()
    cs = _c_at_leaves(tree, roles.d1)
    d21 = roles.d1[roles.g2]
    at_g1 = [p for p in leaves if int(tree.node[p]) == roles.g1]
    at_g2 = [p for p in leaves if int(tree.node[p]) == roles.g2]
    bad_g1 = [p for p in at_g1 if not mode.equal(totals[p], d0)]
    bad_g2 = [p for p in at_g2 if not mode.equal(totals[p], d0 - cs[p][1] + d21)
              or mode.less_than(totals[p], d0)]
    attain_g2 = [p for p in at_g2 if mode.equal(totals[p], d0)]
    minimum = min(totals[p] for p in leaves)
    numbers: dict[str, Number | None] = {"d_s0_g1": d0, "min_U1": minimum,
                                         "min_U1_backward": br.value, "walks_to_g1": len(at_g1),
                                         "walks_to_g2": len(at_g2),
                                         "walks_to_g2_attaining": len(attain_g2)}
    problems = []
    if not (mode.equal(minimum, d0) and mode.equal(br.value, d0)):
        problems.append(f"the minimum of U¹ is {show(minimum)} (backward induction "
                        f"{show(br.value)}), not d(s0,g1) = {show(d0)}")
    if bad_g1:
        problems.append(f"{len(bad_g1)} walks ending at g1 do not cost d(s0,g1), e.g. "
                        f"{show_walk(inst, tree.walk(bad_g1[0]))} costs {show(totals[bad_g1[0]])}")
    if bad_g2:
        problems.append(f"{len(bad_g2)} walks ending at g2 break d(s0,g1) − c_T + d(g2,g1) "
                        f"≥ d(s0,g1), e.g. {show_walk(inst, tree.walk(bad_g2[0]))}")
    if problems:
        return CheckRecord("lemma.L1.lower_bound", "fail", "; ".join(problems), numbers, "L1")
    extra = (f"; {len(attain_g2)} of the {len(at_g2)} walks ending at g2 also attain it "
             f"(exactly those with d(g2,g1) <= c_(T-1), proofs/L1.md)" if attain_g2 else
             f"; the {len(at_g2)} walks ending at g2 cost more")
    return CheckRecord("lemma.L1.lower_bound", "pass",
                       f"min over all {len(leaves)} walks of U¹ against σ* is d(s0,g1) = "
                       f"{show(d0)}, attained by all {len(at_g1)} walks ending at g1{extra}",
                       numbers, "L1")


def l2_no_revisits(ctx: Context) -> CheckRecord:
    """``lemma.L2.no_revisits``: Lemma 2 over all walks of the tree.

    Examples
    --------
    The triangle's tree has no revisiting walk (every neighbour of ``s`` is a goal):

    >>> from tests.dppverify.checks.doctest_inputs import triangle_context as context
    >>> r = l2_no_revisits(context())
    >>> r.status, r.numbers["min_U2_walks"], r.numbers["min_U2_paths"], r.numbers["walks"]
    ('pass', 1, 1, 2)
    >>> r.numbers["min_U2_revisiting"] is None
    True
    """
    tree, roles, mode = ctx.tree, ctx.roles, ctx.numbers
    totals = leaf_totals(tree, roles, ctx.sigma_star, 2)
    simple = simple_mask(tree)
    leaves = tree.leaves().tolist()
    m_all = min(totals[p] for p in leaves)
    simple_leaves = [p for p in leaves if simple[p]]
    m_simple = min(totals[p] for p in simple_leaves)
    non_simple = [totals[p] for p in leaves if not simple[p]]
    m_non = min(non_simple) if non_simple else None
    br_all = ctx.best_response(ctx.sigma_star, 2)
    br_simple = attacker_best_response(tree, roles, ctx.sigma_star, 2, allowed=simple)
    numbers: dict[str, Number | None] = {"min_U2_walks": m_all, "min_U2_paths": m_simple,
                                         "min_U2_revisiting": m_non, "walks": len(leaves),
                                         "paths": len(simple_leaves)}
    ok = (mode.equal(m_all, m_simple) and mode.equal(br_all.value, m_all)
          and mode.equal(br_simple.value, m_simple)
          and (m_non is None or mode.less_than(m_all, m_non)))
    if ok:
        tail = ("no walk of the tree revisits a node" if m_non is None else
                f"every walk that revisits a node costs more (at least {show(m_non)})")
        return CheckRecord("lemma.L2.no_revisits", "pass",
                           f"the secondary's best response over all {len(leaves)} walks "
                           f"({show(m_all)}) equals that over the {len(simple_leaves)} simple "
                           f"paths; {tail}", numbers, "L2")
    return CheckRecord("lemma.L2.no_revisits", "fail",
                       f"min over walks {show(m_all)}, over simple paths {show(m_simple)}, over "
                       f"revisiting walks {show(m_non)} (backward induction {show(br_all.value)}"
                       f" / {show(br_simple.value)})", numbers, "L2")


def xi2_secondary_value(ctx: Context) -> CheckRecord:
    """``lemma.XI2.secondary_value``: proofs/XI2.md's ``U²* = M − d(s0, g1)`` bounds the tree's min.

    Examples
    --------
    ``M = min_v d(s0, v) + d(v, g1) + d(v, g2) = 4`` (at ``v = g2``), so ``U²* = 4 − 3 = 1``:

    >>> from tests.dppverify.checks.doctest_inputs import triangle_context as context
    >>> r = xi2_secondary_value(context())
    >>> r.status, dict(r.numbers)
    ('pass', {'M': 4, 'U2_star': 1, 'min_U2_tree': 1})
    """
    inst, roles, mode = ctx.instance, ctx.roles, ctx.numbers
    d0 = dijkstra(inst.succ, inst.start)
    M = min(d0[v] + roles.d1[v] + roles.d2[v] for v in range(inst.n_nodes))
    u2_star = M - roles.d1[inst.start]
    u2_star = mode.convert(u2_star)
    br = ctx.best_response(ctx.sigma_star, 2)
    numbers: dict[str, Number | None] = {"M": M, "U2_star": u2_star, "min_U2_tree": br.value}
    if mode.less_than(br.value, u2_star):
        return CheckRecord("lemma.XI2.secondary_value", "fail",
                           f"the walk {show_walk(inst, br.walk)} costs the secondary "
                           f"{show(br.value)} < M − d(s0,g1) = {show(u2_star)}", numbers, "XI2")
    how = ("equals it" if mode.equal(br.value, u2_star) else
           f"exceeds it: an optimal path needs more than H = {ctx.tree.horizon} steps")
    return CheckRecord("lemma.XI2.secondary_value", "pass",
                       f"min over the tree of U² against σ* is {show(br.value)}; M − d(s0,g1) = "
                       f"{show(u2_star)} (M = {show(M)}); the tree's minimum {how}", numbers,
                       "XI2")
