"""How far the drive's elements reach into the rest of the core (issue 32):
the C++ lines, comments left out, that name a specific element outside the
element and friction-law folders, and the C++ files that name the DC motor.

Usage: python tools/element_footprint.py [ROOT] [--files]

The elements and the names that stand for them (types, accessors, states
and channels of their own):
  DC motor         dc_motor DcMotor motor_current motor_voltage copper_loss
                   armature
  end stops        end_stop EndStop exact_stop stop_force
  preloaded nut    preload PreloadedNut
  train stages     train_friction TrainFriction motor_friction gear_loss
                   RotorBalance RotorMode rotor_row
  LuGre bristles   bristle lugre
  load spring      load_spring LoadSpring
  base excitation  base_excitation BaseExcitation base_work base_force
The element folders: cpp/{src,include/leadscrew}/model/elements/, the laws':
cpp/{src,include/leadscrew}/friction/ (a registry line names its element by
design and is counted where it stands outside them).
"""

import pathlib
import re
import sys

ELEMENTS = {
    "dc_motor": r"dc_?motor|DcMotor|motor_current|motor_voltage|copper_loss|armature",
    "end_stops": r"end_?stop|EndStop|exact_?stop|stop_force",
    "preloaded_nut": r"preload|PreloadedNut",
    "train_stages": r"train_friction|TrainFriction|motor_friction|gear_loss|RotorBalance|"
                    r"RotorMode|rotor_row",
    "lugre_bristles": r"bristle|lugre",
    "load_spring": r"load_spring|LoadSpring",
    "base_excitation": r"base_excitation|BaseExcitation|base_work|base_force",
}
OWN = re.compile(r"^cpp/(src|include/leadscrew)/(model/elements|friction)/")


def code_lines(text):
    """The lines of a C++ source without its comments (// and /* */) and strings."""
    text = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.S)
    for line in text.splitlines():
        line = re.sub(r'"(\\.|[^"\\])*"', '""', line)
        yield line.split("//", 1)[0]


def footprint(root):
    root = pathlib.Path(root)
    per_file, dc_files = {}, set()
    patterns = {k: re.compile(v, re.I) for k, v in ELEMENTS.items()}
    for path in sorted(root.glob("cpp/**/*")):
        if path.suffix not in (".cpp", ".hpp", ".h"):
            continue
        rel = path.relative_to(root).as_posix()
        for line in code_lines(path.read_text(errors="replace")):
            named = [k for k, p in patterns.items() if p.search(line)]
            if "dc_motor" in named:
                dc_files.add(rel)
            if named and not OWN.match(rel):
                per_file[rel] = per_file.get(rel, 0) + 1
    return per_file, sorted(dc_files)


def main(argv):
    root = next((a for a in argv if not a.startswith("--")), ".")
    per_file, dc_files = footprint(root)
    print(f"lines naming an element outside the element and law folders: {sum(per_file.values())}")
    print(f"C++ files naming the DC motor: {len(dc_files)}")
    if "--files" in argv:
        for rel, n in sorted(per_file.items(), key=lambda kv: -kv[1]):
            print(f"  {n:4d}  {rel}")
        print("DC motor:", *dc_files, sep="\n  ")


if __name__ == "__main__":
    main(sys.argv[1:])
