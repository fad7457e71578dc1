"""Sphinx configuration of the documentation site (``python3 dev.py docs``).

The source folder is the repository root, so the Markdown pages keep the links they have on
GitHub: ``README.md`` is the home page, ``docs/*.md`` the guides, ``proofs/*.md`` the proofs,
``dppverify/checks.md`` the check ids, ``CHANGELOG.md``; ``docs/site/`` holds the few pages
only the site needs (the table of contents, the API reference). MyST reads the Markdown,
autodoc and autosummary the docstrings, numpydoc their numpy-style sections. Warnings are
errors (``dev.py docs`` passes ``-W``).
"""

from __future__ import annotations

import importlib.util
import shutil
import sys
import types
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from dppverify.version import __version__  # noqa: E402

project = "dppverify"
author = "The dppverify developers"
copyright = "2026, The dppverify developers"
version = release = __version__

root_doc = "docs/site/index"
include_patterns = ["README.md", "CHANGELOG.md", "docs/*.md", "docs/site/**",
                    "proofs/*.md", "dppverify/checks.md", "examples/workflow.ipynb"]
exclude_patterns = ["docs/_build/**", ".venv/**", "docs/site/_templates/**",
                    "docs/site/_extra/**"]

extensions = [
    "myst_nb",  # MyST Markdown (it loads myst_parser) and the notebook, executed at build time
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx.ext.napoleon",  # reads the numpy-style sections (numpydoc's format), fast
]
# .rst first: autosummary writes its pages with the first suffix; myst-nb reads the Markdown
# (as MyST) and the notebook
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
myst_heading_anchors = 3
# dollarmath: $...$ and $$...$$ as on GitHub, $$...$$ also inside a paragraph (the proofs write
# their display formulas on the line after the text); html_image: <img> tags become images
# whose files are copied into the site (the README's and docs/overview.md's figures)
myst_enable_extensions = ["dollarmath", "html_image"]
myst_dmath_double_inline = True

# the notebook is executed on every build, in a fresh temporary folder (it reads the bundled
# examples by name and writes its files there, never into the checkout); a cell that raises
# fails the build
nb_execution_mode = "force"
nb_execution_in_temp = True
nb_execution_timeout = 600
nb_execution_raise_on_error = True
nb_merge_streams = True

autosummary_generate = True
# autosummary writes its pages into docs/site/_generated and never deletes one: start afresh,
# so a module renamed since the last build leaves no stale page behind
shutil.rmtree(ROOT / "docs" / "site" / "_generated", ignore_errors=True)
autosummary_imported_members = False
autodoc_default_options = {"members": True, "show-inheritance": True}
autodoc_typehints = "none"  # the Parameters sections say the types
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False

# a module page: its docstring, its members, its submodules
templates_path = [str(ROOT / "docs/site/_templates")]
# a module's page documents exactly its __all__ (the public modules: docs/cli.md "Python API");
# the front doors' names are indexed there, their home modules' pages are not indexed again


def _skip_aliases(app: object, what: str, name: str, obj: object, skip: bool,
                  options: object) -> bool | None:
    """Leave out type aliases such as ``Normal = tuple[int, ...]`` (autodoc cannot sign them)."""
    return True if isinstance(obj, types.GenericAlias) else None


def setup(app: Any) -> None:
    app.connect("autodoc-skip-member", _skip_aliases)


html_theme = "alabaster"
html_title = f"dppverify {release}"
# MathJax 3 from the sphinx-mathjax-offline package (the docs extra), copied into _static and
# loaded from there: every formula renders offline, no CDN. (Its Sphinx extension does the same
# but declares no parallel safety, which would make the build read serially.)
_MATHJAX = importlib.util.find_spec("sphinx-mathjax-offline")
if _MATHJAX is None or _MATHJAX.origin is None:
    raise ImportError("the site needs sphinx-mathjax-offline: pip install -e '.[docs]'")
html_static_path = [str(Path(_MATHJAX.origin).parent / "static")]
mathjax_path = "mathjax/tex-chtml.js"
html_extra_path = ["site/_extra"]  # index.html: the site's front page at the top of the build
suppress_warnings = [
    "myst.header",  # the proofs number their sections freely (### under #)
    # the two packages define the same names on purpose (each its own Instance, errors,
    # numbers: docs/architecture.md, "What stays twice"), so an unqualified type in a
    # docstring has two targets; the link goes to one of them
    "ref.python",
]
