"""Untrusted glue of the extracted Coq kernel: the three JSON documents as the token stream that
``driver.ml`` reads (standard library only).

It decides nothing the Coq kernel decides. It reads the documents' *structure* the way
``dppverify/kernel`` reads it (JSON with exact numbers, node ids resolved to node indices, an id
that is no node becomes the index ``n``, the instance's edges as sorted adjacency lists, the
witness's header and hashes) and, where that structure is broken, it stops with the status the
Python kernel's reader gives (a one-line ``VERDICT <status>`` stream). Every semantic condition
(walks along arcs, probabilities and distributions, duplicates, list lengths, every inequality)
is left to the extracted ``Kernel.decide``.

Usage: ``python3 translate.py INSTANCE PROFILE WITNESS > tokens`` (or :func:`tokens` on bytes).
Integers are written as signed binary numerals (``0``, ``+101``, ``-11``), so the OCaml driver
builds Coq's binary numbers without arithmetic of its own.
"""

from __future__ import annotations

import hashlib
import json
import sys
from fractions import Fraction
from typing import Any

__all__ = ["tokens"]

_WITNESS_KEYS = {"format", "instance_sha256", "profile_sha256", "denominator", "distances",
                 "types", "guarantee", "counterexamples", "producer"}


class _Stop(Exception):
    def __init__(self, status: str) -> None:
        super().__init__(status)
        self.status = status


def _parse(data: bytes) -> Any:
    try:
        return json.loads(data, parse_float=Fraction, parse_int=int,
                          parse_constant=lambda name: (_ for _ in ()).throw(ValueError(name)))
    except (ValueError, RecursionError):
        raise _Stop("bad-input") from None


def _number(x: Any) -> Fraction | None:
    if type(x) is int or type(x) is Fraction:
        return Fraction(x)
    if type(x) is str and len(x) <= 1000:
        try:
            return Fraction(x)
        except (ValueError, ZeroDivisionError):
            return None
    return None


def _key(x: Any) -> Any:
    if type(x) in (str, int):
        return x
    if type(x) is Fraction:
        return int(x) if x.denominator == 1 else x
    if type(x) is list:
        out = tuple(_key(y) for y in x)
        return None if None in out else out
    return None


def _z(x: int) -> str:
    return "0" if x == 0 else ("+" if x > 0 else "-") + format(abs(x), "b")


def _q(x: Fraction) -> str:
    return f"{_z(x.numerator)} {_z(x.denominator)}"


class _Out:
    def __init__(self) -> None:
        self.parts: list[str] = []

    def add(self, *xs: Any) -> None:
        self.parts.extend(str(x) for x in xs)


def _instance(doc: Any, out: _Out) -> tuple[dict[Any, int], int, list[int]]:
    if type(doc) is not dict:
        raise _Stop("bad-input")
    if doc.get("format") == "dpp-map-instance/1":
        raise _Stop("not-translated")
    if doc.get("numbers", "exact") != "exact":
        raise _Stop("undecided")
    g = doc.get("graph")
    if type(g) is not dict or g.get("multigraph", False) or \
            type(g.get("directed", False)) is not bool:
        raise _Stop("bad-input")
    nodes, edges = g.get("nodes"), g.get("edges", g.get("links"))
    if type(nodes) is not list or type(edges) is not list:
        raise _Stop("bad-input")
    ids = [_key(nd.get("id")) if type(nd) is dict else None for nd in nodes]
    index = {x: i for i, x in enumerate(ids)}
    if None in index or len(index) < len(ids):
        raise _Stop("bad-input")
    adj: list[dict[int, Fraction]] = [{} for _ in ids]
    for e in edges:
        u = index.get(_key(e.get("source"))) if type(e) is dict else None
        v = index.get(_key(e.get("target"))) if type(e) is dict else None
        w = _number(e.get("weight", 1)) if type(e) is dict else None
        if u is None or v is None or w is None or w <= 0:
            raise _Stop("bad-input")
        for a, b in ((u, v),) if g.get("directed", False) or u == v else ((u, v), (v, u)):
            if b in adj[a]:
                raise _Stop("bad-input")
            adj[a][b] = w
    n = len(ids)
    out.add(n)
    for row in adj:
        out.add(len(row))
        for u, w in sorted(row.items()):
            out.add(u, _q(w))

    def node(raw: Any) -> int:
        k = _key(raw)
        if k is None or k not in index:
            raise _Stop("bad-input")
        return index[k]
    start = node(doc.get("start"))
    raw = doc.get("goals")
    if not (type(raw) is list and 2 <= len(raw) <= 64):
        raise _Stop("bad-input")
    goals = [node(x) for x in raw]
    if len(set(goals)) < len(goals):
        raise _Stop("bad-input")
    prior = doc.get("prior")
    p = [_number(x) for x in prior] if type(prior) is list else []
    if len(p) != len(goals) or None in p or not all(0 < x < 1 for x in p) or sum(p) != 1:  # type: ignore[operator, arg-type]
        raise _Stop("bad-input")
    out.add(start, len(goals), *goals, len(p), *(_q(x) for x in p))  # type: ignore[arg-type]
    return index, n, goals


def _walk(raw: Any, index: dict[Any, int], n: int, out: _Out) -> None:
    """A walk: its node indices (``n`` for an id that is no node), or refuted when not a list."""
    if type(raw) is not list:
        raise _Stop("refuted")
    out.add(len(raw), *(index.get(_key(x), n) if _key(x) is not None else n for x in raw))


def _mixture(raw: Any, key: str, index: dict[Any, int], n: int, out: _Out) -> None:
    if type(raw) is not list:
        raise _Stop("refuted")
    out.add(len(raw))
    for e in raw:
        p = _number(e.get("probability")) if type(e) is dict else None
        if p is None:
            raise _Stop("refuted")
        _walk(e.get(key), index, n, out)
        out.add(_q(p))


def _numbers(raw: Any, out: _Out) -> None:
    if type(raw) is not list:
        raise _Stop("refuted")
    xs = [_number(x) for x in raw]
    if None in xs:
        raise _Stop("refuted")
    out.add(len(xs), *(_q(x) for x in xs))  # type: ignore[arg-type]


def _profile(doc: Any, index: dict[Any, int], n: int, goals: list[int], out: _Out) -> None:
    fmt = doc.get("format") if type(doc) is dict else None
    N = len(goals)
    if fmt == "dpp-ngoal-profile/1":
        out.add("N")
        if "goals" in doc:
            gs = doc["goals"] if type(doc["goals"]) is list and doc["goals"] else [None]
            out.add(1, len(gs), *(index.get(_key(x), n) if _key(x) is not None else n for x in gs))
        else:
            out.add(0)
        att = doc.get("attacker")
        if type(att) is not list:
            raise _Stop("refuted")
        out.add(len(att))
        for m in att:
            if type(m) is not list or not m:
                raise _Stop("refuted")
            _mixture(m, "path", index, n, out)
        d = doc.get("defender")
        if type(d) is dict and d.get("rule") == "guarantee":
            h = [_number(x) for x in d["h"]] if type(d.get("h")) is list else []
            if len(h) != N or None in h:
                raise _Stop("refuted")
            extras = d.get("normals", [])
            ok = type(extras) is list and len(extras) <= 64 and all(
                type(a) is list and len(a) == N and all(type(x) is int and 0 <= x <= 16 for x in a)
                and any(x > 1 for x in a) for a in extras) and \
                len(set(map(tuple, extras))) == len(extras)
            if not ok or set(d) - {"rule", "h", "normals"}:
                raise _Stop("bad-input")
            out.add("G", len(h), *(_q(x) for x in h), len(extras))  # type: ignore[arg-type]
            for a in extras:
                out.add(len(a), *a)
            return
        if type(d) is not dict or d.get("rule") != "table" or \
                type(d.get("entries", [])) is not list:
            raise _Stop("refuted")
        es = d.get("entries", [])
        out.add("T", len(es))
        for e in es:
            _walk(e.get("walk") if type(e) is dict else None, index, n, out)
            _numbers(e.get("probabilities"), out)
        if d.get("default") is None:
            out.add("0")
        else:
            out.add("D")
            _numbers(d["default"], out)
        return
    if fmt != "dpp-profile/1" or N != 2:
        raise _Stop("bad-input")
    out.add("2")
    gs = doc.get("goals")
    for k in ("primary", "secondary"):
        x = _key(gs.get(k)) if type(gs) is dict else None
        out.add(index.get(x, n) if x is not None else n)
    att = doc.get("attacker")
    att = att if type(att) is dict else {}
    for k in ("primary", "secondary"):
        m = att.get(k)
        if type(m) is not list or not m:
            raise _Stop("refuted")
        _mixture(m, "path", index, n, out)
    d = doc.get("defender")
    x = _key(d.get("goal")) if type(d) is dict else None
    out.add(index.get(x, n) if x is not None else n)
    rule = d.get("rule") if type(d) is dict else None
    if rule == "progress":
        out.add("P")
    elif rule == "table":
        es = d.get("entries", [])
        if type(es) is not list:
            raise _Stop("refuted")
        out.add("T", len(es))
        for e in es:
            _walk(e.get("walk") if type(e) is dict else None, index, n, out)
            p = _number(e.get("probability")) if type(e) is dict else None
            if p is None:
                raise _Stop("refuted")
            out.add(_q(p))
        default = d.get("default")
        if default is None:
            out.add("0")
        elif default == "progress":
            out.add("P")
        else:
            p = _number(default)
            if p is None:
                raise _Stop("refuted")
            out.add("D", _q(p))
    else:
        out.add("O")


def _int_list(xs: Any) -> list[Any] | None:
    if type(xs) is list and set(map(type, xs)) <= {int, type(None)}:
        return xs
    return None


def _labels(rec: dict[str, Any], key: str, out: _Out) -> None:
    if key not in rec:
        out.add("-")
        return
    xs = _int_list(rec[key])
    if xs is None:
        out.add("!")
    else:
        out.add("+", len(xs), *("_" if x is None else _z(x) for x in xs))


def _nums(raw: Any, out: _Out) -> None:
    """A list of exact numbers (``_`` where an entry is none), or ``!`` when not a list."""
    if type(raw) is not list:
        out.add("!")
        return
    out.add("+", len(raw))
    for x in raw:
        v = _number(x)
        out.add("_" if v is None else _q(v))


def _guarantee(g: Any, out: _Out) -> None:
    if type(g) is not dict or set(g) - {"m", "covers", "steps"} or type(g.get("m")) is not list:
        out.add("!")
        return
    out.add("+", len(g["m"]))
    for xs in g["m"]:
        ys = _int_list(xs)
        if ys is None:
            out.add("!")
        else:
            out.add("+", len(ys), *("_" if x is None else _z(x) for x in ys))
    covers = g.get("covers", [])
    covers = covers if type(covers) is list else [None]
    out.add(len(covers))
    for c in covers:
        _nums(c, out)
    steps = g.get("steps")
    if type(steps) is not list:
        out.add("!")
        return
    out.add("+", len(steps))
    for rec in steps:
        rec = rec if type(rec) is dict else {}
        _nums(rec.get("sigma"), out)
        duals = rec.get("duals")
        if type(duals) is not list:
            out.add("!")
            continue
        out.add("+", len(duals))
        for d in duals:
            d = d if type(d) is dict else {}
            _nums(d.get("y"), out)
            _nums(d.get("fix"), out)
            z = _number(d.get("z"))
            out.add("_" if z is None else _q(z))


def _witness(wit: dict[str, Any], index: dict[Any, int], n: int, N: int, out: _Out) -> None:
    S = wit.get("denominator")
    out.add(_z(S) if type(S) is int else "0")
    D = wit.get("distances")
    lists = [_int_list(xs) for xs in D] if type(D) is list else [None]
    if None in lists:
        out.add(0)
    else:
        out.add(1, len(lists))
        for xs in lists:
            assert xs is not None
            out.add(len(xs), *("_" if x is None else _z(x) for x in xs))
    extra = wit.get("counterexamples", [])
    extra = extra if type(extra) is list else [None]
    out.add(len(extra))
    for c in extra:
        t = c.get("type") if type(c) is dict else None
        out.add(t if type(t) is int and 0 <= t < N else N)
        w = c.get("walk") if type(c) is dict else None
        if type(w) is list:
            out.add(len(w), *(index.get(_key(x), n) if _key(x) is not None else n for x in w))
        else:
            out.add(1, n)
    types = wit.get("types")
    if type(types) is not list:
        out.add(0)
    else:
        out.add(1, len(types))
        for rec in types:
            if type(rec) is not dict:
                out.add(0, "-", "-", "-", "-")
                continue
            out.add(1 if set(rec) <= {"trie", "exit", "P", "Q"} else 0)
            for key in ("trie", "exit", "P", "Q"):
                _labels(rec, key, out)
    out.add(int("types" in wit), int("counterexamples" in wit))
    if "guarantee" in wit:
        _guarantee(wit["guarantee"], out)
    else:
        out.add("-")


def tokens(instance: bytes, profile: bytes, witness: bytes) -> str:
    """The token stream of the three documents (``VERDICT <status>`` where the reading stops).

    Examples
    --------
    >>> tokens(b"[", b"{}", b"{}")
    'VERDICT bad-input'
    """
    out = _Out()
    try:
        index, n, goals = _instance(_parse(instance), out)
        wit = _parse(witness)
        if type(wit) is not dict or wit.get("format") != "dpp-witness/1" or \
                set(wit) - _WITNESS_KEYS:
            raise _Stop("bad-input")
        for key, data in (("instance", instance), ("profile", profile)):
            if wit.get(f"{key}_sha256") != hashlib.sha256(data).hexdigest():
                raise _Stop("bad-input")
        _profile(_parse(profile), index, n, goals, out)
        _witness(wit, index, n, len(goals), out)
    except _Stop as stop:
        return f"VERDICT {stop.status}"
    return " ".join(out.parts)


if __name__ == "__main__":
    docs = []
    for name in sys.argv[1:4]:
        with open(name, "rb") as f:
            docs.append(f.read())
    sys.stdout.write(tokens(*docs) + "\n")
