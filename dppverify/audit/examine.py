"""One audited example: run the solver on an instance and certify its answer.

Examples
--------
>>> doc = {"graph": {"nodes": [{"id": 0}, {"id": 1}], "edges": []}, "start": 0,
...        "goals": [0, 1], "prior": ["1/2", "1/2"]}
>>> examine(lambda d: 1 / 0, doc).message
'the solver raised ZeroDivisionError: division by zero'
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from dppverify.audit.config import DEFAULT_CONFIG, AuditConfig
from dppverify.audit.runner import Answer, SolverRunner, call_in_process, one_line
from dppverify.certificate import Certificate
from dppverify.certify import certify
from dppverify.errors import CheckerError, ProfileError, TreeTooLargeError, UndecidedError
from dppverify.formats.json_reading import parse_json

Doc = dict[str, Any]


@dataclass(frozen=True)
class Outcome:
    """The audit of one instance.

    Attributes
    ----------
    instance : dict
        The instance document given to the solver.
    profile : object
        What the solver returned, after a JSON round trip (None if it failed to answer with
        a JSON object).
    certificate : Certificate or None
        The checker's certificate (None when the profile could not be certified at all).
    check : str
        The first failing check id, or ``solver.error`` / ``solver.timeout`` /
        ``solver.output`` / ``profile.format``; empty when the example passed.
    message : str
        One line for humans.
    traceback : str
        The solver's traceback when it raised (written to ``failure.json``).
    where : str
        ``Type@file:line`` of the exception the solver raised (empty otherwise).
    """

    instance: Doc
    profile: Any
    certificate: Certificate | None
    check: str = ""
    message: str = ""
    traceback: str = ""
    where: str = ""

    @property
    def passed(self) -> bool:
        """True when the profile was certified (verdict ``pass``)."""
        return self.check == ""

    @property
    def identity(self) -> str:
        """What makes two failures the same failure (as hypothesis tells them apart): the
        failing check id, or for a solver that raised, ``solver.error:Type@file:line`` (the
        exception type and the place it was raised). Shrinking keeps it fixed.

        Examples
        --------
        >>> from dppverify.game.examples import triangle_document
        >>> examine(lambda d: {"format": "dpp-profile/2"}, triangle_document()).identity
        'profile.format'
        >>> examine(lambda d: 1 / 0, triangle_document()).identity  # doctest: +ELLIPSIS
        'solver.error:ZeroDivisionError@<doctest ...>:1'
        """
        return f"{self.check}:{self.where}" if self.where else self.check


def examine(solver: SolverRunner | Callable[[Doc], Any], doc: Doc,
            config: AuditConfig = DEFAULT_CONFIG) -> Outcome:
    """Solve ``doc`` with ``solver`` and certify the answer (``config``'s ``max_prefixes``,
    ``trials`` and ``seed``).

    ``solver`` is a :class:`~dppverify.audit.runner.SolverRunner` (isolated, as
    :func:`~dppverify.audit.run_audit` uses) or a plain callable, called in this process.

    Raises :class:`~dppverify.errors.TreeTooLargeError` when the walk tree exceeds
    ``config.max_prefixes`` (the caller skips the example); everything the solver does wrong
    is an :class:`Outcome` with ``passed`` False.

    Parameters
    ----------
    solver : SolverRunner or callable
        The solver under test.
    doc : dict
        The instance document given to it.
    config : AuditConfig
        The certification options (``max_prefixes``, ``trials``, ``seed``).

    Returns
    -------
    Outcome
        The instance, the solver's profile, its certificate and the first failing check (empty
        when it passed).

    Raises
    ------
    TreeTooLargeError
        The walk tree is larger than ``config.max_prefixes`` (the caller skips the example).

    Examples
    --------
    >>> from dppverify.game.examples import triangle_document
    >>> examine(lambda d: {"format": "dpp-profile/2"}, triangle_document()).check
    'profile.format'
    """
    answer: Answer = solver(doc) if isinstance(solver, SolverRunner) else call_in_process(
        solver, doc)
    if answer.text is None:
        return Outcome(doc, None, None, answer.check, answer.message, answer.traceback,
                       answer.where)
    try:
        profile = parse_json(answer.text)
    except (ValueError, RecursionError) as exc:
        return Outcome(doc, None, None, "solver.output",
                       f"the solver's profile is not JSON: {one_line(exc)}")
    if not isinstance(profile, dict):
        return Outcome(doc, None, None, "solver.output",
                       f"the solver's profile is {type(profile).__name__}, not a JSON object")
    try:
        cert = certify(doc, profile, max_prefixes=config.max_prefixes, trials=config.trials,
                       seed=config.seed)
    except TreeTooLargeError:
        raise
    except UndecidedError as exc:  # never a pass: the game cannot be decided for the profile
        return Outcome(doc, profile, None, "certify.undecided", one_line(exc))
    except ProfileError as exc:
        return Outcome(doc, profile, None, "profile.format", one_line(exc))
    except CheckerError as exc:  # e.g. a horizon or instance problem caused by the profile
        return Outcome(doc, profile, None, "profile.format", one_line(exc))
    if cert.passed:
        return Outcome(doc, profile, cert)
    bad = [c for c in cert.checks if c.status != "pass" and c.kind != "fact"]
    first = next((c for c in bad if c.status == "fail"), bad[0])
    return Outcome(doc, profile, cert, first.id,
                   f"verdict {cert.verdict}: {first.status} {first.id}: {first.message}")
