"""The command line's catalog: ``leadscrew list`` (what ships with leadscrew)
and ``leadscrew scene copy NAME [PATH]`` (a shipped scene out for editing)."""

from __future__ import annotations

import argparse
import os
import re
from pathlib import Path
from typing import List

from ._hints import did_you_mean
from .cli_parser import UsageError
from .files import write_text

__all__: List[str] = []


_WIDTH = 90  # characters of a description


def _first_sentence(text: str) -> str:
    """The first sentence of a docstring or comment, on one line, cut at a
    word to at most ``_WIDTH`` characters (abbreviations as "Fig. 5.4" do
    not end it, nor "et al.")."""
    words = " ".join((text or "").split())
    match = re.search(r"(?<!Fig)(?<!eq)(?<!e\.g)(?<! al)\.(\s|$)", words)
    sentence = words if match is None else words[: match.start() + 1]
    if len(sentence) <= _WIDTH:
        return sentence
    return sentence[: sentence.rfind(" ", 0, _WIDTH - 3)] + " ..."


def _scene_summary(name: str) -> str:
    """A shipped scene's first sentence: its file's opening comment."""
    from . import scenes

    comment = []
    for line in scenes.path(name).read_text(encoding="utf-8").splitlines():
        if not line.startswith("#") or not line.strip("# "):
            break
        comment.append(line.lstrip("#").strip())
    return _first_sentence(" ".join(comment))


def _catalog() -> List[str]:
    """The lines ``leadscrew list`` prints."""
    from . import profiles, scenes, studies
    from .scene_schema import friction_laws

    lines = ["scenes (leadscrew run NAME; leadscrew scene copy NAME to edit one):"]
    lines += [f"  {name:30s} {_scene_summary(name)}" for name in scenes.available()]
    lines += ["studies (leadscrew study NAME SCENE KEY=VALUE ...):"]
    lines += [f"  {name:30s} {_first_sentence(function.__doc__)}"
              for name, function in sorted(studies.STUDIES.items())]
    lines += ["friction laws (a scene's friction.law):"]
    lines += [f"  {law['name']:30s} {_first_sentence(law['doc'])}" for law in friction_laws()]
    lines += ["vibration profiles (ls.profiles.load(NAME); a load {type = \"random\", "
              "profile = NAME}):"]
    lines += [f"  {name:30s} {profiles.info(name).source}"
              + ("" if profiles.info(name).verified else " (table not verified against it)")
              for name in profiles.names()]
    return lines


def _list(args: argparse.Namespace) -> int:
    """``leadscrew list``: the shipped scenes, the studies, the friction
    laws and the vibration profiles, one line each with what it is."""
    print("\n".join(_catalog()))
    return 0


def _copy_scene(name: str, target: "str | None") -> Path:
    """Copy the shipped scene ``name`` (its comments included) to ``target``:
    a file, a directory (``DIR/NAME.toml``) or, by default, ``NAME.toml``.

    Raises:
        UsageError: no shipped scene has that name, the target exists (never
            overwritten) or is not a ``.toml`` file.
        leadscrew.WriteError: the file cannot be written (nothing is left).
    """
    from . import scenes

    stem = name[:-5] if name.endswith(".toml") else name
    if stem not in scenes.available():
        raise UsageError(f"scene copy {name}: not a shipped scene"
                         f"{did_you_mean(name, scenes.available())} "
                         f"({', '.join(scenes.available())})")
    path = Path(target) if target else Path(f"{stem}.toml")
    if path.is_dir():
        path = path / f"{stem}.toml"
    if path.suffix != ".toml":
        raise UsageError(f"scene copy {name} {target}: a scene file ends in .toml "
                         f"(e.g. {path.with_name(path.name + '.toml')})")
    if path.exists():
        raise UsageError(f"scene copy {name}: {path} exists; leadscrew does not overwrite it "
                         f"(remove it, or give another PATH)")
    return write_text(path, scenes.path(stem).read_text(encoding="utf-8"))


def _scene_copy(args: argparse.Namespace) -> int:
    """``leadscrew scene copy NAME [PATH]``."""
    path = _copy_scene(args.scene, args.path)
    print(f"wrote {os.fspath(path)} (run it: leadscrew run {os.fspath(path)})")
    return 0
