"""Sphinx configuration of leadscrew's documentation site.

Build it (warnings as errors, as tests/test_docs.py does):
``python -m sphinx -W -b html docs docs/_build/html``.
"""

import leadscrew

project = "leadscrew"
copyright = "the leadscrew developers"
author = "the leadscrew developers"
release = version = leadscrew.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "generated/*.md", "physics/*.py"]
myst_enable_extensions = ["dollarmath"]
myst_heading_anchors = 3

autosummary_generate = True
templates_path = ["_templates"]  # a class page documents its members
autodoc_typehints = "description"
napoleon_google_docstring = True
napoleon_numpy_docstring = False
autodoc_inherit_docstrings = False  # an Executor's submit: the standard library's text
napoleon_use_ivar = True  # a class's Attributes as fields, not a second description

html_theme = "alabaster"
html_title = f"leadscrew {release}"


def public_names():
    """Every public name: ``leadscrew.__all__`` and, for each public module
    in it, the names of its ``__all__`` that are not the same object as a
    top-level name (documented once, under the shorter name)."""
    import importlib
    import types

    top = {}
    for name in leadscrew.__all__:
        top[f"leadscrew.{name}"] = getattr(leadscrew, name)
    names = list(top)
    seen = {id(value) for value in top.values() if not isinstance(value, types.ModuleType)}
    for name, value in list(top.items()):
        if not isinstance(value, types.ModuleType):
            continue
        module = importlib.import_module(name)
        for member in getattr(module, "__all__", []):
            obj = getattr(module, member)
            if id(obj) in seen or isinstance(obj, types.ModuleType):
                continue
            seen.add(id(obj))
            names.append(f"{name}.{member}")
    return names


def write_api_page(app, config=None):
    """docs/api.rst: an autosummary of every public name, each its own page
    (generated/), written anew at each build so that it cannot drift."""
    import pathlib

    lines = ["API reference", "=============", "",
             "Every public name of the package, each with its page from its docstring.", "",
             ".. autosummary::", "   :toctree: generated", ""]
    lines += [f"   {name}" for name in public_names()]
    pathlib.Path(app.srcdir, "api.rst").write_text("\n".join(lines) + "\n", encoding="utf-8")


def plain_text_docstring(app, what, name, obj, options, lines):
    """The docstrings are plain text read in a terminal: |x| is an absolute
    value (on one line or two), not a reStructuredText substitution; a
    constant's docstring is its own comment, not its type's (a dict's)."""
    import re

    if what in ("data", "attribute") and lines and obj.__doc__ == type(obj).__doc__:
        lines[:] = []
        return
    text = "\n".join(lines)
    text = re.sub(r"(?<![|\\])\|(?=[^|\s`])((?:[^|`\n]|\n(?!\s*\n))*?[^|\s`])\|(?!\|)",
                  r"\\|\1\\|", text)
    lines[:] = text.split("\n")


def setup(app):
    # At config-inited: before Sphinx lists the source files (a fresh clone
    # has no api.rst yet) and autosummary writes the pages it lists.
    app.connect("config-inited", write_api_page)
    app.connect("autodoc-process-docstring", plain_text_docstring)
