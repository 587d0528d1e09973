"""Sphinx configuration of rocketsim's site: MyST Markdown pages under docs/, the
reference generated from the code (the command line by sphinx-click, the Python API by
autodoc, the file formats by docs/_ext/rocketsim_docs.py).

Build: ``python -m sphinx -W --keep-going -n -b html docs docs/_build/html``
(warnings are errors, every cross-reference must resolve; tests/docs/test_docs_site.py
builds it so on every run of the suite).
"""

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))

from rocketsim.version import __version__  # noqa: E402

project = "rocketsim"
author = "the rocketsim authors"
copyright = "the rocketsim authors, MIT licence"
version = release = __version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx_click",
    "rocketsim_docs",
]

source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
root_doc = "index"
exclude_patterns = ["_build", "_ext", "**/.ipynb_checkpoints"]

# MyST: ``$...$`` maths, definition lists, ``{attribute}`` fences, and anchors for the
# headings a page's links name (``physics.md#input-bounds``).
myst_enable_extensions = ["dollarmath", "deflist", "colon_fence", "attrs_block"]
myst_heading_anchors = 4

# Every reference must resolve: a docstring's :func: to a moved name fails the build.
# Other libraries' names (numpy's arrays, pandas' frames, the standard library's paths)
# are not linked: their inventories (intersphinx) would need the network at build time.
nitpicky = True
# The command line's help and the docstrings hold commands to copy: ``--to`` stays two
# hyphens and quotes stay straight.
smartquotes = False
nitpick_ignore_regex = [
    (r"py:.*", r"(numpy|np|pandas|pd|pathlib|datetime|dt|click|matplotlib|collections|typing"
               r"|concurrent|os|io|dask|distributed|xarray|mcap|greenlet)(\..*)?"),
    (r"py:class", r"(ndarray|DataFrame|Path|datetime|Figure|Axes|Callable|Iterable|Iterator"
                  r"|Sequence|Mapping|Any|TextIO|BinaryIO|PathLike)"),
    # pieces of a builtin generic (``dict[str, dict[str, str]]``) that Sphinx splits
    # a dataclass field's type at
    (r"py:class", r"(dict|list|tuple|set)\[.*"),
]

autodoc_member_order = "bysource"
autodoc_typehints = "signature"
autodoc_preserve_defaults = True

html_theme = "furo"
html_title = f"rocketsim {release}"

# what a tutorial's code prints, set apart from the code ({output} blocks)
html_static_path = ["_static"]
html_css_files = ["output.css"]
