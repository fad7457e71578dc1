"""Certificates: one record per check, and the ``dpp-certificate/1`` JSON form.

``docs/formats.md`` §3. Exact numbers are written as ``"p/q"`` strings, LP values as JSON
floats; :meth:`Certificate.from_json` reads them back (strings to exact rationals).
"""

from __future__ import annotations

import dataclasses
import json
from collections.abc import Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from types import MappingProxyType
from typing import Any, Literal, cast

from dppio.limits import check_numeral, check_rational
from dppverify.errors import CertificateError
from dppverify.exact import Number, format_number, normalize
from dppverify.exploitability import Exploitability, exploitability_of
from dppverify.limits import MAX_HORIZON
from dppverify.registry import KINDS, Kind, kind_of

__all__ = ["CERTIFICATE_FORMAT", "STATUSES", "Certificate", "CheckRecord", "Status", "Verdict"]

CERTIFICATE_FORMAT = "dpp-certificate/1"

Status = Literal["pass", "fail", "error", "skipped"]
Verdict = Literal["pass", "fail", "error", "incomplete"]
STATUSES: tuple[Status, ...] = ("pass", "fail", "error", "skipped")

NumberEntry = Number | None


@dataclass(frozen=True)
class CheckRecord:
    """The outcome of one check.

    Attributes
    ----------
    id : str
        Stable check id (``dppverify/checks.md``).
    status : {"pass", "fail", "error", "skipped"}
        ``fail`` refutes the profile (or a lemma on this instance); ``error`` means the check
        could not be carried out (e.g. an LP did not solve); ``skipped`` means it does not
        apply or depends on a failed check.
    message : str
        One line for humans.
    numbers : Mapping
        Exact numbers (``int``/``Fraction``), LP values (``float``) or None.
    proof : str or None
        The proof file id in ``proofs/`` that the check tests (TEL, L1, …).
    route : str or None
        ``"tree"`` or ``"structured"``: the route that computed the record (None in
        certificates written before routes existed).
    relies_on : str or None
        What the record's computation trusts, e.g. ``"relies on proofs/WALKBR.md"``.
    """

    id: str
    status: Status
    message: str
    numbers: Mapping[str, NumberEntry] = field(default_factory=dict)
    proof: str | None = None
    route: str | None = None
    relies_on: str | None = None

    def __post_init__(self) -> None:
        if self.status not in STATUSES:
            raise CertificateError(f"check {self.id}: unknown status {self.status!r}")
        object.__setattr__(self, "numbers", MappingProxyType(dict(self.numbers)))

    @property
    def passed(self) -> bool:
        """True when the status is ``pass``."""
        return self.status == "pass"

    @property
    def kind(self) -> Kind:
        """``check`` (evidence) or ``consistency`` (the checker's own computations compared),
        from the registry (:func:`~dppverify.registry.kind_of`)."""
        return kind_of(self.id)

    def to_json(self) -> dict[str, Any]:
        """The record as a JSON object (``kind`` is written for readers, never read back: it
        comes from the registry)."""
        doc: dict[str, Any] = {"id": self.id, "kind": self.kind, "status": self.status,
                               "message": self.message,
                               "numbers": {k: _write_number(k, v) for k, v in self.numbers.items()}}
        if self.proof is not None:
            doc["proof"] = self.proof
        if self.route is not None:
            doc["route"] = self.route
        if self.relies_on is not None:
            doc["relies_on"] = self.relies_on
        return doc

    @classmethod
    def from_json(cls, doc: Any) -> CheckRecord:
        """Read a record written by :meth:`to_json`."""
        if not isinstance(doc, Mapping):
            raise CertificateError("a check record must be a JSON object")
        try:
            numbers = {str(k): _read_number(v) for k, v in dict(doc.get("numbers", {})).items()}
            status = doc["status"]
            if status not in STATUSES:
                raise CertificateError(f"check {doc.get('id')!r}: unknown status {status!r}")
            proof, route, relies = doc.get("proof"), doc.get("route"), doc.get("relies_on")
            return cls(id=str(doc["id"]), status=cast(Status, status),
                       message=str(doc.get("message", "")), numbers=numbers,
                       proof=None if proof is None else str(proof),
                       route=None if route is None else str(route),
                       relies_on=None if relies is None else str(relies))
        except KeyError as exc:
            raise CertificateError(f"check record is missing {exc}") from None
        except (TypeError, ValueError, ZeroDivisionError) as exc:
            raise CertificateError(f"malformed check record: {exc}") from None


COUNT_KEYS = frozenset({
    "H", "T", "t_I", "t_II", "seed", "defects", "primary_walks", "secondary_walks", "walks",
    "paths", "prefixes", "infosets", "at_one_half", "violations", "mismatches",
    "sum_violations", "range_violations", "walks_to_g1", "walks_to_g2",
    "walks_to_g2_attaining", "attackers", "strict_infosets_checked", "primary_strategies",
    "off_path_prefixes"})
"""Numbers that count something (walks, prefixes, steps, seeds): JSON integers in a
certificate. Every other exact number is a ``"p/q"`` string, even when it is an integer."""


def _write_number(key: str, v: NumberEntry) -> str | float | int | None:
    if key in COUNT_KEYS and v is not None and not isinstance(v, float):
        f = Fraction(v)
        if f.denominator == 1:
            return int(f)
    return format_number(v)


def _read_number(v: Any) -> NumberEntry:
    """A number of a check record, within the limits of :mod:`dppio.limits` (a numeral such
    as ``"1e999999999"`` is refused before it is expanded)."""
    if v is None or isinstance(v, float):
        return v
    if isinstance(v, bool):
        raise ValueError(f"not a number: {v!r}")
    if isinstance(v, int | Fraction):
        check_rational(v, where="number", error=ValueError)
        return normalize(Fraction(v))
    if isinstance(v, str):
        if v in ("inf", "-inf", "nan"):
            return float(v)
        check_numeral(v, where="number", error=ValueError)
        f = Fraction(v)
        check_rational(f, where="number", error=ValueError)
        return normalize(f)
    raise ValueError(f"not a number: {v!r}")


def _read_count(v: Any, what: str, limit: int = 10**18, low: int = 0) -> int:
    """An integer field of a certificate (horizon, seed, tree sizes) from ``low`` to
    ``limit``."""
    if isinstance(v, bool) or not isinstance(v, int) or not low <= v <= limit:
        raise ValueError(f"{what} must be an integer from {low} to {limit}, got {str(v)[:40]}")
    return v


def verdict_of(checks: tuple[CheckRecord, ...]) -> Verdict:
    """Over the records of kind ``check`` and ``consistency``: ``fail`` if any failed, else
    ``error`` if any errored, else ``incomplete`` if any was skipped, else ``pass``.

    Records of kind ``fact`` (the paper's lemmas, "is this the paper's construction") are
    reported beside the verdict and never decide it
    (:data:`~dppverify.registry.CHECKS`).

    Examples
    --------
    >>> verdict_of((CheckRecord("a", "pass", ""), CheckRecord("b", "skipped", "")))
    'incomplete'
    >>> verdict_of((CheckRecord("value.U", "pass", ""),
    ...             CheckRecord("lemma.L5.induced_beliefs", "fail", "belief 1/9, not 0")))
    'pass'
    """
    statuses = {c.status for c in checks if c.kind != "fact"}
    if "fail" in statuses:
        return "fail"
    if "error" in statuses:
        return "error"
    if "skipped" in statuses:
        return "incomplete"
    return "pass"


def merge_routes(tree: list[CheckRecord], structured: list[CheckRecord]) -> list[CheckRecord]:
    """``--route both``: one record per check of the tree route, merged with the structured one.

    Equal statuses give that record (``route="both"``); a route that skipped a check decided
    nothing, so the other route's record stands (its message says so); any other difference is
    an ``error`` record naming both. A check only the tree route ran keeps its record.

    Examples
    --------
    >>> t = [CheckRecord("a", "pass", "ok", route="tree"), CheckRecord("b", "pass", "ok"),
    ...      CheckRecord("c", "skipped", "no tree")]
    >>> s = [CheckRecord("a", "pass", "ok"), CheckRecord("b", "fail", "regret 1"),
    ...      CheckRecord("c", "pass", "fine")]
    >>> [(r.id, r.status, r.route) for r in merge_routes(t, s)]
    [('a', 'pass', 'both'), ('b', 'error', 'both'), ('c', 'pass', 'both')]
    >>> merge_routes(t, s)[2].message
    'fine (tree route: skipped, no tree)'
    """
    other = {r.id: r for r in structured}
    out = []
    for r in tree:
        s = other.get(r.id)
        if s is None:
            out.append(r)
            continue
        relies_on = f"tree: {r.relies_on}; structured: {s.relies_on}"
        if r.status == s.status:
            out.append(dataclasses.replace(r, route="both", relies_on=relies_on))
        elif "skipped" in (r.status, s.status):
            kept, gave, name = (s, r, "tree") if r.status == "skipped" else (r, s, "structured")
            out.append(dataclasses.replace(
                kept, route="both", relies_on=relies_on,
                message=f"{kept.message} ({name} route: skipped, {gave.message})"))
        else:
            out.append(CheckRecord(r.id, "error", f"the routes disagree: tree {r.status} "
                                   f"({r.message}); structured {s.status} ({s.message})",
                                   dict(r.numbers), r.proof, route="both", relies_on=relies_on))
    return out


@dataclass(frozen=True, eq=False)  # __eq__ below (by JSON); unhashable, as __eq__ implies
class Certificate:
    """The result of :func:`dppverify.certify`: every check with its outcome.

    Attributes
    ----------
    checks : tuple of CheckRecord
        In the documented order (``dppverify/checks.md``).
    horizon : int or None
        ``H`` of the truncated game the checks ran on; None for the untruncated game
        (structured route; written ``"inf"`` in JSON).
    exact : bool
        True when every exact number is an exact rational; False in float mode.
    tolerance : float or None
        Float mode's relative tolerance (None when exact).
    lp_solver, lp_tolerance
        The LP solver and the relative tolerance of LP-vs-exact agreement.
    prefixes, leaves : int
        Size of the walk tree.
    seed : int or None
        Seed of the random attackers of the L3/L4 checks.
    info : Mapping
        Free-form context (instance size, labelling, …).
    route : str
        ``"tree"``, ``"structured"`` or ``"both"``: the route(s) the checks ran on.
    not_run : Mapping
        Check ids the route does not run, each with the reason (structured route).
    provenance : Mapping or None
        What was certified (:mod:`dppverify.provenance`): the sha256 of the instance and
        the profile, the dppverify version, the route, the number mode and the command;
        None in certificates written before provenance existed.
    exploitability : Exploitability or None
        Every player's exact regret and their sum, NashConv (:mod:`dppverify.exploitability`),
        on the game of ``horizon``; None in certificates written before it existed.

    Examples
    --------
    >>> c = Certificate(checks=(CheckRecord("value.U", "pass", "U = 12/5",
    ...                                     {"U": Fraction(12, 5), "U_lp": 2.4}),),
    ...                 horizon=1, exact=True)
    >>> c.verdict, c.to_json()["checks"][0]["numbers"]
    ('pass', {'U': '12/5', 'U_lp': 2.4})
    >>> Certificate.from_json(c.to_json()) == c
    True
    """

    checks: tuple[CheckRecord, ...]
    horizon: int | None
    exact: bool
    tolerance: float | None = None
    lp_solver: str = "CLARABEL"
    lp_tolerance: float = 1e-7
    prefixes: int = 0
    leaves: int = 0
    seed: int | None = None
    info: Mapping[str, Any] = field(default_factory=dict)
    route: str = "tree"
    not_run: Mapping[str, str] = field(default_factory=dict)
    provenance: Mapping[str, Any] | None = None
    exploitability: Exploitability | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "checks", tuple(self.checks))
        object.__setattr__(self, "info", MappingProxyType(dict(self.info)))
        object.__setattr__(self, "not_run", MappingProxyType(dict(self.not_run)))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Certificate):
            return NotImplemented
        return self.to_json() == other.to_json()

    @property
    def verdict(self) -> Verdict:
        """``pass`` exactly when every check passed (see :func:`verdict_of`)."""
        return verdict_of(self.checks)

    @property
    def passed(self) -> bool:
        """True when the verdict is ``pass``."""
        return self.verdict == "pass"

    def check(self, check_id: str) -> CheckRecord:
        """The record of ``check_id`` (KeyError if absent)."""
        for c in self.checks:
            if c.id == check_id:
                return c
        raise KeyError(check_id)

    def of_kind(self, kind: Kind) -> tuple[CheckRecord, ...]:
        """The records of ``kind`` (``check``: evidence for the verdict; ``consistency``: the
        checker's own computations compared, reported apart from the pass count; ``fact``:
        the paper's lemmas and construction, reported beside the verdict).

        Examples
        --------
        >>> c = Certificate(checks=(CheckRecord("value.U", "pass", ""),
        ...     CheckRecord("pbne.belief_consistency", "pass", "")), horizon=1, exact=True)
        >>> [r.id for r in c.of_kind("consistency")], c.counts()
        (['pbne.belief_consistency'], {'check': (1, 1), 'consistency': (1, 1), 'fact': (0, 0)})
        """
        return tuple(c for c in self.checks if c.kind == kind)

    def counts(self) -> dict[Kind, tuple[int, int]]:
        """``(passed, total)`` per kind; the ``N/M checks passed`` of the text report is the
        ``check`` entry (see :meth:`of_kind`)."""
        return {k: (sum(c.passed for c in self.of_kind(k)), len(self.of_kind(k)))
                for k in KINDS}

    def failed(self) -> tuple[CheckRecord, ...]:
        """The records whose status is not ``pass``."""
        return tuple(c for c in self.checks if c.status != "pass")

    @property
    def truncated(self) -> bool:
        """True when the certificate is about the game truncated at a finite ``H``."""
        return self.horizon is not None

    def game_line(self) -> str:
        """The game the verdict is about, for a verdict line.

        Examples
        --------
        >>> Certificate(checks=(), horizon=1, exact=True).game_line()
        'the game truncated at H = 1'
        >>> Certificate(checks=(), horizon=None, exact=True).game_line()
        'the untruncated game (H = inf)'
        """
        if self.horizon is None:
            return "the untruncated game (H = inf)"
        return f"the game truncated at H = {self.horizon}"

    def truncation_note(self) -> str | None:
        """One line saying a truncated game's certificate is not one for the full game."""
        if self.horizon is None:
            return None
        return (f"this certifies the game truncated at H = {self.horizon} only, not the full "
                f"(untruncated) game; omit the horizon to certify the untruncated game")

    def game_record(self) -> dict[str, Any]:
        """The certificate's ``game`` record: the horizon, the ``truncated`` flag and, when
        truncated, the note that it is not a certificate for the full game.

        Examples
        --------
        >>> Certificate(checks=(), horizon=None, exact=True).game_record()
        {'horizon': 'inf', 'truncated': False}
        """
        doc: dict[str, Any] = {"horizon": "inf" if self.horizon is None else self.horizon,
                               "truncated": self.truncated}
        note = self.truncation_note()
        if note is not None:
            doc["note"] = note
        return doc

    def to_json(self) -> dict[str, Any]:
        """The ``dpp-certificate/1`` document."""
        doc: dict[str, Any] = {
            "format": CERTIFICATE_FORMAT,
            "verdict": self.verdict,
            "game": self.game_record(),
            "counts": {k: {"passed": p, "total": t} for k, (p, t) in self.counts().items()},
            "horizon": "inf" if self.horizon is None else self.horizon,
            "route": self.route,
            "exact": self.exact,
            "tolerance": self.tolerance,
            "lp": {"solver": self.lp_solver, "tolerance": self.lp_tolerance},
            "tree": {"prefixes": self.prefixes, "leaves": self.leaves},
            "seed": self.seed,
            "info": json.loads(json.dumps(dict(self.info), default=str)),
            "checks": [c.to_json() for c in self.checks],
            "not_run": dict(self.not_run),
        }
        if self.exploitability is not None:
            doc["exploitability"] = self.exploitability.to_json()
        if self.provenance is not None:
            doc["provenance"] = json.loads(json.dumps(dict(self.provenance)))
        return doc

    @classmethod
    def from_json(cls, doc: Any) -> Certificate:
        """Read a ``dpp-certificate/1`` document (dict or JSON text).

        Raises
        ------
        CertificateError
            If the document is malformed or its verdict contradicts its checks.
        """
        if isinstance(doc, str | bytes):
            try:
                doc = json.loads(doc)
            except json.JSONDecodeError as exc:
                raise CertificateError(f"certificate is not JSON: {exc.msg}") from None
            except (ValueError, RecursionError) as exc:  # an integer of 5000 digits, nesting
                raise CertificateError(f"certificate is not readable JSON: {exc}") from None
        if not isinstance(doc, Mapping) or doc.get("format") != CERTIFICATE_FORMAT:
            raise CertificateError(f"not a {CERTIFICATE_FORMAT} document")
        try:
            checks = tuple(CheckRecord.from_json(c) for c in doc["checks"])
            lp = doc.get("lp") or {}
            tree = doc.get("tree") or {}
            tol = doc.get("tolerance")
            horizon = None if doc["horizon"] == "inf" else \
                _read_count(doc["horizon"], "horizon", MAX_HORIZON)
            cert = cls(checks=checks, horizon=horizon, exact=bool(doc["exact"]),
                       tolerance=None if tol is None else float(tol),
                       lp_solver=str(lp.get("solver", "CLARABEL")),
                       lp_tolerance=float(lp.get("tolerance", 1e-7)),
                       prefixes=_read_count(tree.get("prefixes", 0), "tree.prefixes"),
                       leaves=_read_count(tree.get("leaves", 0), "tree.leaves"),
                       seed=None if doc.get("seed") is None else _read_count(doc["seed"], "seed",
                                                                             2**64, -2**64),
                       info=dict(doc.get("info") or {}),
                       route=str(doc.get("route", "tree")),
                       not_run={str(k): str(v) for k, v in dict(doc.get("not_run") or {}).items()},
                       provenance=_provenance(doc.get("provenance")))
            if doc.get("exploitability") is not None:
                cert = dataclasses.replace(cert, exploitability=_exploitability(
                    doc["exploitability"], checks, horizon, bool(doc["exact"])))
        except KeyError as exc:
            raise CertificateError(f"certificate is missing {exc}") from None
        except (TypeError, ValueError, AttributeError, OverflowError) as exc:
            raise CertificateError(f"malformed certificate: {exc}") from None
        game = doc.get("game")
        if game is not None and game != cert.game_record():
            raise CertificateError(f"certificate game record {game!r} contradicts its horizon "
                                   f"{doc['horizon']!r}")
        if doc.get("verdict") != cert.verdict:
            raise CertificateError(f"certificate verdict {doc.get('verdict')!r} contradicts its "
                                   f"checks (they give {cert.verdict!r})")
        return cert


def _provenance(value: Any) -> dict[str, Any] | None:
    if value is None:
        return None
    if not isinstance(value, Mapping):
        raise TypeError("provenance must be a JSON object")
    return dict(value)


def _exploitability(value: Any, checks: tuple[CheckRecord, ...], horizon: int | None,
                    exact: bool) -> Exploitability:
    """The certificate's ``exploitability`` record, recomputed from its checks (goals and
    priors from the record) and refused when the record says otherwise."""
    if not isinstance(value, Mapping) or not isinstance(value.get("types"), list):
        raise TypeError("exploitability must be a JSON object with a list of types")
    types = value["types"]
    if not all(isinstance(t, Mapping) for t in types):
        raise TypeError("exploitability types must be JSON objects")
    e = exploitability_of(checks, goals=[t.get("goal") for t in types],
                          priors=[Fraction(str(t.get("prior"))) for t in types],
                          horizon=horizon, exact=exact)
    if e.to_json() != dict(value):
        raise CertificateError("the certificate's exploitability record contradicts its checks")
    return e
