"""The human-readable certificate that ``dpp certify`` prints without ``--json``.

One header line (the verdict, the game, the tallies), then one row per check of kind
``check``, then the consistency checks and the facts under their own headings
(:data:`CONSISTENCY_HEADING`, :data:`FACTS_HEADING`), and last the exploitability (every
player's exact regret and NashConv, :mod:`dppverify.exploitability`).
"""

from __future__ import annotations

from dppio.text import count, show
from dppverify.certificate import Certificate, CheckRecord

NUMBERS_WIDTH = 44

CONSISTENCY_HEADING = ("consistency checks (the checker's own computations compared; a failure "
                       "is the checker's fault, not counted above):")

FACTS_HEADING = ("facts about the profile and the instance (the paper's lemmas, whether this is "
                 "the paper's construction; reported beside the verdict, never deciding it):")


def _numbers(rec: CheckRecord) -> list[str]:
    """The record's numbers as ``key=value`` items, wrapped into lines of NUMBERS_WIDTH.

    Nothing is cut: a number too long for a line is shown as a decimal (``text.show``); its
    exact form is in the ``--json`` certificate.
    """
    lines: list[str] = []
    for item in (f"{k}={show(v)}" for k, v in rec.numbers.items() if v is not None):
        if lines and len(lines[-1]) + 1 + len(item) <= NUMBERS_WIDTH:
            lines[-1] += " " + item
        else:
            lines.append(item)
    return lines or [""]


def format_table(cert: Certificate) -> str:
    """The human-readable certificate: a header line and one row per check.

    Parameters
    ----------
    cert : Certificate
        The result of :func:`~dppverify.certify.certify`.

    Returns
    -------
    str
        What ``dpp certify`` prints without ``--json``.

    Examples
    --------
    >>> from dppverify import certify
    >>> from dppverify.game.examples import triangle_document
    >>> profile = {"format": "dpp-profile/1", "goals": {"primary": "g1", "secondary": "g2"},
    ...     "defender": {"rule": "progress", "goal": "g1"},
    ...     "attacker": {"primary": [{"path": ["s", "g1"], "probability": "4/7"},
    ...                              {"path": ["s", "g2"], "probability": "3/7"}],
    ...                  "secondary": [{"path": ["s", "g2"], "probability": 1}]}}
    >>> lines = format_table(certify(triangle_document(), profile, horizon=1)).splitlines()
    >>> lines.index(CONSISTENCY_HEADING) < lines.index(FACTS_HEADING), "..." in "".join(lines)
    (True, False)
    >>> for line in lines[:2] + lines[6:8]:  # doctest: +NORMALIZE_WHITESPACE
    ...     print(line)
    verdict: PASS for the game truncated at H = 1 (11/11 checks passed; 2/2 consistency checks
      agree; 6/6 facts hold; 3 prefixes, exact; LP CLARABEL agreement within 1e-07 relative)
    note: this certifies the game truncated at H = 1 only, not the full (untruncated) game;
      omit the horizon to certify the untruncated game
    value.U    pass    U=12/5 U_lp=2.4 U_tree=12/5  U = 12/5, LP evaluation 2.4
    value.VoI  pass    U_bar=27/10 VoI=1/9          Ū = 27/10, VoI = 1/9
    >>> format_table(certify(triangle_document(), profile)).splitlines()[0][:50]
    'verdict: PASS for the untruncated game (H = inf) ('
    >>> print(lines[-1])  # doctest: +NORMALIZE_WHITESPACE
    exploitability on the game truncated at H = 1: NashConv 0 = Attacker 0 (type regrets: g1 0,
      g2 0, weighted by the prior) + Defender 0
    """
    game = cert.game_line()
    evidence = [(c.id, c.status, _numbers(c), c.message) for c in cert.of_kind("check")]
    own = [(c.id, c.status, _numbers(c), c.message) for c in cert.of_kind("consistency")]
    facts = [(c.id, c.status, _numbers(c), c.message) for c in cert.of_kind("fact")]
    rows = [("check", "status", ["numbers"], "message"), *evidence, *own, *facts]
    w0 = max(len(r[0]) for r in rows)
    w1 = max(len(r[1]) for r in rows)
    w2 = max(len(x) for r in rows for x in r[2])

    def row(a: str, b: str, c: list[str], d: str) -> list[str]:
        first = f"{a:<{w0}}  {b:<{w1}}  {c[0]:<{w2}}  {d}".rstrip()
        return [first, *(f"{'':<{w0}}  {'':<{w1}}  {x}".rstrip() for x in c[1:])]

    note = cert.truncation_note()
    lines = [_header(cert)] + ([f"note: {note}"] if note else [])
    for r in rows[:1 + len(evidence)]:
        lines += row(*r)
    for heading, group in ((CONSISTENCY_HEADING, own), (FACTS_HEADING, facts)):
        if group:
            lines.append(heading)
            for r in group:
                lines += row(*r)
    if cert.exploitability is not None:
        lines.append(f"exploitability on {game}: {cert.exploitability.summary()}")
    return "\n".join(lines)



def _header(cert: Certificate) -> str:
    """The verdict line: the game, the tallies, the route and the number mode."""
    counts = cert.counts()
    passed, total = counts["check"]
    tally = f"{passed}/{total} checks passed"
    if counts["consistency"][1]:
        tally += "; {}/{} consistency checks agree".format(*counts["consistency"])
    if counts["fact"][1]:
        tally += "; {}/{} facts hold".format(*counts["fact"])
    mode = "exact" if cert.exact else f"float mode, relative tolerance {cert.tolerance:g}"
    game = cert.game_line()
    if cert.route == "structured":
        skipped = f"; not run: {', '.join(cert.not_run)}" if cert.not_run else ""
        return (f"verdict: {cert.verdict.upper()} for {game} ({tally}; structured route (no "
                f"walk tree), {mode}{skipped})")
    both = ", both routes" if cert.route == "both" else ""
    return (f"verdict: {cert.verdict.upper()} for {game} ({tally}; "
            f"{count(cert.prefixes, 'prefix')}{both}, {mode}; LP "
            f"{cert.lp_solver} agreement within {cert.lp_tolerance:g} relative)")
