"""Fuzz test of ``leadscrew.simulate`` over random drive trains (issues 17
and 19): the elements of the drive train (a DC motor with or without its
friction, an ideal, lossy or worm gear stage, exact or penalty end stops, a
preloaded nut) drawn freely against one another, every concept and play, and
the integrator (the scene's default, event-driven, Moreau-Jean), by
``helpers.train_fuzz``. Every case has one of the outcomes issue 17 allows:
a result that passes its checks (the simulator's and the independent
``helpers.result_invariants``), a ``ValueError`` naming a key or option the
case set (a combination the core refuses names one of its keys), a
``SimulationError`` or a ``JammingError``. ``tests/fuzz_scenes.py
--generator train`` runs the same generator for thousands of cases."""

import json

from helpers.scene_fuzz import prepare_parent, run_all_allowed, run_case
from helpers.train_fuzz import TRAIN_SEED, generate_train, make_train_case

# About 15 s with two workers on a quiet machine (200 cases: 19 s).
TRAIN_CASES = 150
CASE_TIMEOUT = 10.0


def test_fuzz_drive_trains():
    prepare_parent()
    drawn = generate_train(TRAIN_CASES, TRAIN_SEED)
    assert len(drawn) == TRAIN_CASES
    counts = run_all_allowed(drawn, CASE_TIMEOUT)
    # Not only refusals: a good share of the drawn trains run and pass.
    assert counts["passed"] >= TRAIN_CASES // 5, counts


def test_train_generator_is_deterministic_and_covers_the_elements():
    first = [json.dumps(c, sort_keys=True) for c in generate_train(40, 3)]
    assert first == [json.dumps(c, sort_keys=True) for c in generate_train(40, 3)]
    drawn = generate_train(300, TRAIN_SEED)
    for tag, values in [("concept", {"rigid", "flexible_nut", "flexible"}),
                        ("contact", {"none", "exact", "bistop", "cubic"}),
                        ("motor", {"torque", "speed", "dc", "dc+friction"}),
                        ("gear", {"none", "ideal", "lossy", "worm"}),
                        ("stops", {"none", "exact", "penalty"}),
                        ("preload", {"none", "preload"}),
                        ("integrator", {"default", "event_driven", "moreau"})]:
        assert {c["tags"][tag] for c in drawn} == values, tag
    assert not any(c["hostile"] for c in drawn)
    case = drawn[11]
    assert json.dumps(make_train_case(case["seed"]), sort_keys=True) == json.dumps(
        case, sort_keys=True)


def test_moreau_worm_through_penalty_stops_passes_the_independent_energy_check():
    """A case of the first run of the generator: Moreau-Jean (the scene's
    default with a worm stage on the flexible concept) books the rotor
    contact's friction at each slipping step's end speed, (1 - theta) Q (w+ -
    w0) beyond the scheme's work; the simulator's energy bound allows it and
    the independent check did not (residual -1.15e-10 J against its -3.7e-11
    J). It now adds the rotor contact's term from the loss channels."""
    scene = {
        "concept": "flexible", "drive": "screw",
        "thread": {"pitch": 0.002374754618947265, "mean_diameter": 0.027419624266447645,
                   "flank_angle": 0.18914577346196765},
        "friction": {"law": "coulomb", "mu": 0.2970692596402167},
        "screw": {"radius": 0.012527345556529736, "length": 0.1601729553693012,
                  "youngs_modulus": 3060719593.1344304},
        "nut": {"outer_radius": 0.03230538215217786, "length": 0.007118229975439949,
                "youngs_modulus": 163107579094.1192, "position": 0.01356701700952762,
                "density": 935.9139258044703},
        "rotor": {"inertia": 1.9234256951470885e-07}, "load": {"mass": 0.03133253672736649},
        "loads": {"axial_force": {"type": "sine", "amplitude": 0.585444205578445,
                                  "omega": 11.560829550056127, "phase": 3.9545642882220204,
                                  "offset": -0.6708170774777908},
                  "drive_torque": {"type": "constant", "value": 0.0017557895572002395}},
        "gear": {"type": "worm", "ratio": 0.5415847346018836, "lead_angle": 0.333569301287954,
                 "mu": 0.36578270348551534, "mu_static": 0.427681981301283},
        "end_stops": {"contact": "penalty", "stiffness": 195720.1642028878,
                      "damping": 5.226356755537941, "upper": 0.00234252798028809}}
    case = {"seed": 0, "scene": scene, "hostile": [], "tags": {},
            "options": {"t_end": 0.010718588084588936, "max_events": 2000, "max_steps": 100000}}
    outcome = run_case(case)
    assert outcome["outcome"] == "passed", outcome
