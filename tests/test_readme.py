"""The README's API tour runs as written."""

import pathlib
import re

README = pathlib.Path(__file__).resolve().parents[1] / "README.md"


def test_readme_python_blocks_run():
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(), flags=re.S)
    assert len(blocks) >= 3
    namespace = {}
    for block in blocks:
        exec(compile(block, str(README), "exec"), namespace)  # noqa: S102


def test_readme_commands_are_the_ci_commands():
    text = README.read_text()
    ci = (README.parent / ".ci" / "run").read_text()
    assert "<!-- test-command -->" in text and "test-command" in ci


def test_every_name_the_readme_uses_is_reachable_from_import_leadscrew():
    """``ls.integrate.solve_ode``, ``ls.lcp.solve``, ``ls.scene.describe_schema``
    ...: each dotted name the README writes after ``ls.`` resolves right after
    ``import leadscrew as ls`` (in a fresh interpreter: another test's import
    of a submodule would make it an attribute here)."""
    import json
    import subprocess
    import sys

    # "ls." not inside a word or a path (drive_models.md, drive_rigid.hpp).
    names = sorted(set(re.findall(r"(?<![\w./])ls\.([A-Za-z_]\w*(?:\.[A-Za-z_]\w*)*)",
                                  README.read_text())))
    assert {"integrate.solve_ode", "lcp.solve", "scene.describe_schema", "Thread"} <= set(names)
    script = ("import functools, json, sys\nimport leadscrew as ls\n"
              "missing = []\n"
              "for name in json.loads(sys.argv[1]):\n"
              "    try:\n"
              "        functools.reduce(getattr, name.split('.'), ls)\n"
              "    except AttributeError:\n"
              "        missing.append(name)\n"
              "print(json.dumps(missing))\n")
    done = subprocess.run([sys.executable, "-c", script, json.dumps(names)], capture_output=True,
                          text=True, timeout=120, check=True)
    assert json.loads(done.stdout) == []
