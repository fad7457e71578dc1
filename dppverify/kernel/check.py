"""The kernel's decision: read the three documents, verify the witness, return one verdict
(proofs/KERNEL.md K.2, in its order)."""

from __future__ import annotations

from fractions import Fraction
from functools import cache
from itertools import compress, pairwise, repeat
from operator import lt, not_
from pathlib import Path
from typing import Any

from dppverify.kernel.defender import check_greedy
from dppverify.kernel.guarantee import GuaranteeRule
from dppverify.kernel.profile import Guarantee, read_profile, walk
from dppverify.kernel.reading import INF, Instance, labels, parse, read_instance, sha256
from dppverify.kernel.table import TableRule
from dppverify.kernel.verdict import BadInput, Beyond, Refuted, Stop, Undecided, Verdict

_KEYS = {"format", "instance_sha256", "profile_sha256", "denominator", "distances", "types",
         "guarantee", "counterexamples", "producer"}


def check(instance: bytes, profile: bytes, witness: bytes | dict[str, Any], *,
          base_dir: str | Path | None = None) -> Verdict:
    """Decide whether ``profile`` is a weak PBNE of the untruncated game ``instance``, from
    ``witness`` (the three documents' bytes, exactly as read, or the witness already parsed as
    JSON values; ``base_dir``: where a map instance's relative ``map`` path starts).

    Parameters
    ----------
    instance, profile : bytes
        The instance and the profile documents, exactly as read (their sha256 must be the
        witness's ``instance_sha256`` and ``profile_sha256``).
    witness : bytes or dict
        The ``dpp-witness/1`` document (``docs/formats.md`` §5), as bytes or parsed.
    base_dir : str or Path, optional
        Where a compact map instance's relative ``map`` path starts.

    Returns
    -------
    Verdict
        ``pass``, ``fail`` (with the counterexample the kernel verified), ``bad-input`` or
        ``undecided`` (the inequality that fails, or a game the kernel does not decide), with
        its one line; never raises on any input.

    Examples
    --------
    >>> inst = b'''{"graph": {"nodes": [{"id": "s"}, {"id": "a"}, {"id": "b"}],
    ...   "edges": [{"source": "s", "target": "a"}, {"source": "s", "target": "b"}]},
    ...   "start": "s", "goals": ["a", "b"], "prior": ["1/2", "1/2"]}'''
    >>> prof = b'''{"format": "dpp-ngoal-profile/1",
    ...   "attacker": [[{"path": ["s", "a"], "probability": 1}],
    ...                [{"path": ["s", "b"], "probability": 1}]],
    ...   "defender": {"rule": "table", "default": ["1/2", "1/2"], "entries": [
    ...       {"walk": ["s", "a"], "probabilities": [1, 0]},
    ...       {"walk": ["s", "b"], "probabilities": [0, 1]}]}}'''
    >>> import json
    >>> wit = json.dumps({"format": "dpp-witness/1", "instance_sha256": sha256(inst),
    ...     "profile_sha256": sha256(prof), "denominator": 2,
    ...     "distances": [[2, 0, 4], [2, 4, 0]],
    ...     "types": [{"trie": [2, 0, 4], "exit": [1, 0, 4]},
    ...               {"trie": [2, 4, 0], "exit": [1, 4, 0]}]})
    >>> check(inst, prof, wit.encode())
    Verdict(status='pass', message='PASS: a weak PBNE of the untruncated game (2 types, 3 \
nodes, trie of 3 prefixes, 2 reached prefixes)', applicable=True)
    >>> check(inst, prof, wit.replace('[1, 0, 4]', '[2, 0, 4]').encode()).message
    'type 0, node "s": E(x) <= w·q + E(u) fails on an arc'
    """
    try:
        return _decide(instance, profile, witness, None if base_dir is None else Path(base_dir))
    except Stop as stop:
        return Verdict(stop.status, str(stop), not isinstance(stop, Beyond))


def _decide(instance: bytes, profile: bytes, witness: bytes | dict[str, Any],
            base_dir: Path | None) -> Verdict:
    inst = read_instance(instance, base_dir)
    wit = witness if isinstance(witness, dict) else parse(witness, "witness")
    if type(wit) is not dict or wit.get("format") != "dpp-witness/1":
        raise BadInput("witness: not a dpp-witness/1 document")
    if set(wit) - _KEYS:
        raise BadInput(f"witness: keys not in the format: {sorted(set(wit) - _KEYS)[:5]}")
    for key, data in (("instance", instance), ("profile", profile)):
        if wit.get(f"{key}_sha256") != sha256(data):
            raise BadInput(f"witness: {key}_sha256 is not the sha256 of this {key}'s bytes (a "
                           f"witness for another {key})")
    prof = read_profile(profile, inst)
    S, n, N, dists = wit.get("denominator"), inst.graph.n, len(inst.goals), wit.get("distances")
    if type(S) is not int or S < 1 or type(dists) is not list or len(dists) != N:
        raise BadInput(f"witness: needs a positive integer denominator and {N} distance lists")
    D = [labels(xs, n, f"distances[{j}]") for j, xs in enumerate(dists)]
    for j, g in enumerate(inst.goals):
        _check_distances(inst, j, g, D[j], S)
    if any(d[v] == INF for d in D for v in (inst.start, *inst.goals)):
        raise BadInput("a goal is unreachable from the start or from another goal: the "
                       "instance is not a valid game")
    inst.alive = alive = list(map(lt, map(min, *D), repeat(INF)))
    dead = list(compress(range(n), map(not_, alive)))
    rule: TableRule | GuaranteeRule
    if isinstance(prof.rule, Guarantee):
        if set(wit) & {"types", "counterexamples"}:
            raise BadInput("witness: the guarantee rule's witness has \"guarantee\" only")
        rule = GuaranteeRule(inst, prof.rule, D, S, wit.get("guarantee"), prof.mixtures, dead)
    elif "guarantee" in wit:
        raise BadInput("witness: a table Defender's witness has \"types\", not \"guarantee\"")
    else:
        rule = TableRule(inst, prof.rule, D, S)
    evaluate = cache(lambda w: _evaluate(inst, rule, w, D, S))
    U = [sum((p * evaluate(w)[1][t] for w, p in mix), Fraction(0))
         for t, mix in enumerate(prof.mixtures)]
    reached = check_greedy(inst, prof.mixtures, lambda w: evaluate(w)[0])
    extra = wit.get("counterexamples", [])
    for k, c in enumerate(extra if type(extra) is list else [None]):
        t = c.get("type") if type(c) is dict else None
        try:
            if type(t) is not int or not 0 <= t < N:
                raise Refuted(f"profile: counterexamples[{k}] needs a \"type\" 0..{N - 1}")
            _sig, cost = _evaluate(inst, rule, walk(inst, c.get("walk"), f"counterexamples[{k}]"
                                                    ".walk", True), D, S)
        except Refuted as exc:  # a malformed counterexample is the witness's defect
            raise BadInput(f"witness: {str(exc)[9:]}") from None
        if cost[t] < U[t]:
            raise Refuted(f"type {t}: the walk of counterexamples[{k}] costs "
                          f"{Fraction(cost[t], S)} < U = {U[t] / S}: regret > 0")
    types = wit.get("types", [None] * N if isinstance(rule, GuaranteeRule) else None)
    if type(types) is not list or len(types) != N:
        raise BadInput(f"witness: types must be a list of {N} records")
    for t in range(N):
        rule.check_type(t, types[t], dead, U[t])
    what = f"trie of {len(rule.node)} prefixes" if isinstance(rule, TableRule) else "guarantee rule"
    return Verdict("pass", f"PASS: a weak PBNE of the untruncated game ({N} types, {n} nodes, "
                           f"{what}, {reached} reached prefixes)")


def _check_distances(inst: Instance, j: int, g: int, D: list[Any], S: int) -> None:
    """K.1: ``D(g) = 0`` and ``D(v) = min over arcs of w + D(u)`` elsewhere."""
    expect = inst.graph.relax(D, Fraction(S), INF)
    expect[g] = 0
    if expect != D:
        what = "D(g) = 0" if (v := next(v for v in range(len(D)) if expect[v] != D[v])) == g \
            else "D(v) = min over arcs (w + D(u))"
        raise Undecided(f"distances[{j}] (to {inst.show(g)}) at node {inst.show(v)}: {what} "
                        "fails: not the exact distances")


def _evaluate(inst: Instance, rule: TableRule | GuaranteeRule, w: tuple[int, ...],
              D: list[list[Any]], S: int) -> tuple[list[Any], list[Any]]:
    """Each step's costs ``S·w·σ(θ)`` along the walk ``w``, and each type's ``S·J_θ(w)``."""
    mem, steps = rule.start(), []
    for v, u in pairwise(w):
        mem, s = rule.step(mem, v, u, inst.graph.weight(v, u))  # type: ignore[arg-type]
        if s is None:
            shown = ", ".join(inst.show(x) for x in w)
            raise Refuted(f"profile: the table Defender is undefined on the walk [{shown}] "
                          "(no entry, no default)")
        steps.append(s)
    return steps, [sum(c) + d[w[-1]] for c, d in zip(zip(*steps, strict=True) if steps else
                                                     [()] * len(D), D, strict=True)]
