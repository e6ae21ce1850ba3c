"""An exact end stop after a decaying run of bounces (issue 31, reproduction
1): a rebound whose flight lies below the integrator's resolution made the
gap's root fire with the load leaving, the event left the load one ulp
beyond the face, and the gap's root (it ends the free flight only falling
through 0) never fired again: the load passed the rigid stop by 0.215 mm
with every check passing. The physics asserted with the checks off
(``check=False``), and the result check ``exact_stops`` that now catches
the class (docs/physics/end_stops.md, "Exact stops";
docs/physics/result_checks.md, "exact_stops")."""

import numpy as np
import pytest

import leadscrew as ls

UPPER = 0.0005  # [m]


def reproduction(concept="flexible", restitution=0.4):
    """The issue's scene: 200 N press the load (on the nut's soft spring, a
    47 MPa nut) into an exact upper stop 0.5 mm ahead."""
    return ls.Scene.from_dict({
        "concept": concept, "thread": {"pitch": 0.0007, "mean_diameter": 0.02},
        "friction": {"mu": 0.2}, "nut": {"youngs_modulus": 47000000.0},
        "loads": {"axial_force": 200.0},
        "end_stops": {"upper": UPPER, "contact": "exact", "restitution": restitution}})


def resolution(r, rtol=1e-8, atol=1e-10):
    """The root's resolution on the load's position (result_checks.md,
    exact_stops): the largest speed times 128 ulp of t_end, and ten times
    the integrator's tolerance on the face's position (the defaults)."""
    eps = np.finfo(float).eps
    return (np.max(np.abs(r["v_load"])) * 128 * eps * r.t[-1] + 10 * (atol + rtol * UPPER)
            + 64 * eps * UPPER)


@pytest.mark.parametrize("concept", ["flexible", "flexible_nut"])
@pytest.mark.parametrize("restitution", [0.1, 0.4, 0.8])
def test_the_load_never_passes_an_exact_stop(concept, restitution):
    # (At e = 0.8 the bounces decay more slowly: the load passed the stop
    # after 0.02 s, before 0.05 s.)
    r = ls.simulate(reproduction(concept, restitution), 0.05, check=False)
    impacts = [e for e in r.events if "upper end stop impact" in e.kind]
    assert len(impacts) >= 2  # (it bounces)
    assert np.max(r["u_load"]) - UPPER <= resolution(r)
    check = r.checks["exact_stops"]
    assert check["applies"] and check["passed"], check
    assert check["value"] <= check["bound"] <= resolution(r) * (1 + 1e-12)


@pytest.mark.parametrize("concept", ["flexible", "flexible_nut"])
@pytest.mark.parametrize("restitution", [0.1, 0.4, 0.8])
def test_the_bounces_end_in_a_closed_contact_holding_the_load(concept, restitution):
    # Before 0.05 s the rebounds fall below the bounce threshold: the
    # contact closes and holds the load at the face (zero speed), the stop
    # pushing it back (toward -u) against the 200 N.
    r = ls.simulate(reproduction(concept, restitution), 0.05)
    closed = [e.time for e in r.events if "upper end stop impact, closed" in e.kind]
    assert len(closed) == 1
    after = r.t > closed[0]
    assert np.all(r["u_load"][after] == UPPER)
    assert np.all(r["v_load"][after] == 0.0)
    assert np.all(r["stop_force"][after] < 0.0)
    assert r["u_load"][-1] == UPPER


def test_the_result_check_is_reported_where_the_scene_has_exact_stops_only():
    r = ls.simulate(reproduction(), 0.005)
    assert r.checks["exact_stops"]["applies"]
    penalty = ls.Scene.from_dict({
        "concept": "flexible", "thread": {"pitch": 0.0007, "mean_diameter": 0.02},
        "friction": {"mu": 0.2}, "loads": {"axial_force": 200.0},
        "end_stops": {"upper": UPPER, "stiffness": 1e7}})
    assert not ls.simulate(penalty, 0.005).checks["exact_stops"]["applies"]
