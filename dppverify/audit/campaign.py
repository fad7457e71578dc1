"""The audit campaign: draw instances with hypothesis, examine each, shrink the first failure.

:func:`run_audit` runs the solver under test through a
:class:`~dppverify.audit.runner.SolverRunner` (a worker process or a command, under one
timeout), stops at the first failing example, writes it to ``out`` at once, then shrinks it
— hypothesis' shrinking, then :func:`~dppverify.audit.pruning.prune_failure` — within a
:class:`~dppverify.audit.pruning.ShrinkBudget`, rewriting ``out`` whenever a smaller failure
is found.

Nested campaigns
----------------
A campaign is one hypothesis run seeded by ``seed`` whose settings never depend on the
budget: ``max_examples`` is always :data:`~dppverify.limits.MAX_AUDIT_EXAMPLES`, and the
budget only says when to stop (the test raises :class:`_Enough` before the solver sees the
``examples + 1``-th game). Under a fixed seed and fixed settings, hypothesis draws each game
from the games drawn before it and how they ended; before the first failure every game
ended the same way whatever the solver (a pass, or a skip that is not reported to
hypothesis as a rejection), so the stream of games depends only on the seed, the strategy
and its settings (``max_nodes``). Games already audited are not examined again: examples
are distinct games (equal documents, :func:`game_key`). Hence a budget of ``N`` audits
exactly the first ``N`` examples of any larger budget with the same seed, and a solver
that fails at example ``k`` fails there for every budget ``>= k``
(``tests/dppverify/audit/test_audit_nesting.py``).
"""

from __future__ import annotations

import hashlib
import json
import sys
from collections.abc import Callable
from typing import Any

from hypothesis import HealthCheck, Phase, Verbosity, given, reject, settings
from hypothesis import seed as hypothesis_seed
from hypothesis import strategies as st

from dppverify.audit.config import (
    DEFAULT_CONFIG,
    HYPOTHESIS_SHARE,
    SKIP_FACTOR,
    SKIP_FLOOR,
    AuditConfig,
)
from dppverify.audit.examine import Outcome, examine
from dppverify.audit.pruning import prune_failure
from dppverify.audit.report import AuditReport, check_output_folder, save_failure
from dppverify.audit.runner import PythonRunner, SolverRunner
from dppverify.errors import AuditError, TreeTooLargeError
from dppverify.limits import MAX_AUDIT_EXAMPLES
from dppverify.strategies import grid_worlds, instances, priors, weighted_graphs

Doc = dict[str, Any]


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
    given: object = max_nodes  # checked as given, whatever its type
    if isinstance(given, bool) or not isinstance(given, int) or given < 2:
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


class _Found(Exception):
    """Raised inside the hypothesis test to mark a failing example."""


def run_audit(solver: SolverRunner | Callable[[Doc], Any], config: AuditConfig = DEFAULT_CONFIG,
              *, strategy: st.SearchStrategy[Doc] | None = None,
              log: Callable[[str], None] | None = None) -> AuditReport:
    """Audit ``solver`` on up to ``config.examples`` generated instances.

    Parameters
    ----------
    solver : SolverRunner or callable
        A runner (:class:`~dppverify.audit.runner.PythonRunner`,
        :class:`~dppverify.audit.runner.CommandRunner`) or a callable mapping an instance
        document to a profile document, which is then run in a worker process
        (:class:`~dppverify.audit.runner.PythonRunner` with ``config.timeout``).
    config : AuditConfig
        The campaign: its example budget (the first ``examples`` distinct games of the
        seed's stream: a smaller budget audits a prefix of a larger one, see the module
        docstring), seed, instance size, certification options, shrinking budget, output
        folder (written as soon as the first failure is found, rewritten whenever shrinking
        finds a smaller one) and progress bar.
    strategy : SearchStrategy, optional
        Instances to draw instead of :func:`audit_instances` (``max_nodes`` is then unused).
    log : callable, optional
        Receives one-line status messages (the first failure and where it was written).

    Returns
    -------
    AuditReport

    Examples
    --------
    A "solver" that always answers the triangle's equilibrium is certified on the triangle
    and refuted on the first generated instance:

    >>> from hypothesis import strategies as st
    >>> from dppverify.game.examples import triangle_document, triangle_profile
    >>> answer = triangle_profile()
    >>> run_audit(lambda doc: answer, AuditConfig(examples=3),
    ...           strategy=st.just(triangle_document())).passed
    True
    >>> report = run_audit(lambda doc: answer, AuditConfig(examples=20, shrink=False))
    >>> report.passed, report.examples, report.failure.check
    (False, 1, 'profile.wellformed')
    """
    if config.out is not None:
        check_output_folder(config.out)  # before any example: never a campaign that cannot report
    source = audit_instances(max_nodes=config.max_nodes) if strategy is None else strategy
    if isinstance(solver, SolverRunner):
        runner, owned = solver, False
    else:
        runner, owned = PythonRunner(solver, timeout=config.timeout), True
    try:
        return _campaign(runner, source, config, log=log)
    finally:
        if owned:
            runner.close()


class _Enough(BaseException):
    """Raised inside the hypothesis test once the budget's examples are done: it ends the run
    without counting as a failure (hypothesis lets ``BaseException`` s that are not
    ``Exception`` s pass through, as it does ``KeyboardInterrupt``)."""


def game_key(doc: Doc) -> str:
    """The identity of a generated game: the sha256 of its canonical JSON (two examples are
    the same game exactly when their documents are equal).

    Examples
    --------
    >>> game_key({"b": 1, "a": [2]}) == game_key({"a": [2], "b": 1})
    True
    """
    text = json.dumps(doc, sort_keys=True, separators=(",", ":"), default=str)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _campaign(runner: SolverRunner, source: st.SearchStrategy[Doc], config: AuditConfig, *,
              log: Callable[[str], None] | None) -> AuditReport:
    """One hypothesis run whose settings never depend on ``examples`` (see the module
    docstring, "Nested campaigns"): the budget only says when to stop."""
    from tqdm import tqdm

    bar = tqdm(total=config.examples, desc="audit", unit="ex", disable=not config.progress,
               file=sys.stderr, leave=False)
    run = _Campaign(runner, config, log, bar)
    phases = [Phase.generate, Phase.shrink] if config.shrink else [Phase.generate]
    # max_examples is the same for every budget: hypothesis' generation (its early small
    # examples, its mutations) is then the same sequence whatever the budget
    hypothesis_settings = settings(
        parent=settings.get_profile("default"), max_examples=MAX_AUDIT_EXAMPLES,
        database=None, deadline=None, derandomize=False, phases=phases,
        verbosity=Verbosity.quiet, suppress_health_check=list(HealthCheck), print_blob=False,
        report_multiple_bugs=False)
    test = hypothesis_settings(hypothesis_seed(config.seed)(given(source)(run.one)))
    try:
        test()
    except _Enough:
        pass
    except Exception:  # _Found, or hypothesis' Flaky error around a failure
        if not run.found:
            raise
    try:
        return run.report()
    finally:
        bar.close()


class _Campaign:
    """The state of one campaign: what hypothesis drew so far, the failures found (the first
    one, then every smaller one with its identity), the budget and the files written."""

    def __init__(self, runner: SolverRunner, config: AuditConfig,
                 log: Callable[[str], None] | None, bar: Any) -> None:
        self.runner, self.config, self.log, self.bar = runner, config, log, bar
        self.budget = config.budget()
        self.examples = self.skipped = 0
        self.seen: set[str] = set()
        self.found: list[Outcome] = []
        self.files: tuple[Any, ...] = ()
        self.unwritten: list[str] = []  # why the failure's files could not be written
        self.skip_limit = max(SKIP_FLOOR, SKIP_FACTOR * config.examples)
        self.stopped = False

    def record(self, outcome: Outcome) -> None:
        """Keep a failure (the first, or a smaller one) and write it to ``config.out``."""
        self.found.append(outcome)
        if self.config.out is not None:
            self.files = save_failure(outcome, self.config.out, seed=self.config.seed,
                                      unwritten=self.unwritten)
        if len(self.found) > 1:
            self.bar.set_description(f"shrinking: {self.budget.used}/{self.budget.calls} calls, "
                                     f"{len(outcome.instance['graph']['nodes'])} nodes")

    def first(self, outcome: Outcome) -> None:
        """The first failure: keep it, say so, start the shrinking budget."""
        self.record(outcome)
        out, shrink = self.config.out, self.config.shrink
        if self.log is not None and not self.unwritten:  # (else the end says it, in one line)
            where = f"; written to {out}" if out is not None else ""
            plan = (f"; shrinking it (budget: {self.budget.describe()})" if shrink else "")
            self.log(f"audit: example {self.examples} fails {outcome.check}{where}{plan}")
        self.budget.start()
        if shrink:
            self.bar.reset(total=self.budget.calls)
            self.bar.set_description("shrinking")

    def shrinking(self, doc: Doc) -> None:
        """Hypothesis shrinking: keep ``doc`` when it fails as the first failure did."""
        # hypothesis' shrinking gets half the budget, the pruning pass the rest
        if not self.config.shrink or not self.budget.spend(HYPOTHESIS_SHARE):
            return
        self.bar.update(1)
        try:
            outcome = examine(self.runner, doc, self.config)
        except TreeTooLargeError:
            reject()  # raises: hypothesis discards the example
        if outcome.passed or outcome.identity != self.found[0].identity:
            return  # another failure: shrinking stays on the first one (as hypothesis)
        self.record(outcome)
        raise _Found(outcome.message)

    def one(self, doc: Doc) -> None:
        """The hypothesis test: examine one drawn game."""
        if self.found:  # shrinking (or hypothesis replaying the failure)
            self.shrinking(doc)
            return
        key = game_key(doc)
        if key in self.seen:
            return  # a game already audited is not an example again
        if self.examples >= self.config.examples:
            raise _Enough
        self.seen.add(key)
        try:
            outcome = examine(self.runner, doc, self.config)
        except TreeTooLargeError:
            # skipped, not rejected: what hypothesis draws next must not depend on the solver
            self.skipped += 1
            if self.skipped >= self.skip_limit:
                self.stopped = True
                raise _Enough from None
            return
        self.examples += 1
        self.bar.update(1)
        if not outcome.passed:
            self.first(outcome)
            raise _Found(outcome.message)

    def report(self) -> AuditReport:
        """The campaign's report; the first failure pruned within what is left of the budget."""
        config, shrink = self.config, self.config.shrink
        if not self.found and self.examples == 0:
            if self.stopped:
                raise AuditError(f"every generated example was skipped: walk trees larger than "
                                 f"max_prefixes={config.max_prefixes} (lower --max-nodes)")
            raise AuditError("the instance strategy gave no example")
        if not self.found:
            note = ""
            if self.examples < config.examples:
                note = (f"stopped after {self.skipped} skipped examples" if self.stopped else
                        "the generator has no further distinct game")
            return AuditReport(True, self.examples, self.skipped, 0, None, None,
                               seed=config.seed, max_nodes=config.max_nodes, shrunk=shrink,
                               note=note)
        # every failure accepted while shrinking is smaller and has the first one's identity
        minimal = self.found[-1]
        if shrink:
            minimal, _ = prune_failure(self.runner, minimal, config, budget=self.budget,
                                       on_improve=self.record)
        return AuditReport(False, self.examples, self.skipped, self.budget.used, minimal,
                           self.found[0], self.files, config.seed, config.max_nodes,
                           shrunk=shrink, budget_exhausted=shrink and self.budget.exhausted,
                           unwritten=self.unwritten[0] if self.unwritten and not self.files
                           else "")
