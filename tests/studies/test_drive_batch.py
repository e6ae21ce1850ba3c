"""The C++ batch of drive simulations (leadscrew.studies._batch.DriveBatch) and
the efficiency sweep built on it, against the per-case path: a Scene edited
in Python and simulated by leadscrew.simulate, one case at a time."""

import concurrent.futures
import math
import os
import pickle
import subprocess
import sys
import textwrap
import threading

import numpy as np
import pandas as pd
import pytest

import leadscrew as ls
from leadscrew import _core
from helpers.scenes import thesis_scene
from leadscrew.studies._batch import DriveBatch
from leadscrew.studies._sweep import SerialExecutor, run_chunks
from leadscrew.studies.drive_efficiency import efficiency_vs_mu

CHANNELS = ["u_load", "v_load", "omega_drive", "drive_torque", "work_drive", "friction_loss",
            "energy_residual"]


def scene(**changes):
    return ls.Scene.from_dict(thesis_scene(**changes))


def speed_controlled(base, omega=-10.0):
    return base.replace(loads={"drive_torque": None, "drive_speed": omega},
                        initial={"rotor_speed": omega})


def simulated(case_scene, t_end, t_eval, channels, **options):
    """The per-case path: (channels, sample times) from leadscrew.simulate."""
    result = ls.simulate(case_scene, t_end, t_eval=t_eval, **options)
    return np.array([result[name] for name in channels])


def described(call):
    """The row text of a failed per-case call, as the sweeps write it."""
    try:
        call()
    except Exception as error:
        return f"{type(error).__name__}: {error}"
    raise AssertionError("the call did not fail")


# (scene changes, speed-controlled, simulated time, options): every concept,
# both friction formulations, exact backlash (under the thesis's torque).
CONFIGURATIONS = {
    "rigid": ({}, True, 0.2, {}),
    "flexible_nut": (dict(concept="flexible_nut"), True, 0.02, {}),
    "flexible": (dict(concept="flexible"), True, 0.02, {}),
    "rigid arctan": (dict(friction={"law": "arctan_velocity", "mu": 0.3, "k_v": 1e4}), True,
                     0.02, dict(rtol=1e-6, atol=1e-9)),
    "rigid backlash": (dict(backlash={"axial": 1e-4}), False, 0.5, {}),
}


@pytest.mark.parametrize("name", list(CONFIGURATIONS))
def test_batch_samples_are_the_per_case_simulation_bit_for_bit(name):
    """Setting mu and the axial force in C++ gives the same parameters as
    Scene.replace, so every sample is identical, not merely close."""
    changes, speed, t_end, options = CONFIGURATIONS[name]
    base = speed_controlled(scene(**changes)) if speed else scene(**changes)
    t_eval = [0.0, t_end / 3, t_end / 2, t_end]
    cases = [(0.0, -5.0), (0.1, -20.0), (0.35, -80.0)]
    batch = DriveBatch(base, ["mu", "axial_force"], CHANNELS, t_end, t_eval, **options)
    samples, errors, wall_time = batch.run(cases)
    assert samples.shape == (len(cases), len(CHANNELS), len(t_eval))
    for (mu, force), ours, error, time in zip(cases, samples, errors, wall_time):
        edited = base.replace(friction={"mu": mu}, loads={"axial_force": force})
        try:
            reference = simulated(edited, t_end, t_eval, CHANNELS, **options)
        except ls.SimulationError:  # then the batch row holds the same message
            assert error == described(lambda: simulated(edited, t_end, t_eval, CHANNELS,
                                                        **options))
            assert np.isnan(ours).all() and np.isnan(time)
            continue
        assert error is None and time > 0
        np.testing.assert_array_equal(ours, reference)
    assert errors.count(None) == len(cases)


@pytest.mark.parametrize("parameters, values, edit", [
    (["drive_torque"], [[-0.05], [0.02]], lambda s, v: s.replace(loads={"drive_torque": v})),
    (["load_mass"], [[0.5], [4.0]], lambda s, v: s.replace(load={"mass": v})),
    (["rotor_inertia", "rotor_speed"], [[2e-5, 1.0], [5e-6, -3.0]],
     lambda s, inertia, speed: s.replace(rotor={"inertia": inertia},
                                         initial={"rotor_speed": speed})),
], ids=["drive_torque", "load_mass", "rotor"])
def test_other_parameters_of_a_torque_driven_drive(parameters, values, edit):
    """The batch serves other sweeps: any scene input that is one field."""
    base = scene(loads={"drive_torque": -0.04, "axial_force": -10.0})
    t_eval = np.linspace(0.0, 0.3, 7)
    samples, errors, _ = DriveBatch(base, parameters, CHANNELS, 0.3, t_eval).run(values)
    assert errors == [None, None]
    for row, ours in zip(values, samples):
        np.testing.assert_array_equal(ours, simulated(edit(base, *row), 0.3, t_eval, CHANNELS))


def test_each_case_takes_the_default_integrator_of_its_own_model():
    """Exact backlash of zero play is the thread without play: with the arctan
    law simulate's default is then an ODE integrator, not event_driven."""
    base = scene(friction={"law": "arctan_velocity", "mu": 0.3, "k_v": 1e4},
                 backlash={"axial": 1e-4})
    t_eval = [0.01, 0.05]
    options = dict(rtol=1e-6, atol=1e-9)
    samples, errors, _ = DriveBatch(base, ["clearance"], CHANNELS, 0.05, t_eval,
                                    **options).run([[0.0], [1e-4]])
    assert errors == [None, None]
    integrators = []
    for play, ours in zip([0.0, 1e-4], samples):
        result = ls.simulate(base.replace(backlash={"axial": play}), 0.05, t_eval=t_eval,
                             **options)
        integrators.append(result.integrator)
        np.testing.assert_array_equal(ours, [result[name] for name in CHANNELS])
    assert integrators[0] != integrators[1] == "event_driven"


def test_rigid_batch_efficiency_is_the_closed_form():
    """eq. (5.2) from the batch's works at steady state: tan a / tan(a + rho')
    (thesis Fig. 5.6), and the output work F v dt."""
    thread = ls.Thread(1e-3, 20e-3)
    batch = DriveBatch(speed_controlled(scene()), ["mu", "axial_force"],
                       ["work_drive", "friction_loss", "v_load"], 0.2, [0.1, 0.2])
    mu = np.array([0.0, 0.05, 0.2, 0.5])
    samples, errors, _ = batch.run(np.column_stack([mu, np.full(4, -30.0)]))
    work = samples[:, 0, 1] - samples[:, 0, 0]
    loss = samples[:, 1, 1] - samples[:, 1, 0]
    closed = [ls.efficiency(thread, m) for m in mu]
    np.testing.assert_allclose((work - loss) / work, closed, rtol=1e-12)
    np.testing.assert_allclose(samples[:, 2, 1], 10.0 * thread.lead_per_radian, rtol=1e-12)
    np.testing.assert_allclose(work - loss, 30.0 * 10.0 * thread.lead_per_radian * 0.1,
                               rtol=1e-12)


def test_failed_cases_are_rows_with_the_per_case_message():
    """A bad value, a solver failure and a jam each fail their own row, with the
    text the per-case path writes; the cases between them run."""
    base = speed_controlled(scene(concept="flexible"))
    batch = DriveBatch(base, ["mu", "axial_force"], ["u_load"], 0.01, [0.0, 0.01],
                       max_steps=50)
    samples, errors, wall_time = batch.run([[0.1, -10.0], [-1.0, -10.0], [0.1, math.nan]])
    edited = base.replace(friction={"mu": 0.1}, loads={"axial_force": -10.0})
    assert errors[0] == described(lambda: ls.simulate(edited, 0.01, t_eval=[0.0, 0.01],
                                                      max_steps=50))
    assert errors[0].startswith("SimulationError: at t = ")
    assert errors[1] == "ValueError: friction.mu = -1 is invalid: must be a finite number >= 0"
    assert errors[2] == "ValueError: axial_force = nan is invalid: must be a finite number"
    assert np.isnan(samples).all() and np.isnan(wall_time).all()

    # A self-locking drive whose load is heavy jams (test_simulation_drive.py).
    jam = ls.Scene.from_dict(thesis_scene(
        drive="nut", rotor={"inertia": 1e-6},
        thread={"pitch": 1e-3, "mean_diameter": 20e-3, "hand": "right", "flank_angle": 0.0}))
    samples, errors, _ = DriveBatch(jam, ["load_mass"], ["u_load"], 1.0, [0.0, 1.0]).run(
        [[50.0], [1.0]])
    assert errors[0] == described(lambda: ls.simulate(jam.replace(load={"mass": 50.0}), 1.0,
                                                      t_eval=[0.0, 1.0]))
    assert errors[0].startswith("JammingError")
    assert errors[1] is None and np.isfinite(samples[1]).all()


def test_a_channel_the_model_lacks_fails_each_case():
    """"gap" exists only with backlash: the batch cannot know before a case runs."""
    batch = DriveBatch(scene(), ["mu"], ["u_load", "gap"], 0.01, [0.01])
    _, errors, _ = batch.run([[0.1], [0.2]])
    assert all(e.startswith('ValueError: channels entry "gap" is invalid') for e in errors)


@pytest.mark.parametrize("parameters, channels, t_eval, options, error, match", [
    (["mu", "nu"], ["u_load"], [0.1], {}, ValueError, 'parameters entry = "nu".*"mu", "k_v"'),
    (["mu", "mu"], ["u_load"], [0.1], {}, ValueError, "must not repeat"),
    (["drive_speed"], ["u_load"], [0.1], {}, ValueError, "torque-driven"),
    (["mu"], [], [0.1], {}, ValueError, "channels"),
    (["mu"], ["u_load"], [], {}, ValueError, "t_eval"),
    (["mu"], ["u_load"], [0.1], {"friction": "arctan_velocity"}, ValueError, "friction.law"),
    (["mu"], ["u_load"], [0.1], {"t_eval": [0.1]}, TypeError, "t_eval"),
    (["mu"], ["u_load"], [0.1], {"rtoll": 1e-6}, TypeError, "rtoll"),
])
def test_bad_requests_raise_at_once(parameters, channels, t_eval, options, error, match):
    with pytest.raises(error, match=match):
        DriveBatch(scene(), parameters, channels, 0.1, t_eval, **options)


def test_drive_torque_needs_a_torque_driven_base_and_values_their_width():
    with pytest.raises(ValueError, match="speed-controlled"):
        DriveBatch(speed_controlled(scene()), ["drive_torque"], ["u_load"], 0.1, [0.1])
    batch = DriveBatch(scene(), ["mu", "axial_force"], ["u_load"], 0.1, [0.1])
    for values in ([0.1, 2.0], [[0.1]], [[[0.1, 2.0]]]):
        with pytest.raises(ValueError, match="values has shape"):
            batch.run(values)
    samples, errors, wall_time = batch.run(np.empty((0, 2)))
    assert samples.shape == (0, 1, 1) and errors == [] and wall_time.shape == (0,)


def test_rotor_speed_needs_a_torque_driven_base():
    """A speed-controlled drive starts at drive_speed(0), as its scene's
    initial.rotor_speed says: a batch does not vary it silently."""
    with pytest.raises(ValueError, match=r"parameters entry 'rotor_speed' is invalid for a "
                                         r"speed-controlled scene .* starts at drive_speed\(0\)"):
        DriveBatch(speed_controlled(scene()), ["rotor_speed"], ["u_load"], 0.1, [0.1])
    DriveBatch(scene(), ["rotor_speed"], ["u_load"], 0.1, [0.1])


def test_a_batch_pickles_and_gives_the_same_samples():
    batch = DriveBatch(speed_controlled(scene()), ["mu", "axial_force"], CHANNELS, 0.1,
                       [0.05, 0.1], rtol=1e-9)
    copy = pickle.loads(pickle.dumps(batch))
    assert copy.parameters == ["mu", "axial_force"] and copy.channels == CHANNELS
    np.testing.assert_array_equal(copy.run([[0.2, -7.0]])[0], batch.run([[0.2, -7.0]])[0])


def per_case_efficiency(base, mu, load, speed, t_end, window, **options):
    """eq. (5.2) for one case on the per-case path (the study before the batch)."""
    omega = -base.thread.hand_sign * speed
    running = base.replace(friction={"mu": mu},
                           loads={"drive_torque": None, "drive_speed": omega,
                                  "axial_force": -load},
                           initial={"rotor_speed": omega})
    start, end = window
    result = ls.simulate(running, t_end, t_eval=[0.0, start, 0.5 * (start + end), end],
                         **options)
    work, loss = result["work_drive"], result["friction_loss"]

    def eta(i, j):
        return ((work[j] - work[i]) - (loss[j] - loss[i])) / (work[j] - work[i])

    return {"efficiency": eta(1, 3),
            "window_change": abs(eta(2, 3) - eta(1, 2)) / abs(eta(1, 3)),
            "drive_torque": result["drive_torque"][3], "work_drive": work[3] - work[1],
            "friction_loss": loss[3] - loss[1], "load_speed": result["v_load"][3]}


@pytest.mark.parametrize("changes, mu, loads, options", [
    ({}, np.linspace(0.0, 0.5, 11), [10.0, 100.0], {}),
    (dict(concept="flexible_nut"), [0.05, 0.3], [20.0], dict(t_end=0.04)),
    (dict(friction={"law": "arctan_velocity", "mu": 0.3, "k_v": 1e4}), [0.1], [20.0],
     dict(t_end=0.02)),
], ids=["rigid", "flexible_nut", "arctan"])
def test_efficiency_vs_mu_matches_the_per_case_path(changes, mu, loads, options):
    base = scene(**changes)
    frame = efficiency_vs_mu(base, mu, loads, progress=False, **options)
    t_end = options.get("t_end", 0.2)
    for row in frame.itertuples():
        expected = per_case_efficiency(base, row.mu, row.load, 10.0, t_end,
                                       (t_end / 2, t_end), rtol=1e-8, atol=1e-10)
        for name, value in expected.items():
            assert getattr(row, name) == value, name
        assert row.error is None and row.wall_time > 0


def test_efficiency_rows_of_failed_and_undrivable_cases():
    """Failed rows carry the per-case message and NaN; undrivable ones are not
    simulated (eta = 0) and keep their place in the mu-major order."""
    cot = 1.0 / math.tan(ls.Thread(1e-3, 20e-3).lead_angle)
    base = scene(concept="flexible")
    frame = efficiency_vs_mu(base, [0.1, 1.01 * cot, 0.2], [20.0], t_end=0.1, max_steps=50,
                             progress=False)
    assert list(frame["simulated"]) == [True, False, True]
    for index, mu in ((0, 0.1), (2, 0.2)):
        expected = described(lambda: per_case_efficiency(base, mu, 20.0, 10.0, 0.1,
                                                         (0.05, 0.1), max_steps=50))
        assert frame.loc[index, "error"] == expected
        assert frame.loc[index, ["efficiency", "work_drive", "wall_time"]].isna().all()
    assert frame.loc[1, "error"] is None and frame.loc[1, "efficiency"] == 0.0
    assert frame.loc[1, "drive_torque"] == math.inf


def test_efficiency_options_are_checked_before_the_sweep():
    with pytest.raises(TypeError, match="t_eval"):
        efficiency_vs_mu(scene(), [0.1], [10.0], t_eval=[0.1], progress=False)
    with pytest.raises(ValueError, match="friction.law"):
        efficiency_vs_mu(scene(), [0.1], [10.0], friction="arctan_velocity", progress=False)
    # Values the core would refuse in every case alike: refused once, before
    # any case runs (the batch checks them as simulate() would).
    for options, message in [({"rtol": -1.0}, r"rtol = -1 is invalid: must be a finite "
                                               r"number in \(0, 0\.001\]"),
                             ({"integrator": "nope"}, r"integrator = \"nope\" is invalid"),
                             ({"smooth_integrator": "euler"}, "smooth_integrator"),
                             ({"max_steps": 1.5}, "max_steps = 1.5 is invalid"),
                             ({"atol": "tight"}, "atol = 'tight' is invalid"),
                             ({"max_events": -1}, "max_events = -1 is invalid"),
                             # the limits of the method between events (rigid:
                             # the one-step rk_verner6) and Moreau's step count
                             ({"max_order": 3}, "max_order = 3 is invalid: must be 0 for "
                                                "rk_verner6"),
                             ({"integrator": "moreau", "dt": 1e-3, "max_steps": 10},
                              "needs 200 steps, more than max_steps = 10")]:
        with pytest.raises(ValueError, match=message):
            efficiency_vs_mu(scene(), [0.1, 0.2], [10.0], progress=False, **options)


@pytest.mark.parametrize("chunk_size", [None, 1, 7, 1000])
def test_efficiency_is_the_same_for_every_executor_and_chunking(chunk_size, monkeypatch):
    """Chunks are independent C++ calls: how the cases are split and where they
    run changes nothing."""
    from leadscrew.studies import _sweep

    mu, loads = np.linspace(0.0, 0.5, 13), [10.0, 50.0, 100.0]
    reference = efficiency_vs_mu(scene(), mu, loads, executor=SerialExecutor(), progress=False)
    if chunk_size is not None:
        monkeypatch.setattr(_sweep, "guided_size", lambda remaining, workers, cost: chunk_size)
        monkeypatch.setattr(_sweep, "MIN_CHUNK_SECONDS", 0.0)  # no equal split at the end
    class ChunkingSerialExecutor(SerialExecutor):
        """Serial, but not exactly SerialExecutor: the sweep sends it chunks."""

    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        for executor in (SerialExecutor(), ChunkingSerialExecutor(), pool, None):
            frame = efficiency_vs_mu(scene(), mu, loads, executor=executor, progress=False)
            pd.testing.assert_frame_equal(frame.drop(columns="wall_time"),
                                          reference.drop(columns="wall_time"), check_exact=True)


def test_run_chunks_gives_chunks_in_order_and_failures_per_chunk():
    def total(cases):
        if 13 in cases:
            raise ValueError("unlucky chunk")
        return sum(cases)

    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        chunks = run_chunks(total, range(20), executor=pool, progress=False, chunk_size=6)
    assert [c.cases for c in chunks] == [range(0, 6), range(6, 12), range(12, 18),
                                         range(18, 20)]
    assert [c.value for c in chunks] == [15, 51, None, 37]
    assert [c.error for c in chunks] == [None, None, "ValueError: unlucky chunk", None]
    assert all(c.elapsed > 0 for c in chunks if c.ok) and chunks[2].elapsed == 0.0
    assert run_chunks(total, [], progress=False) == []
    pool.shutdown()
    refused = run_chunks(total, [1, 2], executor=pool, progress=False)
    assert all(c.error.startswith("RuntimeError") for c in refused)


# The batch's own threads (DriveBatch.run(values, workers)).

def jamming_batch():
    """A self-locking drive driven by its nut: a heavy load jams (JammingError),
    a light one runs, and a negative mu or a NaN mass is an invalid row."""
    jam = ls.Scene.from_dict(thesis_scene(
        drive="nut", rotor={"inertia": 1e-6},
        thread={"pitch": 1e-3, "mean_diameter": 20e-3, "hand": "right", "flank_angle": 0.0}))
    return DriveBatch(jam, ["load_mass", "mu"], CHANNELS, 0.2, [0.0, 0.05, 0.2])


MIXED_ROWS = [[1.0, 0.3], [50.0, 0.3], [2.0, -1.0], [0.5, 0.1], [math.nan, 0.3],
              [50.0, 0.2], [3.0, 0.25], [1.5, 0.0]]


def run_with(batch, values, workers):
    samples, errors, wall_time = batch.run(values, workers)
    return samples, errors, np.isnan(wall_time)


@pytest.mark.parametrize("workers", [2, 3, len(MIXED_ROWS), 64])
def test_workers_give_the_rows_of_one_thread_bit_for_bit_failures_included(workers):
    """Rows go to whichever thread is free, but each row depends only on its
    values: samples, failures and their messages are those of workers=1, with
    jamming and invalid rows between the good ones (and more workers than rows)."""
    batch = jamming_batch()
    reference = run_with(batch, MIXED_ROWS, 1)
    kinds = [e.split(":")[0] if e else None for e in reference[1]]
    assert kinds == [None, "JammingError", "ValueError", None, "ValueError", "JammingError",
                     "JammingError", None]
    for _ in range(3):  # the order the threads take rows in varies from run to run
        samples, errors, failed = run_with(batch, MIXED_ROWS, workers)
        np.testing.assert_array_equal(samples, reference[0])  # NaN rows equal too
        assert errors == reference[1]
        np.testing.assert_array_equal(failed, reference[2])


def test_the_failure_count_is_that_of_the_failed_rows():
    """The core's result counts its failed rows, so that a sweep without
    failures (the usual case) need not convert one name per row."""
    batch = jamming_batch()
    for workers in (1, 3):
        result = batch._core.run(np.array(MIXED_ROWS), workers)
        assert result.failure_count == 5 == sum(kind != "none" for kind in result.failures)
    assert batch._core.run(np.array([MIXED_ROWS[0], MIXED_ROWS[3]]), 2).failure_count == 0


def test_workers_share_a_sweep_of_cheap_cases_identically():
    """150 rigid cases of ~10 us each: the threads interleave row by row, which
    is where a data race would show."""
    batch, values = cheap_sweep()
    values[[7, 77], 0] = [-0.5, math.inf]  # invalid rows among them
    reference, errors, _ = batch.run(values)
    assert [i for i, e in enumerate(errors) if e] == [7, 77]
    for workers in (2, 4):
        for _ in range(5):
            samples, errors_now, wall_time = batch.run(values, workers)
            np.testing.assert_array_equal(samples, reference)
            assert errors_now == errors
            assert np.isnan(wall_time).sum() == 2 and (wall_time[np.isfinite(wall_time)] > 0).all()


def cheap_sweep():
    """The rigid efficiency sweep's 150 cases as a batch and its values."""
    batch = DriveBatch(speed_controlled(scene()), ["mu", "axial_force"], CHANNELS, 0.2,
                       [0.0, 0.1, 0.15, 0.2])
    mu, loads = np.linspace(0.0, 0.5, 50), [10.0, 50.0, 100.0]
    return batch, np.column_stack([np.repeat(mu, 3), -np.tile(loads, 50)])


def test_two_python_threads_run_batches_on_workers_at_once():
    """The core's helper threads are one pool per process: while one call has
    it, another (from a second Python thread) starts helpers of its own.
    Every result is the serial one, and the pool stays within one helper per
    core."""
    batch, values = cheap_sweep()
    reference, _, _ = batch.run(values)
    mismatches = []

    def sweep():
        for _ in range(8):
            samples, errors, _ = batch.run(values, 2)
            if not (np.array_equal(samples, reference) and errors == [None] * len(values)):
                mismatches.append(samples)

    threads = [threading.Thread(target=sweep) for _ in range(2)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(timeout=120)
    assert not any(thread.is_alive() for thread in threads)
    assert mismatches == []
    assert 1 <= _core.pooled_helper_count() <= max(1, os.cpu_count() or 1)


def test_a_forked_child_runs_a_batch_on_workers():
    """A process forked after a batch ran on the core's helper threads (as
    multiprocessing's fork start method does) has none of those threads: its
    own batch on 2 workers must neither wait for them nor differ. Run in a
    fresh interpreter, so the test process's own threads do not matter."""
    script = textwrap.dedent("""
        import os, sys
        import numpy as np
        sys.path.insert(0, sys.argv[1])
        from studies.test_drive_batch import cheap_sweep
        batch, values = cheap_sweep()
        reference, _, _ = batch.run(values, 2)
        child = os.fork()
        if child == 0:
            import signal
            signal.alarm(60)  # a hang ends the child with SIGALRM
            samples, errors, _ = batch.run(values, 2)
            os._exit(0 if np.array_equal(samples, reference) and not any(errors) else 3)
        _, status = os.waitpid(child, 0)
        print("child status", status)
        sys.exit(0 if os.waitstatus_to_exitcode(status) == 0 else 1)
        """)
    tests = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    done = subprocess.run([sys.executable, "-c", script, tests], capture_output=True, text=True,
                          timeout=180)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "child status 0" in done.stdout


def test_workers_call_a_python_load_under_the_gil():
    """A Python-callable load re-acquires the GIL from the core's threads (run
    releases it): no deadlock, and the per-case samples."""
    def axial_force(t):
        return -10.0 * (1.0 + t)

    base = speed_controlled(scene(loads={"axial_force": axial_force}))
    t_eval = [0.0, 0.05, 0.1]
    batch = DriveBatch(base, ["mu"], CHANNELS, 0.1, t_eval)
    mu = [0.05, 0.1, 0.2, 0.3, -1.0]
    reference = batch.run(np.array(mu)[:, None])
    samples, errors, _ = batch.run(np.array(mu)[:, None], 3)
    np.testing.assert_array_equal(samples, reference[0])
    assert errors == reference[1] == [None] * 4 + [
        "ValueError: friction.mu = -1 is invalid: must be a finite number >= 0"]
    np.testing.assert_array_equal(
        samples[2], simulated(base.replace(friction={"mu": 0.2}), 0.1, t_eval, CHANNELS))


def test_workers_with_no_rows():
    batch = DriveBatch(scene(), ["mu"], ["u_load"], 0.1, [0.1])
    samples, errors, wall_time = batch.run(np.empty((0, 1)), workers=4)
    assert samples.shape == (0, 1, 1) and errors == [] and wall_time.shape == (0,)


@pytest.mark.parametrize("workers", [0, -2, 1.5, True, "2", None])
def test_bad_workers_raise(workers):
    batch = DriveBatch(scene(), ["mu"], ["u_load"], 0.1, [0.1])
    with pytest.raises(ValueError, match=f"workers = {workers!r} is invalid: must be an "
                                         r"integer >= 1"):
        batch.run([[0.1]], workers)


@pytest.mark.parametrize("workers", [0, -3])
def test_the_core_checks_workers_itself(workers):
    """The C++ batch (leadscrew._core.DriveBatch) refuses a count < 1 too,
    before any case runs."""
    batch = DriveBatch(scene(), ["mu"], ["u_load"], 0.1, [0.1])
    with pytest.raises(ValueError, match=f"workers = {workers} is invalid: must be an integer "
                                         ">= 1"):
        batch._core.run(np.array([[0.1]]), workers)


def test_a_huge_worker_count_is_capped_at_the_rows():
    batch = DriveBatch(scene(), ["mu"], ["u_load"], 0.1, [0.1])
    samples, errors, _ = batch.run([[0.1], [0.2]], 10**12)
    np.testing.assert_array_equal(samples, batch.run([[0.1], [0.2]])[0])
    assert errors == [None, None]


def test_default_efficiency_sweep_runs_on_the_cores_threads(monkeypatch):
    """executor=None: one batch call on default_workers() threads of the core
    (no Python thread pool), the same frame as SerialExecutor and a thread
    pool's chunks, failed and undrivable rows included."""
    from leadscrew.studies import _batch, drive_efficiency

    calls = []
    run = _batch.DriveBatch.run

    def spy(self, values, workers=1):
        calls.append((len(values), workers))
        return run(self, values, workers)

    monkeypatch.setattr(_batch.DriveBatch, "run", spy)
    monkeypatch.setattr(drive_efficiency, "default_workers", lambda: 3)
    cot = 1.0 / math.tan(ls.Thread(1e-3, 20e-3).lead_angle)
    mu, loads = [0.0, 0.1, 1.01 * cot, 0.3, 0.45], [10.0, 50.0, 100.0]
    base = scene()
    default = efficiency_vs_mu(base, mu, loads, progress=False)
    assert calls == [(12, 3)]  # the 12 drivable cases, one call
    calls.clear()
    serial = efficiency_vs_mu(base, mu, loads, executor=SerialExecutor(), progress=False)
    assert {workers for _, workers in calls} == {1}
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        pooled = efficiency_vs_mu(base, mu, loads, executor=pool, progress=False)
    assert list(default["simulated"]) == [True] * 6 + [False] * 3 + [True] * 6
    for frame in (serial, pooled):
        pd.testing.assert_frame_equal(default.drop(columns="wall_time"),
                                      frame.drop(columns="wall_time"), check_exact=True)
    # A step bound too small for any case fails every simulated row alike, on
    # every path (the options themselves are valid: the cases run).
    failing = [efficiency_vs_mu(base, mu, loads, executor=executor, max_steps=3, progress=False)
               for executor in (None, SerialExecutor())]
    assert failing[0]["error"].str.startswith("SimulationError").sum() == 12
    pd.testing.assert_frame_equal(failing[0].drop(columns="wall_time"),
                                  failing[1].drop(columns="wall_time"), check_exact=True)


def test_default_efficiency_sweep_with_a_progress_bar(monkeypatch, capsys, watched):
    """With progress the sweep goes to the core in consecutive ranges (here
    forced small), the bar moving after each: the same frame."""
    from leadscrew.studies import _sweep

    mu, loads = np.linspace(0.0, 0.5, 9), [10.0, 100.0]
    quiet = efficiency_vs_mu(scene(), mu, loads, progress=False)
    monkeypatch.setattr(_sweep, "PROGRESS_SECONDS", 1e-9)  # every range a worker's cases
    shown = efficiency_vs_mu(scene(), mu, loads, progress=True)
    assert "efficiency_vs_mu" in capsys.readouterr().err
    pd.testing.assert_frame_equal(shown.drop(columns="wall_time"),
                                  quiet.drop(columns="wall_time"), check_exact=True)
