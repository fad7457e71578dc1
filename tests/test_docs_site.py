"""The documentation site (``python3 dev.py docs``): it builds with warnings as errors, and what
a reader sees is whole — offline too.

The site is built once per test session (the ``site`` fixture; the tests of this module run on
one worker, ``xdist_group``) and then inspected as HTML:

- every formula of the Markdown sources is a math node (a display formula ``$$…$$`` a display
  node), no raw ``$``, ``\\(`` or ``\\[`` is left in the text a reader sees, and MathJax is
  loaded from the site itself (``_static/mathjax``), never from the network;
- every image and every internal link (file and ``#anchor``) resolves inside the build;
- the notebook is a page with the outputs of its build-time execution;
- in a headless Chromium (Debian's ``chromium``, installed by ``.ci/run``; skipped with the
  reason where it is absent) the front page, a proof page, the notebook page and an API page
  render every formula with MathJax, offline, with no MathJax error, and a screenshot is taken.
"""

from __future__ import annotations

import fcntl
import importlib.util
import os
import re
import shutil
import subprocess
import sys
from collections.abc import Iterator
from html import unescape
from html.parser import HTMLParser
from pathlib import Path
from typing import ClassVar
from urllib.parse import unquote, urlsplit

import pytest

from tests import _guard
from tests.test_docstrings import public_modules

ROOT = Path(__file__).resolve().parents[1]
pytestmark = pytest.mark.xdist_group("site")  # one build, on one worker (dev.py: loadfile)

RENDERED_PAGES = ("docs/site/index.html", "proofs/DP.html", "examples/workflow.html",
                  "docs/site/_generated/dppverify.html")
"""The pages the browser test renders: the front page, a proof, the notebook, an API page."""


def _dev() -> object:
    spec = importlib.util.spec_from_file_location("dev", ROOT / "dev.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="session")
def site() -> Path:
    """The site, built once: ``dev.py docs``'s own command (warnings are errors)."""
    # One build per test run, whichever worker asks first (xdist_group keeps most of these
    # tests on one worker, not always all): the workers of a run share PYTEST_XDIST_TESTRUNUID,
    # and autosummary writes into the checkout (docs/site/_generated), so builds take a lock.
    run = os.environ.get("PYTEST_XDIST_TESTRUNUID") or f"solo-{os.getpid()}"
    base = ROOT / "docs" / "_build"
    base.mkdir(parents=True, exist_ok=True)
    out = base / f"test-site-{run}"
    with open(base / "test-site.lock", "w") as handle:
        fcntl.flock(handle, fcntl.LOCK_EX)
        if (out / "built").is_file():
            return out
        for old in base.glob("test-site-*"):  # earlier runs' sites
            shutil.rmtree(old, ignore_errors=True)
        cmd = _dev().docs_command(out, python=sys.executable)  # type: ignore[attr-defined]
        proc = _guard.run(cmd, capture_output=True, text=True, cwd=ROOT)  # no clock: CPU-guarded
        if proc.returncode != 0:
            pytest.fail((proc.stdout + proc.stderr)[-5000:], pytrace=False)
        (out / "built").write_text(run)
    return out


class _Page(HTMLParser):
    """One HTML page: its ids, its references (``href``/``src``), its math nodes and the text a
    reader sees outside math, code and scripts."""

    HIDDEN: ClassVar[set[str]] = {"script", "style", "pre", "code", "textarea"}
    VOID: ClassVar[set[str]] = {"area", "base", "br", "col", "embed", "hr", "img", "input",
                                "link", "meta", "source", "track", "wbr"}

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.ids: set[str] = set()
        self.refs: list[tuple[str, str]] = []
        self.scripts: list[str] = []
        self.math_inline = self.math_display = 0
        self.text: list[str] = []
        self._stack: list[bool] = []  # per open element: inside math or code

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        a = {k: v or "" for k, v in attrs}
        if "id" in a:
            self.ids.add(a["id"])
        for key in ("href", "src"):
            if a.get(key):
                self.refs.append((tag, a[key]))
        if tag == "script" and a.get("src"):
            self.scripts.append(a["src"])
        classes = a.get("class", "").split()
        math = "math" in classes and tag in ("span", "div")
        if math:
            self.math_display += tag == "div"
            self.math_inline += tag == "span"
        if tag in self.VOID:
            return
        hidden = (math or tag in self.HIDDEN or "pre" in classes  # autodoc's values
                  or "highlight" in " ".join(classes))
        self._stack.append(hidden or (bool(self._stack) and self._stack[-1]))

    def handle_endtag(self, tag: str) -> None:
        if tag not in self.VOID and self._stack:
            self._stack.pop()

    def handle_data(self, data: str) -> None:
        if not (self._stack and self._stack[-1]):
            self.text.append(data)


def _pages(site: Path) -> Iterator[tuple[Path, _Page]]:
    for path in sorted(site.rglob("*.html")):
        if "_sources" in path.parts or "_static" in path.parts:
            continue
        page = _Page()
        page.feed(path.read_text(encoding="utf-8"))
        yield path, page


def _display_formulas(markdown: str) -> int:
    """The ``$$…$$`` formulas of a Markdown text, outside code blocks and code spans."""
    text = re.sub(r"^```.*?^```", "", markdown, flags=re.S | re.M)
    text = re.sub(r"`[^`\n]*`", "", text)
    return text.count("$$") // 2


def test_the_site_builds_with_the_guides_proofs_notebook_and_api(site: Path) -> None:
    assert (site / "index.html").is_file() and (site / "docs/site/index.html").is_file()
    for page in ("README.html", "docs/formats.html", "docs/experiments.html",
                 "proofs/NGOAL.html", "CHANGELOG.html", "dppverify/checks.html",
                 "examples/workflow.html"):
        assert (site / page).is_file(), page
    images = {p.name for p in (site / "_images").iterdir()}
    assert {"paper10_map.png", "paper10_beliefs.png", "baselines.png",
            "paper10_equilibrium.png", "voi_density.png"} <= images
    assert 'src="../_images/paper10_map.png"' in (site / "docs/experiments.html").read_text()
    assert 'src="_images/paper10_map.png"' in (site / "README.html").read_text()
    # the API reference, from the docstrings (numpy sections rendered as fields)
    # exactly the public modules of docs/cli.md "Python API", each with its __all__
    api = (site / "docs/site/_generated/dppverify.html").read_text()
    assert 'id="dppverify.certify"' in api and "Parameters" in api and "Examples" in api
    generated = {p.stem for p in (site / "docs/site/_generated").glob("*.html")}
    assert generated == set(public_modules()), generated ^ set(public_modules())


def test_every_formula_is_math_and_no_raw_dollar_is_left(site: Path) -> None:
    unrendered, display = [], []
    for path, page in _pages(site):
        name = path.relative_to(site).as_posix()
        text = "".join(page.text)
        for marker in ("$", "\\(", "\\["):
            if marker in text:
                i = text.index(marker)
                unrendered.append(f"{name}: {marker!r} in …{text[max(0, i - 60):i + 40]!r}…")
        source = ROOT / Path(name).with_suffix(".md")
        if source.is_file() and page.math_display < _display_formulas(source.read_text()):
            display.append(f"{name}: {page.math_display} display formulas, the source has "
                           f"{_display_formulas(source.read_text())}")
    assert not unrendered, "\n".join(unrendered)
    assert not display, "\n".join(display)
    proof = _Page()
    proof.feed((site / "proofs/DP.html").read_text())
    assert proof.math_display >= 6 and proof.math_inline > 200


def test_math_is_served_by_the_site_itself(site: Path) -> None:
    mathjax = site / "_static" / "mathjax" / "tex-chtml.js"
    assert mathjax.is_file() and mathjax.stat().st_size > 100_000
    fonts = list((site / "_static" / "mathjax" / "output" / "chtml" / "fonts").rglob("*.woff"))
    assert fonts, "MathJax's CHTML fonts are not in the site"
    with_math = 0
    for path, page in _pages(site):
        remote = [s for s in page.scripts if urlsplit(s).scheme or s.startswith("//")]
        assert not remote, (path, remote)
        if page.math_inline or page.math_display:
            with_math += 1
            local = [s for s in page.scripts if "mathjax/tex-chtml.js" in s]
            assert local, f"{path} has math but loads no MathJax"
            assert (path.parent / urlsplit(local[0]).path).resolve() == mathjax.resolve()
    assert with_math >= 20


def test_every_image_and_internal_link_resolves(site: Path) -> None:
    pages = dict(_pages(site))
    broken = []
    for path, page in pages.items():
        for tag, ref in page.refs:
            parts = urlsplit(ref)
            if parts.scheme in ("http", "https", "mailto") or ref.startswith("//"):
                continue
            if parts.scheme:
                broken.append(f"{path.relative_to(site)}: <{tag}> {ref} (scheme)")
                continue
            target = (path.parent / unquote(parts.path)).resolve() if parts.path else path
            if not target.exists():
                broken.append(f"{path.relative_to(site)}: <{tag}> {ref} (no such file)")
            elif parts.fragment and target in pages and parts.fragment not in pages[target].ids:
                broken.append(f"{path.relative_to(site)}: <{tag}> {ref} (no such anchor)")
    assert not broken, "\n".join(broken)
    assert sum(len(p.refs) for p in pages.values()) > 1000


def test_the_notebook_is_a_page_with_its_outputs(site: Path) -> None:
    """The notebook ran at build time, in a fresh folder (the map by its bundled name), every
    cell without an error, and shows the results it describes."""
    html = (site / "examples" / "workflow.html").read_text()
    shown = unescape(html)
    assert html.count('class="cell_output') >= 10 and "Traceback" not in shown
    assert "map: paper10.map" in shown
    assert "Fraction(68, 5)" in shown and "Fraction(5, 22)" in shown  # U*, VoI* exactly
    assert "('pass', {'horizon': 'inf', 'truncated': False})" in shown
    assert "wrote p3.json: U = 34/3" in shown and "('dpp-value/1', 3, '34/3', True" in shown
    assert not (ROOT / "examples" / "p3.json").exists()  # nothing written into the checkout
    images = re.findall(r'<img [^>]*src="\.\./_images/([0-9a-f]+\.png)"', html)
    assert len(images) == 2
    for name in images:
        assert (site / "_images" / name).stat().st_size > 10_000
    index = (site / "docs" / "site" / "index.html").read_text()
    assert 'href="../../examples/workflow.html"' in index


CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
CHROMIUM_FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                  "--no-first-run", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync", "--hide-scrollbars")


def _chromium(page: Path, profile: Path, *extra: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [str(CHROMIUM), *CHROMIUM_FLAGS, f"--user-data-dir={profile}",
         "--virtual-time-budget=20000", *extra, page.as_uri()],
        capture_output=True, text=True, timeout=180)


@pytest.mark.skipif(CHROMIUM is None, reason="no chromium on this machine (.ci/run installs "
                                             "Debian's chromium; apt-get install chromium)")
@pytest.mark.parametrize("name", RENDERED_PAGES)
def test_the_page_renders_its_formulas_in_a_browser(site: Path, name: str,
                                                    tmp_path: Path) -> None:
    page = _Page()
    page.feed((site / name).read_text())
    proc = _chromium(site / name, tmp_path / "profile", "--dump-dom")
    assert proc.returncode == 0, proc.stderr[-2000:]
    dom = proc.stdout
    assert "<title>" in dom
    containers = dom.count("<mjx-container")
    assert containers == page.math_inline + page.math_display, (containers, name)
    assert "<mjx-merror" not in dom  # a formula MathJax could not parse
    rendered = _Page()
    rendered.feed(re.sub(r"<mjx-container.*?</mjx-container>", "", dom, flags=re.S))
    shown = "".join(rendered.text)
    assert "\\(" not in shown and "$$" not in shown
    shot = tmp_path / "page.png"
    proc = _chromium(site / name, tmp_path / "profile", f"--screenshot={shot}",
                     "--window-size=1200,1600")
    assert proc.returncode == 0 and shot.stat().st_size > 20_000, proc.stderr[-2000:]
