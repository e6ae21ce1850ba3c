"""preload_tradeoff (issue 19, item 5): efficiency, axial stiffness and creep
against the split nut's preload on the rigid drive, against the closed forms
of tests/helpers/preloaded_nut_reference.py (docs/physics/preloaded_nut.md)."""

import math

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

import leadscrew as ls  # noqa: E402
from helpers import preloaded_nut_reference as reference  # noqa: E402
from helpers.scenes import thesis_scene  # noqa: E402
from leadscrew.studies import (plot_preload_tradeoff, preload_tradeoff,  # noqa: E402
                               preloaded_holding_band, static_holding_band)

PRELOADS = [0.0, 5.0, 10.0, 20.0, 40.0]
STIFFNESS = 1e6  # [N/m]
VIBRATION = {"type": "sine", "amplitude": 30.0, "omega": 2 * math.pi * 20.0, "offset": -10.0}


def scene(torque=-2e-2, **changes):
    return ls.Scene.from_dict(thesis_scene(
        friction={"law": "coulomb", "mu": 0.1}, nut={"preload_stiffness": STIFFNESS},
        loads={"drive_torque": torque, "axial_force": VIBRATION}, **changes))


@pytest.fixture(scope="module")
def frame():
    return preload_tradeoff(scene(), PRELOADS, cycles=4, points_per_cycle=40, progress=False)


def test_efficiency_against_the_closed_form(frame):
    assert frame["error"].isna().all()
    thread = ls.Thread(1e-3, 20e-3)
    mu_eff = reference.effective_mu(0.1, thread.flank_angle)
    expected = [reference.efficiency(10.0, p, thread.lead_angle, mu_eff) for p in PRELOADS]
    np.testing.assert_allclose(frame["efficiency_closed_form"], expected, rtol=1e-12)
    np.testing.assert_allclose(frame["efficiency"], expected, rtol=1e-9)
    assert np.all(np.diff(frame["efficiency"]) < 0.0)  # each newton of preload costs
    # The rigid drive is steady at once: its first run decides.
    assert np.all(frame["efficiency_change"] < 1e-12)
    assert np.all(frame["efficiency_t_end"] == 0.05) and frame.attrs["summary"]["unsteady"] == 0


def test_creep_stops_where_the_holding_band_holds_the_torque(frame):
    # A stuck rigid drive is in static equilibrium: it never slips iff the
    # torque lies in the band at every force of the cycle (closed form).
    holds = frame["holds_closed_form"].to_numpy(dtype=bool)
    creep = frame["creep_per_cycle"].to_numpy()
    assert not holds[0] and holds[-1]
    np.testing.assert_array_equal(creep[holds], 0.0)
    np.testing.assert_array_equal(frame["max_displacement"][holds], 0.0)
    assert np.all(np.abs(creep[~holds]) > 1e-9)
    assert np.all(np.diff(np.abs(creep)) <= 0.0)  # more preload, less creep


def test_axial_stiffness_and_held_reverse_load(frame):
    reversed_load = 30.0 - 10.0
    np.testing.assert_array_equal(frame["held_reverse_load"], PRELOADS)
    for row in frame.itertuples():
        if row.preload >= reversed_load:
            assert row.axial_stiffness == math.inf
        else:
            assert row.axial_stiffness == pytest.approx(
                STIFFNESS * reversed_load / (reversed_load - row.preload), rel=1e-15)
    summary = frame.attrs["summary"]
    assert summary["reversed_load"] == reversed_load and summary["load"] == 10.0
    assert summary["amplitude"] == 30.0 and summary["frequency"] == pytest.approx(20.0)
    assert summary["excitation_from"] == "scene" and summary["raised"] == 0


def test_holding_band_against_the_closed_form():
    s = scene()
    thread = s.thread
    mu_eff = reference.effective_mu(0.1, thread.flank_angle)
    alpha, r_m = thread.lead_angle, thread.mean_radius
    # P = 0: the plain thread's band.
    assert preloaded_holding_band(s, -10.0, 0.0, -1.0) == pytest.approx(
        static_holding_band(s, -10.0), rel=1e-14)
    # A load of 10 N on half A's side (along -x, raised by a negative torque
    # on the right-hand screw), preload 20 N.
    low, high = preloaded_holding_band(s, -10.0, 20.0, -1.0)
    assert -low == pytest.approx(reference.raise_torque(10.0, 20.0, alpha, mu_eff, r_m),
                                 rel=1e-12)
    assert high == pytest.approx(reference.lower_torque(10.0, 20.0, alpha, mu_eff, r_m),
                                 rel=1e-12)


def test_units_and_plot(frame):
    assert set(frame.attrs["units"]) == set(frame.columns)
    assert frame.attrs["units"]["axial_stiffness"] == "N/m"
    ax = plot_preload_tradeoff(frame)
    assert len(ax.lines) == 2
    # The creep where it is real (the rigid drive's below its holding
    # preload: 0.25 of its motion per cycle), in um.
    creep_line = ax.figure.axes[1].get_lines()[0]
    np.testing.assert_array_equal(creep_line.get_ydata(),
                                  np.abs(frame["creep_per_cycle"].to_numpy()) * 1e6)


@pytest.mark.parametrize("changes, arguments, match", [
    ({}, {"preloads": [-1.0]}, "preloads"),
    ({}, {"load": 0.0}, "load"),
])
def test_bad_arguments(changes, arguments, match):
    kwargs = {"preloads": [0.0], "progress": False, **arguments}
    with pytest.raises(ValueError, match=match):
        preload_tradeoff(scene(**changes), **kwargs)


def test_what_a_preloaded_nut_refuses_is_said_up_front():
    # (A review: a DC motor scene failed in every row, a mu_static in every row
    # but P = 0's; mu_static runs now: a regularized law is what is refused.)
    with pytest.raises(ValueError, match=r"nut\.preload = 50 N is invalid with "
                                         r"friction\.law = \"arctan_velocity\": preload_tradeoff's "
                                         r"closed forms .* are exact Coulomb's"):
        preload_tradeoff(scene().replace(friction={"law": "arctan_velocity", "mu": 0.1}),
                         [0.0, 50.0], progress=False)
    # A DC motor is replaced by the study's own drive (a prescribed speed
    # raising, the motor unpowered at rest): the rows of the scene with
    # drive_torque 0 in its place, exactly.
    motor = scene().to_dict()
    motor["loads"].pop("drive_torque")
    motor["motor"] = {"type": "dc", "voltage": 12.0, "resistance": 1.0, "torque_constant": 0.02}
    options = dict(cycles=3, points_per_cycle=20, progress=False)
    driven = preload_tradeoff(motor, [0.0, 50.0], **options)
    unpowered = preload_tradeoff(scene(torque=0.0), [0.0, 50.0], **options)
    assert driven.attrs["summary"]["motor_replaced"] is True
    for column in ("efficiency", "creep_per_cycle", "max_displacement", "holds_closed_form"):
        np.testing.assert_array_equal(driven[column], unpowered[column])


def test_motor_characteristics_refuses_a_preloaded_nut():
    # Its closed form is the plain nut's (a review found it silently beside the wrong train).
    d = thesis_scene(concept="rigid", nut={"preload": 50.0}, loads={"axial_force": 0.0},
                     motor={"type": "dc", "voltage": 12.0, "resistance": 1.0,
                            "torque_constant": 0.02})
    d["loads"].pop("drive_torque")
    with pytest.raises(ValueError, match=r"nut\.preload = 50\.0 is invalid for "
                                         r"motor_characteristics: must be 0"):
        ls.studies.motor_characteristics(d, [10.0], progress=False)


@pytest.mark.parametrize("backlash", [None, {"axial": 1e-4, "contact": "bistop"}])
def test_a_flexible_concept_simulates_stiffness_and_creep(backlash):
    # flexible_nut, without play and with penalty play (half A lifts off):
    # the stiffness at the load from the simulation; the preload that holds
    # the reversed peak (R = 30 - 10 = 20 N) stops the creep.
    changes = {"concept": "flexible_nut"}
    if backlash:
        changes["backlash"] = backlash
    flexible = scene(**changes)
    frame = preload_tradeoff(flexible, [0.0, 10.0, 40.0], cycles=4, points_per_cycle=40,
                             progress=False)
    assert frame["error"].isna().all()
    stiffness, creep = frame["axial_stiffness"].to_numpy(), frame["creep_per_cycle"].to_numpy()
    assert abs(creep[0]) > 1e-6 and abs(creep[2]) < 1e-3 * abs(creep[0])
    # (the rigid band holds the torque at P = 40, not below)
    assert list(frame["holds_closed_form"]) == [False, False, True]
    eta, closed = frame["efficiency"].to_numpy(), frame["efficiency_closed_form"].to_numpy()
    assert np.all(np.diff(eta) < 0.0)
    held = frame["held_reverse_load"].to_numpy()
    if backlash:
        # The play rattles at P = 0; at P = 10 half A lifts off at the
        # reversed peak (P + k_p d_0 < 20 N), at P = 40 it holds: stiffer.
        assert np.all(np.diff(stiffness) > 0.0) and stiffness[1] > 5 * stiffness[0]
        # In steady raising the spring relaxes by half A's added penetration
        # (S < P): a little above the closed form at P.
        assert np.all(eta >= closed - 1e-4 * closed)
        np.testing.assert_allclose(eta, closed, rtol=5e-2)
        lift_off = [ls.studies.lift_off_spring_force(flexible.replace(nut={"preload": p}))
                    for p in (10.0, 40.0)]
        np.testing.assert_array_equal(held[1:], [value[0] for value in lift_off])
        assert held[0] == 0.0 and held[1] < 20.0 < held[2] and np.all(held[1:] > [10.0, 40.0])
        assert lift_off[1][1] == pytest.approx(
            abs(flexible.replace(nut={"preload": 40.0}).model().parameters.play_position)
            - 0.5e-4, rel=1e-12)
    else:
        # Without play the thread holds the nut at any preload: the nut's
        # axial spring at the load, whatever P.
        nut = flexible.derived()["nut_axial_stiffness"]
        np.testing.assert_allclose(stiffness, nut, rtol=1e-2)
        np.testing.assert_allclose(eta, closed, rtol=1e-3)
        np.testing.assert_array_equal(held, [0.0, 10.0, 40.0])


def test_with_mu_static_the_efficiency_is_mus_and_the_band_mu_statics():
    # Coulomb's law with mu_static: the raise slips at mu' (the closed form's
    # efficiency), the stuck drive holds up to mu_static' (the band): the
    # creep is zero exactly where that band holds the torque.
    static = scene().replace(friction={"mu_static": 0.15})
    preloads = [0.0, 5.0, 20.0]
    frame = preload_tradeoff(static, preloads, cycles=4, points_per_cycle=40, progress=False)
    assert frame["error"].isna().all()
    thread = ls.Thread(1e-3, 20e-3)
    mu_eff = reference.effective_mu(0.1, thread.flank_angle)
    expected = [reference.efficiency(10.0, p, thread.lead_angle, mu_eff) for p in preloads]
    np.testing.assert_allclose(frame["efficiency"], expected, rtol=1e-9)
    holds = frame["holds_closed_form"].to_numpy(dtype=bool)
    creep = frame["creep_per_cycle"].to_numpy()
    assert not holds[0] and holds[-1]
    np.testing.assert_array_equal(creep[holds], 0.0)
    assert np.all(np.abs(creep[~holds]) > 1e-9)
    # mu_static widens the band: P = 20 N holds with it, and creeps with mu alone.
    plain = preload_tradeoff(scene(), [20.0], cycles=4, points_per_cycle=40, progress=False)
    assert holds[2] and not plain["holds_closed_form"][0]
    assert abs(plain["creep_per_cycle"][0]) > 1e-9


SEAT_LOAD, SEAT_MU = 80.0, 0.12  # the shipped seat adjuster's static force [N] and mu


def seat_closed_form(preloads):
    thread = ls.scenes.load("seat_adjuster").thread
    mu_eff = reference.effective_mu(SEAT_MU, thread.flank_angle)
    return [reference.efficiency(SEAT_LOAD, p, thread.lead_angle, mu_eff) for p in preloads]


@pytest.fixture(scope="module")
def seat_frame():
    # The shipped seat adjuster: a DC motor (replaced by the study's drive),
    # an ideal 5:1 stage, the flexible concept with exact play (closed by the
    # preload), mu_static 0.15. 1 s of raising: its springs settle.
    return preload_tradeoff(ls.scenes.load("seat_adjuster"), [0.0, 20.0, 50.0], t_end=1.0,
                            cycles=3, progress=False)


def test_the_shipped_seat_adjuster(seat_frame):
    frame = seat_frame
    assert frame["error"].isna().all()
    expected = seat_closed_form([0.0, 20.0, 50.0])
    np.testing.assert_allclose(frame["efficiency_closed_form"], expected, rtol=1e-12)
    np.testing.assert_allclose(frame["efficiency"], expected, rtol=1e-4)
    assert np.all(np.diff(frame["efficiency"]) < 0.0)
    # The ideal stage loses nothing: the train's efficiency is the thread's.
    np.testing.assert_array_equal(frame["train_efficiency"], frame["efficiency"])
    summary = frame.attrs["summary"]
    assert summary["gear_ratio"] == 5.0 and summary["motor_replaced"] is True
    assert summary["play_closed"] is True and summary["drive_torque"] == 0.0
    # 80 N against 30 N of vibration: never reversed, held by the
    # self-locking thread at any preload (the creep is the flexible
    # model's round-off, u_load's scale 1e-2 m).
    assert frame["holds_closed_form"].all()
    assert np.all(np.abs(frame["creep_per_cycle"]) < 1e-9)
    # The figure draws that round-off as no creep, not as a trend.
    creep_line = plot_preload_tradeoff(seat_frame).figure.axes[1].get_lines()[0]
    np.testing.assert_array_equal(creep_line.get_ydata(), 0.0)
    np.testing.assert_array_equal(frame["held_reverse_load"], [0.0, 20.0, 50.0])


def test_the_seat_adjuster_with_the_studys_defaults():
    # The call as it stands: rows with no error, the efficiency
    # falling and on its closed form. At the default t_end = 0.05 s the
    # flexible seat's springs still settle (the efficiency 8 % off); the
    # study lengthens each run until its efficiency is steady.
    frame = preload_tradeoff(ls.scenes.load("seat_adjuster"), [0, 20, 50], progress=False)
    assert frame["error"].isna().all()
    assert np.all(np.diff(frame["efficiency"]) < 0.0)
    np.testing.assert_allclose(frame["efficiency"], seat_closed_form([0, 20, 50]), rtol=1e-4)
    assert np.all(frame["efficiency_change"] <= 1e-4)
    assert np.all(frame["efficiency_t_end"] > 0.05) and frame.attrs["summary"]["unsteady"] == 0


def test_an_efficiency_run_that_never_settles_is_said():
    # 32 times 1e-4 s is still the seat's transient: the rows keep their
    # last run's numbers, and the study says they are not steady.
    with pytest.warns(ls.StudyWarning, match=r"in 2 of 2 rows the efficiency still changed by "
                                             r"up to .* at 32 times t_end = 0.0001 s"):
        frame = preload_tradeoff(ls.scenes.load("seat_adjuster"), [20, 50], t_end=1e-4,
                                 cycles=2, progress=False)
    assert np.all(frame["efficiency_change"] > 1e-4)
    np.testing.assert_array_equal(frame["efficiency_t_end"], [32e-4, 32e-4])
    assert frame.attrs["summary"]["unsteady"] == 2


def test_a_reversed_peak_beyond_the_preload_on_exact_play_is_a_rows_error():
    # 100 N of vibration on 80 N: 20 N reversed. P = 10 N would let half A
    # lift off into the exact play (not modelled): that row says so and
    # keeps its efficiency; P = 0 (the plain nut's play) and 50 N run.
    with pytest.warns(ls.StudyWarning, match="1 of 3 rows raised"):
        frame = preload_tradeoff(ls.scenes.load("seat_adjuster"), [0.0, 10.0, 50.0],
                                 amplitude=100.0, t_end=0.05, cycles=3, progress=False)
    errors = list(frame["error"])
    assert errors[0] is None and errors[2] is None
    assert "nut.preload = 10 N holds less than the vibration's reversed peak 20 N: half A " \
           "would lift off into the exact play, which is not modelled" in errors[1]
    assert np.isnan(frame["creep_per_cycle"][1]) and np.isfinite(frame["efficiency"][1])


def test_a_worm_stage_with_a_preload_is_refused_with_what_to_do():
    worm = ls.scenes.load("seat_adjuster_worm")
    with pytest.raises(ValueError, match=r"nut\.preload = 20 N is invalid with gear\.type = "
                                         r"\"worm\": .*use nut\.preload = 0, or gear\.type = "
                                         r"\"ideal\""):
        preload_tradeoff(worm, [0.0, 20.0], progress=False)


def test_the_cli_writes_the_seat_adjusters_table_and_figure(tmp_path, capsys):
    from leadscrew import cli
    code = cli.main(["study", "preload_tradeoff", "seat_adjuster", "preloads=0,20,50",
                     "t_end=0.05", "cycles=3", "progress=false", "-o", str(tmp_path)])
    out, err = capsys.readouterr()
    assert code == 0, err
    table = tmp_path / "preload_tradeoff_seat_adjuster.csv"
    assert table.exists() and (tmp_path / "preload_tradeoff_seat_adjuster.png").exists()
    import pandas as pd
    frame = pd.read_csv(table, skiprows=[1])
    assert list(frame["preload"]) == [0.0, 20.0, 50.0]
    assert np.all(np.diff(frame["efficiency"]) < 0.0) and frame["error"].isna().all()


def test_a_left_hand_thread_trades_off_as_the_mirrored_right_hand_one(frame):
    """Issue 31, item 12: the mirror image of the right-hand drive under the
    torque M is the left-hand drive under -M, with the same axial
    vibration: the same efficiency (raised by the mirrored turn), holding
    band verdicts, creep per cycle and displacement, preload by preload."""
    left = preload_tradeoff(scene(torque=2e-2, thread={"pitch": 1e-3, "mean_diameter": 20e-3,
                                                        "hand": "left"}),
                            PRELOADS, cycles=4, points_per_cycle=40, progress=False)
    assert left["error"].isna().all()
    np.testing.assert_array_equal(left["holds_closed_form"], frame["holds_closed_form"])
    for column in ("efficiency", "efficiency_closed_form", "creep_per_cycle",
                   "max_displacement"):
        np.testing.assert_allclose(left[column], frame[column], rtol=1e-9, atol=1e-15,
                                   err_msg=column)


def test_a_left_hand_flexible_drive_has_the_mirrored_stiffness():
    """The stiffness at the load counts the load's place beyond the thread's,
    u_load + h p phi (the springs' deflections): the left-hand flexible
    drive under -M, the mirror image of the right-hand one under M, has the
    same stiffness, creep and efficiency: to 1e-6 (the two runs integrate
    the mirrored equations at the default rtol of 1e-8, in step sequences
    that round-off tells apart, and the stiffness divides by the small
    range of u_load + h p phi: 6e-9 seen); a creep the preload stops (7e-10
    m per cycle at P = 40 N) to 1e-13 m as well, the rotor's absolute
    tolerance (atol 1e-10 rad) times p = 1.6e-4 m/rad and a few cycles."""
    frames = [preload_tradeoff(scene(torque=sign * -2e-2, concept="flexible_nut",
                                     thread={"pitch": 1e-3, "mean_diameter": 20e-3,
                                             "hand": hand}),
                               [0.0, 40.0], cycles=4, points_per_cycle=40, progress=False)
              for sign, hand in ((1.0, "right"), (-1.0, "left"))]
    for column, atol in (("axial_stiffness", 0.0), ("creep_per_cycle", 1e-13),
                         ("efficiency", 0.0)):
        np.testing.assert_allclose(frames[1][column], frames[0][column], rtol=1e-6,
                                   atol=atol, err_msg=column)
