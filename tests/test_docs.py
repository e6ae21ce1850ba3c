"""The documentation site (docs/, Sphinx with MyST) builds without a warning
and has a page for every public name."""

import importlib
import pathlib
import shutil
import subprocess
import sys

DOCS = pathlib.Path(__file__).resolve().parents[1] / "docs"


def test_the_site_builds_without_warnings_with_a_page_per_public_name(tmp_path):
    # From docs/ as a fresh clone has it: without the pages a build generates.
    source = tmp_path / "docs"
    shutil.copytree(DOCS, source, ignore=shutil.ignore_patterns("api.rst", "generated", "_build"))
    done = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b",
                           "html", "-d", str(tmp_path / "doctrees"), str(source),
                           str(tmp_path / "html")], capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    assert done.stderr == ""
    sys.path.insert(0, str(DOCS))
    try:
        names = importlib.import_module("conf").public_names()
    finally:
        sys.path.remove(str(DOCS))
    assert {"leadscrew.simulate", "leadscrew.Scene", "leadscrew.fmi.export_fmu",
            "leadscrew.studies.efficiency_vs_mu", "leadscrew.WriteError"} <= set(names)
    import leadscrew

    assert {f"leadscrew.{name}" for name in leadscrew.__all__} <= set(names)
    missing = [name for name in names if not (tmp_path / "html" / "generated" / f"{name}.html")
               .is_file()]
    assert missing == []
    for page in ("guide/tour", "guide/studies", "performance", "reliability",
                 "physics/rigid_drive", "api"):
        assert (tmp_path / "html" / f"{page}.html").is_file(), page
