"""leadscrew.RandomVibration (a stationary Gaussian load from a one-sided
PSD) against its target: the RMS against the square root of the PSD's
integral (log-log segments integrated independently here, by quadrature on a
fine grid), Welch's estimate against the target in every 1/3-octave band of
the range, reproducibility by seed; its errors; named profiles; the scene's
``{type = "random"}`` load through TOML and the core spec."""

import math

import numpy as np
import pytest
from scipy import integrate, signal

import leadscrew as ls

# A vehicle-body-like PSD in (m/s^2)^2/Hz (its values are only a test input).
FREQUENCIES = [10.0, 55.0, 180.0, 300.0, 360.0, 1000.0, 2000.0]
PSD = [20.0, 6.5, 0.25, 0.25, 0.14, 0.14, 0.14]


def target_integral(lo, hi):
    """The PSD's integral over [lo, hi], log-log interpolated, by quadrature."""
    def psd(f):
        return math.exp(np.interp(math.log(f), np.log(FREQUENCIES), np.log(PSD)))
    points = [f for f in FREQUENCIES if lo < f < hi]
    return integrate.quad(psd, lo, hi, points=points or None, limit=200, epsrel=1e-10)[0]


def third_octave_bands():
    """The base-ten 1/3-octave bands (IEC 61260) inside the PSD's range."""
    bands = []
    for k in range(-20, 4):
        centre = 1000.0 * 10.0 ** (k / 10.0)
        lo, hi = centre * 10.0 ** (-1 / 20), centre * 10.0 ** (1 / 20)
        if lo >= FREQUENCIES[0] and hi <= FREQUENCIES[-1]:
            bands.append((lo, hi))
    return bands


@pytest.mark.parametrize("seed", [0, 7])
def test_rms_and_welch_psd_match_the_target(seed):
    duration, fs = 20.0, 8192.0
    load = ls.RandomVibration(FREQUENCIES, PSD, seed=seed, duration=duration)
    t = np.arange(0.0, duration, 1.0 / fs)
    x = load(t)
    rms = math.sqrt(target_integral(FREQUENCIES[0], FREQUENCIES[-1]))
    assert load.rms == pytest.approx(rms, rel=1e-9)  # the core's closed form
    assert np.sqrt(np.mean(x ** 2)) == pytest.approx(rms, rel=0.03)
    assert abs(np.mean(x)) < 1e-3 * rms
    f, p = signal.welch(x, fs=fs, nperseg=2 ** 15)  # 0.25 Hz lines, Hann window
    df = f[1] - f[0]
    bands = third_octave_bands()
    assert len(bands) == 22
    for lo, hi in bands:
        inside = (f >= lo) & (f < hi)
        estimate = p[inside].sum() * df
        error_db = 10.0 * math.log10(estimate / target_integral(lo, hi))
        assert abs(error_db) <= 3.0, (lo, hi, error_db)


def test_gaussian_band_limited_and_periodic():
    load = ls.RandomVibration(FREQUENCIES, PSD, seed=3, duration=5.0)
    t = np.arange(0.0, 5.0, 1.0 / 8192.0)
    x = load(t)
    kurtosis = np.mean((x - x.mean()) ** 4) / np.var(x) ** 2
    assert kurtosis == pytest.approx(3.0, abs=0.15)
    spectrum = np.abs(np.fft.rfft(x)) ** 2
    lines = np.fft.rfftfreq(len(x), 1.0 / 8192.0)
    outside = (lines < 9.0) | (lines > 2001.0)
    assert spectrum[outside].sum() < 1e-6 * spectrum.sum()
    assert np.allclose(load(t + 5.0), x, rtol=0, atol=1e-9 * load.rms)


def test_same_seed_same_signal_other_seed_another():
    t = np.linspace(0.0, 2.0, 20001)
    a = ls.RandomVibration(FREQUENCIES, PSD, seed=11, duration=2.0)(t)
    b = ls.RandomVibration(FREQUENCIES, PSD, seed=11, duration=2.0)(t)
    c = ls.RandomVibration(FREQUENCIES, PSD, seed=12, duration=2.0)(t)
    assert np.array_equal(a, b)
    assert abs(np.corrcoef(a, c)[0, 1]) < 0.1


def test_units_of_the_psd():
    load = ls.RandomVibration(["10 Hz", "2 kHz"], ["1 (m/s^2)^2/Hz", "1 (m/s^2)^2/Hz"],
                              duration="2 s")
    assert load.unit == "m/s^2"
    assert load.rms == pytest.approx(math.sqrt(1990.0), rel=1e-12)
    in_g = ls.RandomVibration([10.0, 2000.0], ["0.01 g0^2/Hz", "0.01 g0^2/Hz"], duration=2.0)
    assert in_g.psd[0] == pytest.approx(0.01 * 9.80665 ** 2, rel=1e-12)
    with pytest.raises(ValueError, match=r"psd\[1\] = .* is invalid: \(N\)\^2/Hz, but"):
        ls.RandomVibration([10.0, 20.0], ["1 (m/s^2)^2/Hz", "1 N^2/Hz"])
    with pytest.raises(ValueError, match=r"psd\[0\] = .*is invalid: must be a PSD"):
        ls.RandomVibration([10.0, 20.0], ["1 m/s^2", "1 m/s^2"])


@pytest.mark.parametrize("arguments, message", [
    (dict(frequencies=[10.0], psd=[1.0]), r"at least two breakpoints"),
    (dict(frequencies=[10.0, 5.0], psd=[1.0, 1.0]), r"frequencies\[1\] = 5 is invalid: "
                                                      r"frequencies must be strictly increasing"),
    (dict(frequencies=[10.0, 20.0], psd=[1.0, 0.0]), r"psd\[1\] = 0 is invalid: must be "
                                                      r"a finite number > 0"),
    (dict(frequencies=[10.0, 20.0], psd=[1.0]), r"must have the same length"),
    (dict(frequencies=[10.2, 10.6], psd=[1.0, 1.0], duration=1.0), r"duration = 1 s is "
                                                                     r"invalid: its frequency"),
    (dict(frequencies=[10.0, 2000.0], psd=[1.0, 1.0], duration=1e4), r"duration = 10000 s "
                                                                      r"is invalid.*2\^24"),
    (dict(frequencies=[10.0, 2000.0], psd=[1.0, 1.0], duration=1e300), r"duration = 1e\+300 s "
                                                                        r"is invalid.*2\^24"),
    (dict(frequencies=[10.0, 1e300], psd=[1.0, 1.0]), r"duration = 10 s is invalid with a "
                                                       r"highest frequency of 1e\+300 Hz"),
    (dict(frequencies=[10.0, 20.0], psd=[1.0, 1.0], seed=-1), r"seed = -1 is invalid"),
    (dict(frequencies=[10.0, 20.0], psd=[1.0, 1.0], seed=1.5), r"seed = 1.5 is invalid"),
])
def test_invalid_arguments_name_the_value_and_range(arguments, message):
    with pytest.raises(ValueError, match=message):
        ls.RandomVibration(**arguments)


def test_profiles_name_their_source_and_warn_when_unverified():
    assert ls.profiles.names() == ["iso16750_3_test_iv"]
    info = ls.profiles.info("iso16750_3_test_iv")
    assert "ISO 16750-3" in info.source and not info.verified
    with pytest.warns(ls.profiles.ProfileWarning, match="not verified"):
        load = ls.profiles.load("iso16750_3_test_iv", seed=4, duration=2.0)
    assert load.unit == "m/s^2" and list(load.frequencies) == list(info.frequencies)
    with pytest.raises(ValueError, match=r"name = 'nope' is invalid: must be one of"):
        ls.profiles.load("nope")


def test_scene_round_trips_a_random_base_acceleration(tmp_path):
    scene = ls.scenes.load("position_holding")
    spec = {"type": "random", "frequencies": ["10 Hz", "500 Hz"],
            "psd": ["2 (m/s^2)^2/Hz", "0.5 (m/s^2)^2/Hz"], "seed": 5, "duration": "2 s"}
    vibrated = scene.replace(loads={"base_acceleration": spec})
    stored = vibrated.to_dict()["loads"]["base_acceleration"]
    assert stored == {"type": "random", "frequencies": [10.0, 500.0], "psd": [2.0, 0.5],
                      "seed": 5, "duration": 2.0}
    path = tmp_path / "vibrated.toml"
    vibrated.to_toml(path)
    again = ls.Scene.from_toml(path)
    assert again == vibrated
    t = np.linspace(0.0, 1.0, 101)
    expected = ls.RandomVibration([10.0, 500.0], [2.0, 0.5], seed=5, duration=2.0)(t)
    assert np.array_equal(again.model().parameters.base_acceleration(t), expected)
    with pytest.warns(ls.profiles.ProfileWarning, match="iso16750_3_test_iv"):
        named = scene.replace(loads={"base_acceleration": {
            "type": "random", "profile": "iso16750_3_test_iv", "seed": 1, "duration": 1.0}})
    assert named.to_dict()["loads"]["base_acceleration"]["psd"][0] == 20.0
    with pytest.raises(ValueError, match=r"loads.base_acceleration.seed = -2 is invalid"):
        scene.replace(loads={"base_acceleration": {**spec, "seed": -2}})
    with pytest.raises(ValueError, match=r"loads.axial_force.profile = 'iso16750_3_test_iv' "
                                         r"is invalid: must be absent: a profile is an acceleration"):
        scene.replace(loads={"axial_force": {"type": "random", "profile": "iso16750_3_test_iv"}})


def test_core_spec_round_trips_a_random_load():
    scene = ls.scenes.load("position_holding").replace(loads={
        "axial_force": {"type": "random", "frequencies": [20.0, 400.0], "psd": [4.0, 1.0],
                        "seed": 9, "duration": 1.5},
        "base_acceleration": {"type": "random", "frequencies": [20.0, 400.0],
                              "psd": [4.0, 1.0], "seed": 10, "duration": 1.5}})
    text = scene.to_core_toml()
    assert 'type = "random"' in text and "seed = 10" in text
    parameters, options = ls._core.read_core_spec(text)
    assert ls._core.write_core_spec(parameters, **options) == text
    t = np.linspace(0.0, 1.0, 101)
    original = scene.model().parameters
    for key in ("axial_force", "base_acceleration"):
        assert np.array_equal(getattr(parameters, key)(t), getattr(original, key)(t))


def test_pickles_with_its_unit():
    # (studies send loads to worker processes)
    import pickle

    load = ls.RandomVibration([10.0, 100.0], ["1 (m/s^2)^2/Hz"] * 2, seed=4, duration=2.0)
    again = pickle.loads(pickle.dumps(load))
    assert again.unit == "m/s^2" and again.seed == 4
    t = np.linspace(0.0, 1.0, 11)
    assert np.array_equal(again(t), load(t))
    assert load.replace(seed=5).unit == "m/s^2" and not np.array_equal(load.replace(seed=5)(t),
                                                                        load(t))
