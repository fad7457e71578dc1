"""The one normalizer of the CLI pins: blank out what legitimately varies between runs.

What varies, and what it becomes:

- timings: ``"seconds": 0.007`` (JSON) and ``0.01 s`` (text) → ``"<SECONDS>"`` / ``<T> s``;
- versions: ``"version": "0.1.0"``, ``"dppverify": "0.1.0"`` → ``"<VERSION>"``, and
  ``dppverify 0.1.0`` in text → ``dppverify <VERSION>``;
- dates and ISO timestamps → ``<DATE>``; 40-hex commit hashes → ``<COMMIT>`` (a file's
  sha256, 64 hex digits, is the file's content and is kept);
- the run's temporary directory and the repository → ``<WORK>`` / ``<REPO>``; the hostname;
- floats printed with 9 or more decimals (an LP solver's float value, a float-mode value) →
  7 significant digits: the exact results are fractions and stay as they are, and an LP's
  float depends on the order of its constraints in the last digits;
- in-process runs only: the certificate's ``provenance.command`` (from ``sys.argv``, which is
  the test runner's, or click's parameters) → ``"<COMMAND>"``; subprocess runs keep it.

Examples
--------
>>> normalize('{"seconds": 0.012, "value_lp": 2.4000000000012456}')
'{"seconds": "<SECONDS>", "value_lp": 2.4}'
>>> normalize("LP value 1.50000000005 (CLARABEL, 3 prefixes, 0.01 s)")
'LP value 1.5 (CLARABEL, 3 prefixes, <T> s)'
>>> normalize('"command": ["dpp", "certify", "x=[1]"]', in_process=True)
'"command": "<COMMAND>"'
"""

from __future__ import annotations

import re
import socket
from pathlib import Path

__all__ = ["normalize"]

REPO = Path(__file__).resolve().parent.parent.parent

_JSON_STRING = r'"(?:[^"\\]|\\.)*"'
_SECONDS = re.compile(r'"(seconds|elapsed|elapsed_seconds|duration|wall_time|time)": '
                      r'-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?')
_VERSION = re.compile(r'"(version|dppverify|solver_version)": "\d+\.\d+[^"]*"')
_TEXT_VERSION = re.compile(r"\b(dppverify|solver|dpp) (?:version )?\d+\.\d+\.\d+"
                           r"(?:[.+-][0-9A-Za-z]+)*")
_TEXT_SECONDS = re.compile(r"\b\d+\.\d+ ?s\b")
_DATE = re.compile(r"\b\d{4}-\d{2}-\d{2}(?:[T ]\d{2}:\d{2}(?::\d{2}(?:\.\d+)?)?"
                   r"(?:Z|[+-]\d{2}:?\d{2})?)?\b")
_COMMIT = re.compile(r"(?<![0-9a-f])[0-9a-f]{40}(?![0-9a-f])")
_LONG_FLOAT = re.compile(r"(?<![\w.])-?\d+\.\d{9,}(?:[eE][-+]?\d+)?(?![\w.])")
_COMMAND = re.compile(rf'"command": (?:null|\[(?:\s*{_JSON_STRING}\s*,?)*\s*\])')


def _short_float(match: re.Match[str]) -> str:
    return f"{float(match.group(0)):.7g}"


def normalize(text: str, *, workdir: str | Path | None = None, in_process: bool = False) -> str:
    """``text`` (a command's stdout, stderr or output file) with the volatile parts replaced.

    Parameters
    ----------
    text : str
        The raw text.
    workdir : str or Path, optional
        The run's temporary working directory (replaced by ``<WORK>``).
    in_process : bool
        Whether the command ran in this process (then ``provenance.command`` is blanked).

    Examples
    --------
    >>> normalize("wrote /tmp/x1/p.json in 0.35 s", workdir="/tmp/x1")
    'wrote <WORK>/p.json in <T> s'
    """
    if workdir is not None:
        for form in {str(Path(workdir).resolve()), str(workdir)}:
            text = text.replace(form, "<WORK>")
    text = text.replace(str(REPO), "<REPO>")
    host = socket.gethostname()
    if len(host) >= 4:
        text = text.replace(host, "<HOST>")
    if in_process:
        text = _COMMAND.sub('"command": "<COMMAND>"', text)
    text = _SECONDS.sub(lambda m: f'"{m.group(1)}": "<SECONDS>"', text)
    text = _VERSION.sub(lambda m: f'"{m.group(1)}": "<VERSION>"', text)
    text = _TEXT_VERSION.sub(lambda m: f"{m.group(1)} <VERSION>", text)
    text = _DATE.sub("<DATE>", text)
    text = _COMMIT.sub("<COMMIT>", text)
    text = _LONG_FLOAT.sub(_short_float, text)
    return _TEXT_SECONDS.sub("<T> s", text)
