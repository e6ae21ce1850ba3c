"""Every notebook in notebooks/ executes without error, in quick mode
(LEADSCREW_QUICK=1) and with the non-interactive Agg backend, within a time
budget per notebook.

The notebooks check the numbers their text states with assert statements in
the code cells next to the claims; the tolerances hold on the quick grids as on
the full ones (a claim only the full grid supports is checked under an explicit
``if`` on the grid). Executing a notebook therefore tests its claims: a failing
assert fails the cell and this test."""

import pathlib
import time

import nbformat
import pytest
from nbclient import NotebookClient

NOTEBOOK_DIR = pathlib.Path(__file__).resolve().parent.parent / "notebooks"
NOTEBOOKS = sorted(NOTEBOOK_DIR.glob("*.ipynb"))
TIMEOUT = 120.0  # s per notebook (the quick runs take a few seconds)


def test_notebooks_are_found():
    assert "friction_block.ipynb" in [path.name for path in NOTEBOOKS]


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[path.name for path in NOTEBOOKS])
def test_notebook_executes(path, monkeypatch):
    # The kernel inherits this environment: matplotlib then never opens a
    # window, and the notebooks shrink their grids and timing repeats.
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.setenv("LEADSCREW_QUICK", "1")
    notebook = nbformat.read(path, as_version=4)
    client = NotebookClient(notebook, timeout=int(TIMEOUT), kernel_name="python3",
                            resources={"metadata": {"path": str(path.parent)}})
    start = time.monotonic()
    client.execute()  # raises CellExecutionError on the first failing cell
    elapsed = time.monotonic() - start
    assert elapsed < TIMEOUT, f"{path.name} took {elapsed:.0f} s (budget {TIMEOUT:.0f} s)"
    errors = [output for cell in notebook.cells if cell.cell_type == "code"
              for output in cell.get("outputs", []) if output.output_type == "error"]
    assert not errors
    executed = [cell for cell in notebook.cells if cell.cell_type == "code"]
    assert executed and all(cell.execution_count for cell in executed)
    # The kernel saw LEADSCREW_QUICK: each notebook's first cell says which mode it ran.
    first = "".join(output.get("text", "") for output in executed[0].get("outputs", []))
    assert first.startswith("QUICK mode")


def assert_statements(notebook):
    return [line for cell in notebook.cells if cell.cell_type == "code"
            for line in cell.source.splitlines() if line.lstrip().startswith("assert ")]


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[path.name for path in NOTEBOOKS])
def test_notebook_checks_its_claims(path):
    """Each notebook keeps the asserts that check its text's numbers; without
    them it would execute, and pass test_notebook_executes, with any numbers."""
    notebook = nbformat.read(path, as_version=4)
    assert len(assert_statements(notebook)) >= 20
