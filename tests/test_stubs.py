"""The type stubs of the extension (python/leadscrew/_core/*.pyi) name exactly
what the compiled module exports."""

import ast
import pathlib

import pytest

import leadscrew._core as core

STUBS = pathlib.Path(__file__).resolve().parents[1] / "python" / "leadscrew" / "_core"


def stub_names(path):
    """(names the stub defines as classes or functions, every name it binds)."""
    tree = ast.parse(path.read_text())
    defined, bound = set(), set()
    for node in tree.body:
        if isinstance(node, (ast.ClassDef, ast.FunctionDef)):
            defined.add(node.name)
        elif isinstance(node, ast.Import):
            bound.update(alias.asname or alias.name.split(".")[-1] for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            bound.update(alias.asname or alias.name for alias in node.names)
        elif isinstance(node, (ast.Assign, ast.AnnAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            bound.update(t.id for t in targets if isinstance(t, ast.Name))
    return defined, defined | bound


def public(module):
    return {n for n in dir(module) if not n.startswith("_")}


@pytest.mark.parametrize("module, stub", [(core, "__init__.pyi"), (core.lcp, "lcp.pyi"),
                                          (core.integrate, "integrate.pyi")])
def test_stubs_match_the_extension(module, stub):
    defined, bound = stub_names(STUBS / stub)
    missing = public(module) - bound
    assert not missing, f"{stub} lacks {sorted(missing)}"
    stale = defined - set(dir(module))
    assert not stale, f"{stub} describes what the module does not have: {sorted(stale)}"
