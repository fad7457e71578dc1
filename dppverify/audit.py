"""Audit any solver on random instances: generate, solve, certify, shrink (``dpp audit``).

A *solver* is any callable mapping an instance document (``docs/formats.md`` §1) to a
``dpp-profile/1`` document (§2): a Python function named ``MODULE:FUNCTION``
(:func:`load_solver`) or a command line ``'prog {instance} {profile}'`` run on files
(:func:`command_solver`). :func:`run_audit` draws instances from the hypothesis strategies of
:mod:`dppverify.strategies`, gives each to the solver, certifies the answer with
:func:`dppverify.certify`, stops at the first instance whose profile is not certified,
shrinks it (hypothesis) to a minimal failing instance, and writes that instance, the
solver's profile and the certificate to a directory.

An example *fails* when the solver raises (or the command exits non-zero), returns something
that is not a JSON object, returns a document that is not ``dpp-profile/1``, or returns a
profile whose certificate verdict is not ``pass``. Examples whose walk tree exceeds
``max_prefixes`` are skipped (counted, never failures). The checker never imports the
solver: callables are imported by name at run time.

Examples
--------
>>> from fractions import Fraction
>>> def stay_put(doc):           # a wrong solver: the Attacker never moves
...     goals, prior = doc["goals"], [Fraction(p) for p in doc["prior"]]
...     g1, g2 = goals if prior[0] >= prior[1] else goals[::-1]
...     stay = [{"path": [doc["start"]], "probability": 1}]
...     return {"format": "dpp-profile/1", "goals": {"primary": g1, "secondary": g2},
...             "defender": {"rule": "progress", "goal": g1},
...             "attacker": {"primary": stay, "secondary": stay}}
>>> report = run_audit(stay_put, examples=50, seed=1)
>>> report.passed, report.failure.check
(False, 'profile.wellformed')
>>> inst = report.failure.instance       # shrunk: a tiny instance, start off the goals
>>> inst["start"] in inst["goals"], len(inst["graph"]["nodes"]) <= 4
(False, True)
"""

from __future__ import annotations

import importlib
import json
import shlex
import subprocess
import sys
import tempfile
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from hypothesis import HealthCheck, Phase, Verbosity, given, reject, settings
from hypothesis import seed as hypothesis_seed
from hypothesis import strategies as st
from hypothesis.errors import Unsatisfiable

from dppverify.certificate import Certificate
from dppverify.certify import certify
from dppverify.errors import CheckerError, ProfileError, TreeTooLargeError
from dppverify.exact import parse_json
from dppverify.instance import instance_from_json
from dppverify.strategies import grid_worlds, instances, priors, weighted_graphs

__all__ = ["AUDIT_MAX_PREFIXES", "AuditError", "AuditReport", "Outcome", "Solver",
           "SolverFailedError", "audit_instances", "command_solver", "examine", "load_solver",
           "prune_failure", "run_audit", "write_failure"]

Doc = dict[str, Any]
Solver = Callable[[Doc], Any]
"""A solver: instance document -> ``dpp-profile/1`` document."""

AUDIT_MAX_PREFIXES = 200_000
"""Default size guard of the walk tree per example; larger examples are skipped."""

AUDIT_TRIALS = 2
"""Random attackers per L3/L4 lemma check (the lemmas concern the instance, not the solver)."""


class AuditError(CheckerError, ValueError):
    """Bad audit input: an unknown solver name, a bad command template, bad arguments."""


class SolverFailedError(Exception):
    """A command-line solver exited non-zero, timed out, or wrote no profile."""


# ----------------------------------------------------------------------------- solvers
def load_solver(spec: str) -> Solver:
    """Import the callable named ``MODULE:FUNCTION`` (``FUNCTION`` may be dotted).

    Raises
    ------
    AuditError
        Malformed name, module that cannot be imported, missing or non-callable attribute.

    Examples
    --------
    >>> load_solver("json:dumps").__name__
    'dumps'
    >>> load_solver("json.dumps")
    Traceback (most recent call last):
    dppverify.audit.AuditError: --solver 'json.dumps' must look like MODULE:FUNCTION
    """
    module_name, sep, attr = spec.partition(":")
    if not sep or not module_name or not attr:
        raise AuditError(f"--solver {spec!r} must look like MODULE:FUNCTION")
    try:
        obj: Any = importlib.import_module(module_name)
    except Exception as exc:  # any import-time error of user code is bad input
        raise AuditError(f"cannot import module {module_name!r}: "
                         f"{type(exc).__name__}: {exc}") from None
    for part in attr.split("."):
        if not hasattr(obj, part):
            raise AuditError(f"module {module_name!r} has no attribute {attr!r}")
        obj = getattr(obj, part)
    if not callable(obj):
        raise AuditError(f"{spec!r} is not callable")
    return obj


def command_solver(template: str, *, timeout: float = 60.0) -> Solver:
    """A solver that runs a command line on files.

    ``template`` must contain ``{instance}`` and ``{profile}``: the instance JSON is written
    to a temporary file, the command runs (no shell; arguments split like a POSIX shell) and
    must write the profile JSON to the ``{profile}`` path and exit 0.

    Raises
    ------
    AuditError
        If the template is malformed or lacks a placeholder.

    Examples
    --------
    >>> solve = command_solver("cp {instance} {profile}")
    >>> solve({"start": 0})
    {'start': 0}
    >>> command_solver("prog {instance}")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.audit.AuditError: --solver-cmd must contain {instance} and {profile}: ...
    """
    try:
        argv = shlex.split(template)
    except ValueError as exc:
        raise AuditError(f"--solver-cmd {template!r}: {exc}") from None
    if not argv or not all(any(p in a for a in argv) for p in ("{instance}", "{profile}")):
        raise AuditError(f"--solver-cmd must contain {{instance}} and {{profile}}: {template!r}")

    def run(doc: Doc) -> Any:
        with tempfile.TemporaryDirectory(prefix="dpp-audit-") as tmp:
            inst, prof = Path(tmp) / "instance.json", Path(tmp) / "profile.json"
            inst.write_text(json.dumps(doc))
            cmd = [a.replace("{instance}", str(inst)).replace("{profile}", str(prof))
                   for a in argv]
            try:
                done = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout,
                                      check=False)
            except FileNotFoundError:
                raise SolverFailedError(f"command not found: {argv[0]!r}") from None
            except subprocess.TimeoutExpired:
                raise SolverFailedError(f"command timed out after {timeout:g} s") from None
            if done.returncode != 0:
                lines = (done.stderr or done.stdout).strip().splitlines()
                last = lines[-1] if lines else "no output"
                raise SolverFailedError(f"command exited {done.returncode}: {last}")
            if not prof.exists():
                raise SolverFailedError("command exited 0 but wrote no profile file")
            return parse_json(prof.read_bytes())

    return run


# ----------------------------------------------------------------------------- instances
def audit_instances(*, max_nodes: int = 8) -> st.SearchStrategy[Doc]:
    """The instances the audit draws: random graphs (integer and fractional weights,
    directed and undirected, strongly connected or not, up to ``2 * max_nodes`` edges beyond
    a spanning scaffold) and weighted grid worlds, at most ``max_nodes`` nodes; the prior is
    exactly 1/2 about 40% of the time. Shrinks towards tiny undirected unit-weight graphs.

    Weighted instances are favoured because they exercise more of the construction: on unit
    weights phase II (``t_I < t_II``) almost never occurs, while about one weighted example
    in ten has it.

    Examples
    --------
    >>> from hypothesis import find, settings
    >>> doc = find(audit_instances(max_nodes=4), lambda d: True,
    ...            settings=settings(database=None))
    >>> len(doc["graph"]["nodes"]), doc["prior"]
    (2, ['1/2', '1/2'])
    """
    if isinstance(max_nodes, bool) or not isinstance(max_nodes, int) or max_nodes < 2:
        raise AuditError(f"max_nodes={max_nodes!r} must be an integer >= 2")
    extra = 2 * max_nodes
    # about 40% exactly 1/2 (the tie of footnote 2), shrinking to it
    prior = st.one_of(priors(), priors(allow_half=False), st.just(["1/2", "1/2"]))
    parts = [
        instances(graphs=weighted_graphs(max_nodes=max_nodes, weights="integers",
                                         max_extra_edges=extra), priors=prior),
        instances(graphs=weighted_graphs(max_nodes=max_nodes, weights="fractions",
                                         max_weight=4, max_extra_edges=extra), priors=prior),
        instances(graphs=weighted_graphs(max_nodes=max_nodes, directed=True,
                                         weights="fractions", max_weight=4,
                                         strongly_connected=False, max_extra_edges=extra),
                  priors=prior),
    ]
    if max_nodes >= 4:
        parts.append(grid_worlds(max_size=max(2, min(max_nodes // 2, 6)), max_cells=max_nodes,
                                 weights="fractions", max_density=0.5, priors=prior))
    return st.one_of(parts)


# ----------------------------------------------------------------------------- one example
@dataclass(frozen=True)
class Outcome:
    """The audit of one instance.

    Attributes
    ----------
    instance : dict
        The instance document given to the solver.
    profile : object
        What the solver returned, after a JSON round trip (None if it raised or returned
        something that is not JSON).
    certificate : Certificate or None
        The checker's certificate (None when the profile could not be certified at all).
    check : str
        The first failing check id, or ``solver.error`` / ``solver.output`` /
        ``profile.format``; empty when the example passed.
    message : str
        One line for humans.
    """

    instance: Doc
    profile: Any
    certificate: Certificate | None
    check: str = ""
    message: str = ""

    @property
    def passed(self) -> bool:
        """True when the profile was certified (verdict ``pass``)."""
        return self.check == ""


def examine(solver: Solver, doc: Doc, *, max_prefixes: int = AUDIT_MAX_PREFIXES,
            trials: int = AUDIT_TRIALS, seed: int = 0) -> Outcome:
    """Solve ``doc`` with ``solver`` and certify the answer.

    Raises :class:`~dppverify.errors.TreeTooLargeError` when the walk tree exceeds
    ``max_prefixes`` (the caller skips the example); everything the solver does wrong is an
    :class:`Outcome` with ``passed`` False.

    Examples
    --------
    >>> doc = {"graph": {"nodes": [{"id": 0}, {"id": 1}], "edges": []}, "start": 0,
    ...        "goals": [0, 1], "prior": ["1/2", "1/2"]}
    >>> examine(lambda d: 1 / 0, doc).message
    'the solver raised ZeroDivisionError: division by zero'
    """
    try:
        answer = solver(json.loads(json.dumps(doc)))  # the solver gets its own copy
    except Exception as exc:  # the solver's own failure is what we audit
        return Outcome(doc, None, None, "solver.error",
                       f"the solver raised {type(exc).__name__}: {_one_line(exc)}")
    if not isinstance(answer, Mapping):
        return Outcome(doc, None, None, "solver.output",
                       f"the solver returned {type(answer).__name__}, not a JSON object")
    try:
        profile = parse_json(json.dumps(answer, default=_number_default))
    except (TypeError, ValueError) as exc:
        return Outcome(doc, None, None, "solver.output",
                       f"the solver's profile is not JSON: {_one_line(exc)}")
    try:
        cert = certify(doc, profile, max_prefixes=max_prefixes, trials=trials, seed=seed)
    except TreeTooLargeError:
        raise
    except ProfileError as exc:
        return Outcome(doc, profile, None, "profile.format", _one_line(exc))
    except CheckerError as exc:  # e.g. a horizon or instance problem caused by the profile
        return Outcome(doc, profile, None, "profile.format", _one_line(exc))
    if cert.passed:
        return Outcome(doc, profile, cert)
    bad = [c for c in cert.checks if c.status != "pass"]
    first = next((c for c in bad if c.status == "fail"), bad[0])
    return Outcome(doc, profile, cert, first.id,
                   f"verdict {cert.verdict}: {first.status} {first.id}: {first.message}")


def _number_default(x: Any) -> Any:
    from fractions import Fraction

    if isinstance(x, Fraction):
        return f"{x.numerator}/{x.denominator}"
    raise TypeError(f"{type(x).__name__} is not JSON serializable")


def _one_line(exc: BaseException) -> str:
    text = " ".join(str(exc).split())
    return text if len(text) <= 300 else text[:297] + "..."


# ----------------------------------------------------------------------------- campaign
@dataclass(frozen=True)
class AuditReport:
    """The result of :func:`run_audit`.

    Attributes
    ----------
    passed : bool
        True when every example was certified.
    examples : int
        Examples solved and certified: all of them on success, else up to and including
        the first failing one (skipped examples not counted).
    skipped : int
        Examples skipped because the walk tree exceeded ``max_prefixes``.
    shrink_calls : int
        Solver calls spent shrinking the failure.
    failure : Outcome or None
        The minimal failing example (None on success).
    first_failure : Outcome or None
        The failing example as first found, before shrinking.
    files : tuple of Path
        Files written for the failure.
    seed, max_nodes : int
        The campaign's settings.
    """

    passed: bool
    examples: int
    skipped: int
    shrink_calls: int
    failure: Outcome | None
    first_failure: Outcome | None
    files: tuple[Path, ...] = field(default=())
    seed: int = 0
    max_nodes: int = 8

    def summary(self) -> str:
        """One line: the verdict and the examples used."""
        skipped = f", {self.skipped} skipped (tree too large)" if self.skipped else ""
        if self.passed:
            return (f"audit PASS: {self.examples} examples certified{skipped} "
                    f"(seed {self.seed}, at most {self.max_nodes} nodes)")
        message = self.failure.message if self.failure is not None else "?"
        return (f"audit FAIL after {self.examples} examples{skipped} (seed {self.seed}; "
                f"shrunk with {self.shrink_calls} more solver calls): {message}")


class _Found(Exception):
    """Raised inside the hypothesis test to mark a failing example."""


def run_audit(solver: Solver, *, examples: int = 100, seed: int = 0, max_nodes: int = 8,
              out: str | Path | None = None, shrink: bool = True, progress: bool = False,
              strategy: st.SearchStrategy[Doc] | None = None,
              max_prefixes: int = AUDIT_MAX_PREFIXES, trials: int = AUDIT_TRIALS) -> AuditReport:
    """Audit ``solver`` on up to ``examples`` generated instances.

    Parameters
    ----------
    solver : callable
        Instance document -> profile document (see :func:`load_solver`,
        :func:`command_solver`).
    examples : int
        Example budget (hypothesis ``max_examples``).
    seed : int
        Seed of the generation: the same seed and solver give the same campaign.
    max_nodes : int
        Largest instance (nodes) of the default strategy :func:`audit_instances`.
    out : path, optional
        Directory for the minimal failing instance, profile and certificate.
    shrink : bool
        Shrink the first failure to a minimal one (default True).
    progress : bool
        Show a tqdm progress bar on stderr.
    strategy : SearchStrategy, optional
        Instances to draw instead of :func:`audit_instances`.
    max_prefixes, trials : int
        Passed to :func:`dppverify.certify` (tree-size guard; random attackers of L3/L4).

    Returns
    -------
    AuditReport

    Examples
    --------
    A "solver" that always answers the triangle's equilibrium is certified on the triangle
    and refuted on the first generated instance:

    >>> from hypothesis import strategies as st
    >>> from dppverify.examples import triangle_document
    >>> answer = {"format": "dpp-profile/1", "goals": {"primary": "g1", "secondary": "g2"},
    ...     "defender": {"rule": "progress", "goal": "g1"},
    ...     "attacker": {"primary": [{"path": ["s", "g1"], "probability": "4/7"},
    ...                              {"path": ["s", "g2"], "probability": "3/7"}],
    ...                  "secondary": [{"path": ["s", "g2"], "probability": 1}]}}
    >>> run_audit(lambda doc: answer, examples=3, strategy=st.just(triangle_document())).passed
    True
    >>> report = run_audit(lambda doc: answer, examples=20, shrink=False)
    >>> report.passed, report.examples, report.failure.check
    (False, 1, 'profile.wellformed')
    """
    if isinstance(examples, bool) or not isinstance(examples, int) or examples < 1:
        raise AuditError(f"examples={examples!r} must be a positive integer")
    if isinstance(seed, bool) or not isinstance(seed, int):
        raise AuditError(f"seed={seed!r} must be an integer")
    source = audit_instances(max_nodes=max_nodes) if strategy is None else strategy
    counts = {"examples": 0, "skipped": 0, "shrink": 0}
    found: list[Outcome] = []

    from tqdm import tqdm

    bar = tqdm(total=examples, desc="audit", unit="ex", disable=not progress, file=sys.stderr,
               leave=False)

    def one(doc: Doc) -> None:
        if found:
            counts["shrink"] += 1
            bar.set_description(f"shrinking ({counts['shrink']})")
        try:
            outcome = examine(solver, doc, max_prefixes=max_prefixes, trials=trials, seed=seed)
        except TreeTooLargeError:
            if not found:
                counts["skipped"] += 1
            reject()
            return
        if not found:
            counts["examples"] += 1
            bar.update(1)
        if not outcome.passed:
            found.append(outcome)
            raise _Found(outcome.message)

    phases = [Phase.generate, Phase.shrink] if shrink else [Phase.generate]
    config = settings(parent=settings.get_profile("default"), max_examples=examples,
                      database=None, deadline=None, derandomize=False, phases=phases,
                      verbosity=Verbosity.quiet, suppress_health_check=list(HealthCheck),
                      print_blob=False, report_multiple_bugs=False)
    test = config(hypothesis_seed(seed)(given(source)(one)))
    try:
        test()
    except Unsatisfiable:
        if not found:
            raise AuditError(f"every generated example was skipped: walk trees larger than "
                             f"max_prefixes={max_prefixes} (lower --max-nodes)") from None
    except Exception:  # _Found, or hypothesis' Flaky error around a failure
        if not found:
            raise
    finally:
        bar.close()
    if not found:
        return AuditReport(True, counts["examples"], counts["skipped"], 0, None, None,
                           seed=seed, max_nodes=max_nodes)
    minimal = found[-1]  # hypothesis replays the minimal failing example last
    calls = max(0, counts["shrink"] - 1)
    if shrink:
        minimal, pruned_calls = prune_failure(solver, minimal, max_prefixes=max_prefixes,
                                              trials=trials, seed=seed)
        calls += pruned_calls
    files = write_failure(minimal, out, seed=seed) if out is not None else ()
    return AuditReport(False, counts["examples"], counts["skipped"], calls, minimal, found[0],
                       files, seed, max_nodes)


def prune_failure(solver: Solver, outcome: Outcome, *, max_prefixes: int = AUDIT_MAX_PREFIXES,
                  trials: int = AUDIT_TRIALS, seed: int = 0) -> tuple[Outcome, int]:
    """Delete nodes and edges from a failing instance while it still fails the same check.

    Hypothesis shrinks the *draws*, which often leaves nodes the failure does not need (the
    node count is drawn first). This greedy pass removes, one at a time, every node other
    than the start and the goals (with its edges), then every edge, keeping a removal when
    the instance stays valid and the solver's answer still fails the same check; it repeats
    until nothing can be removed. Returns the pruned outcome and the solver calls spent.

    Examples
    --------
    >>> def stay_put(doc):           # a wrong solver: the Attacker never moves
    ...     s = doc["start"]
    ...     return {"format": "dpp-profile/1",
    ...             "attacker": {"primary": [{"path": [s], "probability": "1"}],
    ...                          "secondary": [{"path": [s], "probability": "1"}]}}
    >>> doc = {"graph": {"nodes": [{"id": i} for i in range(4)],
    ...        "edges": [{"source": 0, "target": i} for i in (1, 2, 3)]},
    ...        "start": 0, "goals": [1, 2], "prior": ["1/2", "1/2"]}
    >>> pruned, calls = prune_failure(stay_put, examine(stay_put, doc))
    >>> [n["id"] for n in pruned.instance["graph"]["nodes"]], pruned.check
    ([0, 1, 2], 'profile.wellformed')
    """
    calls = 0
    best = outcome
    keep = {json.dumps(best.instance["start"]), *(json.dumps(g) for g in best.instance["goals"])}

    def attempt(doc: Doc) -> Outcome | None:
        nonlocal calls
        try:
            instance_from_json(doc)
        except CheckerError:  # e.g. a goal became unreachable
            return None
        calls += 1
        try:
            result = examine(solver, doc, max_prefixes=max_prefixes, trials=trials, seed=seed)
        except TreeTooLargeError:
            return None
        return result if result.check == best.check else None

    changed = True
    while changed:
        changed = False
        graph = best.instance["graph"]
        for node in list(graph["nodes"]):
            key = json.dumps(node["id"])
            if key in keep:
                continue
            edges = [e for e in graph["edges"]
                     if key not in (json.dumps(e["source"]), json.dumps(e["target"]))]
            nodes = [n for n in graph["nodes"] if n is not node]
            smaller = attempt({**best.instance, "graph": {**graph, "nodes": nodes,
                                                          "edges": edges}})
            if smaller is not None:
                best, changed = smaller, True
                break
        if changed:
            continue
        for edge in list(graph["edges"]):
            edges = [e for e in graph["edges"] if e is not edge]
            smaller = attempt({**best.instance, "graph": {**graph, "edges": edges}})
            if smaller is not None:
                best, changed = smaller, True
                break
    return best, calls


def write_failure(outcome: Outcome, out: str | Path, *, seed: int = 0) -> tuple[Path, ...]:
    """Write a failing example's files into the directory ``out`` (created if needed).

    Parameters
    ----------
    outcome : Outcome
        The failing example (e.g. :attr:`AuditReport.failure`).
    out : str or Path
        The directory.
    seed : int
        The campaign's seed, recorded in ``failure.json``.

    Returns
    -------
    tuple of Path
        The files written: ``instance.json``, ``profile.json`` (if the solver's answer was
        JSON), ``certificate.json`` (if it could be certified) and ``failure.json`` (check
        id, message, seed).

    Examples
    --------
    >>> import json, tempfile
    >>> from dppverify.examples import triangle_document
    >>> outcome = examine(lambda doc: 1 / 0, triangle_document())
    >>> with tempfile.TemporaryDirectory() as d:
    ...     files = write_failure(outcome, Path(d) / "fail", seed=7)
    ...     names = [f.name for f in files]
    ...     failure = json.loads(files[-1].read_text())
    >>> names
    ['instance.json', 'failure.json']
    >>> failure["check"], failure["seed"]
    ('solver.error', 7)
    """
    folder = Path(out)
    folder.mkdir(parents=True, exist_ok=True)
    docs: dict[str, Any] = {"instance.json": outcome.instance}
    if outcome.profile is not None:
        docs["profile.json"] = outcome.profile
    if outcome.certificate is not None:
        docs["certificate.json"] = outcome.certificate.to_json()
    docs["failure.json"] = {"check": outcome.check, "message": outcome.message, "seed": seed}
    written = []
    for name, doc in docs.items():
        path = folder / name
        path.write_text(json.dumps(doc, indent=2, default=_number_default) + "\n")
        written.append(path)
    return tuple(written)
