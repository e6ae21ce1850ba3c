"""A lift-off preloaded nut that leaves stick at a cone edge where the slip,
half B at its slip state, slows at once (docs/physics/preloaded_nut.md,
"Stick with half B toward its edge"): the event-driven scheme chattered
stick <-> slip at one instant until max_events (drive-train fuzz case 7173,
seed 20261127: 2,000 events within 1e-11 s at t = 2.774 ms). It now sticks
with half B toward that edge, as Moreau-Jean's steps do, and Moreau-Jean's
run of the same scene converges to it at first order as dt -> 0."""

import numpy as np

import leadscrew as ls

# Fuzz case 7173 of the drive-train run (seed 20261127), cut to the stick
# phase, its edge and the slip after it.
SCENE = {
    "concept": "flexible", "drive": "nut",
    "thread": {"pitch": 0.001995824130007394, "mean_diameter": 0.013346448451170029,
               "starts": 4},
    "friction": {"law": "coulomb", "mu": 0.28933035389252126},
    "backlash": {"axial": 6.144163858668974e-05, "contact": "cubic",
                 "penetration": 1.0442023997117605e-06},
    "screw": {"radius": 0.004259371951427913, "length": 0.29774902876706383,
              "youngs_modulus": 2019765057.109256, "support": "both_ends"},
    "nut": {"outer_radius": 0.0065529049706854175, "length": 0.004706903442105906,
            "youngs_modulus": 930008845.7907782, "position": 0.04363949089946709,
            "preload": 10.6734420342995, "preload_stiffness": 771208.4211021343},
    "rotor": {"inertia": 8.816183476379204e-05},
    "load": {"mass": 9.269711713405625},
    "loads": {},
    "motor": {"type": "dc", "voltage": 8.601996621155108, "resistance": 1.2500961514157451,
              "torque_constant": 0.029394788784981852, "inductance": 0.0012053974178542332,
              "current_limit": 8.849703289449648},
    "end_stops": {"contact": "penalty", "stiffness": 117777080.61541231,
                  "damping": 8957.458832183673, "lower": -0.00029456922289905154},
}
T_END = 0.0035  # [s]: the edge at 2.774 ms, the slip from 2.808 ms
EDGE = "stick (half B at slip-'s edge)"


def _event_driven():
    return ls.simulate(ls.Scene.from_dict(SCENE), t_end=T_END, integrator="event_driven",
                       rtol=1e-10, atol=1e-14, t_eval="steps", max_events=50)


def test_stick_toward_half_bs_edge_instead_of_chattering():
    result = _event_driven()
    kinds = [event.kind for event in result.events]
    assert kinds == ["stick->" + EDGE, EDGE + "->slip-"]
    # The stick at the edge lasts (34 us), then the slip starts consistent.
    times = [event.time for event in result.events]
    assert times[1] - times[0] > 1e-5
    # Friction never works: the loss (with half B's on its own slip) rises.
    loss = np.asarray(result["friction_loss"])
    assert np.all(np.diff(loss) >= -1e-15 * np.max(np.abs(loss)))
    # The energy account closes with half B's share of its loss booked.
    energy = result.checks["energy_balance"]
    assert energy["passed"] and energy["value"] < 1e-3 * energy["bound"]


def test_moreau_jean_converges_to_it_at_first_order():
    """The friction loss (the stick at the edge, then the slip) of
    Moreau-Jean's run at dt = T/1000, T/4000, T/16000 against the
    event-driven run: 7.1e-3, 1.8e-3, 4.5e-4 of its largest value (the
    scheme's first order; before the edge both runs agree to 5e-5)."""
    result = _event_driven()
    times = np.linspace(0.0, T_END, 141)[1:]
    reference = np.interp(times, result.t, result["friction_loss"])
    scale = np.max(np.abs(reference))
    errors = []
    for steps in (1000, 4000, 16000):
        moreau = ls.simulate(ls.Scene.from_dict(SCENE), t_end=T_END, integrator="moreau",
                             dt=T_END / steps)
        errors.append(np.max(np.abs(np.interp(times, moreau.t, moreau["friction_loss"])
                                    - reference)) / scale)
    assert errors[1] < 0.3 * errors[0] and errors[2] < 0.3 * errors[1]  # dt / 4: error / 4
    assert errors[2] < 6e-4
