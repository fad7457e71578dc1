"""Audit any solver on random instances: generate, solve, certify, shrink (``dpp audit``).

A *solver* is anything mapping an instance document (``docs/formats.md`` §1) to a
``dpp-profile/1`` document (§2): a Python callable, by name ``MODULE:FUNCTION`` or as an
object, or a command line ``'prog {instance} {profile}'`` run on files. One module per job:

- :mod:`~dppverify.audit.runner` runs the solver in isolation (a worker process or a
  command in its own session) under a timeout; whatever the solver does wrong — raise,
  exit, hang, print garbage — is that solver's failure, never the audit's;
- :mod:`~dppverify.audit.examine` solves and certifies one instance (:class:`Outcome`);
- :mod:`~dppverify.audit.campaign` draws instances with hypothesis (:func:`run_audit`);
- :mod:`~dppverify.audit.pruning` shrinks a failure within a budget;
- :mod:`~dppverify.audit.report` holds the result and writes the failure directory.
- :mod:`~dppverify.audit.config` holds the one record of how an audit runs
  (:class:`AuditConfig`) and every default and budget of ``dpp audit``.

An example *fails* when the solver raises, exits or times out (``solver.error``,
``solver.timeout``), returns something that is not a JSON object (``solver.output``), returns
a document that is not ``dpp-profile/1`` (``profile.format``), or returns a profile whose
certificate verdict is not ``pass``. Examples whose walk tree exceeds ``max_prefixes`` are
skipped (counted, never failures). The audit reports PASS only when every example was
certified. The checker never imports the solver: callables are imported by name at run
time, in the worker process.

Examples
--------
>>> from fractions import Fraction
>>> from dppverify.audit import AuditConfig, run_audit
>>> def stay_put(doc):           # a wrong solver: the Attacker never moves
...     goals, prior = doc["goals"], [Fraction(p) for p in doc["prior"]]
...     g1, g2 = goals if prior[0] >= prior[1] else goals[::-1]
...     stay = [{"path": [doc["start"]], "probability": 1}]
...     return {"format": "dpp-profile/1", "goals": {"primary": g1, "secondary": g2},
...             "defender": {"rule": "progress", "goal": g1},
...             "attacker": {"primary": stay, "secondary": stay}}
>>> report = run_audit(stay_put, AuditConfig(examples=50, seed=1))
>>> report.passed, report.failure.check
(False, 'profile.wellformed')
>>> inst = report.failure.instance       # shrunk: a tiny instance, start off the goals
>>> inst["start"] in inst["goals"], len(inst["graph"]["nodes"]) <= 4
(False, True)
"""

from __future__ import annotations

from typing import Any

from dppverify.audit.config import (
    AUDIT_MAX_PREFIXES,
    AUDIT_TRIALS,
    DEFAULT_SHRINK_CALLS,
    DEFAULT_SHRINK_SECONDS,
    DEFAULT_TIMEOUT,
    AuditConfig,
    ShrinkBudget,
)
from dppverify.audit.examine import Outcome, examine
from dppverify.audit.pruning import prune_failure
from dppverify.audit.report import AuditReport, format_report, write_failure
from dppverify.audit.runner import Answer, CommandRunner, PythonRunner, SolverRunner
from dppverify.errors import AuditError

__all__ = ["AUDIT_MAX_PREFIXES", "AUDIT_TRIALS", "DEFAULT_SHRINK_CALLS", "DEFAULT_SHRINK_SECONDS",
           "DEFAULT_TIMEOUT", "Answer", "AuditConfig", "AuditError", "AuditReport",
           "CommandRunner", "Outcome", "PythonRunner", "ShrinkBudget", "SolverRunner",
           "audit_instances", "examine", "format_report", "prune_failure", "run_audit",
           "write_failure"]


def __getattr__(name: str) -> Any:
    """``run_audit`` and ``audit_instances`` load hypothesis: imported on first use."""
    if name in ("run_audit", "audit_instances"):
        from dppverify.audit import campaign

        return getattr(campaign, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
