"""compare_concepts: one load case on the three concepts (thesis Figs. 5.1-5.3)."""

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

import leadscrew as ls  # noqa: E402
from helpers.scenes import thesis_scene  # noqa: E402
from leadscrew.studies._sweep import SerialExecutor  # noqa: E402
from leadscrew.studies.concepts import (  # noqa: E402
    CONCEPTS,
    compare_concepts,
    plot_compare_concepts,
)

T_END = 0.5


@pytest.fixture(scope="module")
def by_nut_modulus():
    """Table 5.1 case (5.1) with E_M = 2 GPa, 200 MPa, 20 MPa (Figs. 5.2, 5.3 go softer)."""
    return {e: compare_concepts(ls.Scene.from_dict(thesis_scene(nut={"youngs_modulus": e})),
                                t_end=T_END, progress=False)
            for e in (2e9, 2e8, 2e7)}


def test_rows_columns_and_units(by_nut_modulus):
    frame = by_nut_modulus[2e9]
    assert list(frame["concept"]) == list(CONCEPTS)
    assert frame["error"].isna().all()
    assert set(frame["reference"]) == {"flexible"}
    assert frame.loc[2, "max_abs_diff"] == 0.0 and frame.loc[2, "rms_diff"] == 0.0
    assert (frame["wall_time"] > 0).all() and (frame["steps"] > 0).all()
    units = frame.attrs["units"]
    assert set(units) == set(frame.columns)
    assert units["max_abs_diff"] == "m" and units["wall_time"] == "s"
    assert all(len(t) == 2001 and t[-1] == T_END for t in frame["t"])


def test_differences_are_those_of_the_simulations(by_nut_modulus):
    """The reported difference is recomputed from direct simulations."""
    scene = ls.Scene.from_dict(thesis_scene(nut={"youngs_modulus": 2e8}))
    t = np.linspace(0.0, T_END, 2001)
    u = {c: ls.simulate(scene.replace(concept=c), T_END, t_eval=t)["u_load"]
         for c in ("rigid", "flexible")}
    frame = by_nut_modulus[2e8]
    assert frame.loc[0, "max_abs_diff"] == np.max(np.abs(u["rigid"] - u["flexible"]))
    np.testing.assert_array_equal(frame.loc[0, "u_load"], u["rigid"])


def test_the_rigid_concept_departs_as_the_nut_softens(by_nut_modulus):
    """The flexible concepts add the nut's elastic deflection, F / k with
    k = E_M A / l: the rigid drive's departure grows as 1 / E_M. The two
    flexible concepts differ by the screw's compliance, which does not change."""
    rigid = [by_nut_modulus[e].loc[0, "max_abs_diff"] for e in (2e9, 2e8, 2e7)]
    assert rigid[0] < rigid[1] < rigid[2]
    for stiffer, softer in zip(rigid, rigid[1:]):
        assert softer / stiffer == pytest.approx(10.0, rel=0.1)
    nut_only = [by_nut_modulus[e].loc[1, "max_abs_diff"] for e in (2e9, 2e8, 2e7)]
    assert max(nut_only) < rigid[0]


def test_a_failed_concept_is_a_row_and_the_reference_falls_back():
    with pytest.warns(ls.StudyWarning, match=r"compare_concepts: 2 of 3 rows raised and decide "
                                             r"nothing .*: 2 SimulationError; first: "
                                             r"SimulationError: .*max_steps"):
        frame = compare_concepts(ls.Scene.from_dict(thesis_scene()), t_end=T_END, points=11,
                                 max_steps=2000, executor=SerialExecutor(), progress=False)
    assert frame.attrs["summary"]["raised"] == 2
    assert frame.attrs["summary"]["raised_reasons"].startswith("2 SimulationError; first: "
                                                               "SimulationError: ")
    assert frame.attrs["summary_units"] == {"raised": "1"}
    assert frame.loc[0, "error"] is None
    assert frame.loc[1, "error"].startswith("SimulationError")
    assert frame.loc[2, "error"].startswith("SimulationError")
    assert list(frame["reference"]) == ["rigid"] * 3
    assert frame.loc[0, "max_abs_diff"] == 0.0
    assert np.isnan(frame.loc[1, "max_abs_diff"]) and frame.loc[1, "u_load"] is None
    ax = plot_compare_concepts(frame)
    assert len(ax.lines) == 1


def test_plot(by_nut_modulus):
    ax = plot_compare_concepts(by_nut_modulus[2e7])
    assert len(ax.lines) == 3
    assert ax.get_xlabel() == "time t [s]"


@pytest.mark.parametrize("concepts, match", [((), "at least one"), (("stiff",), "stiff"),
                                             (("rigid", "rigid"), "twice")])
def test_bad_concepts(concepts, match):
    with pytest.raises(ValueError, match=match):
        compare_concepts(ls.Scene.from_dict(thesis_scene()), concepts=concepts)


def test_bad_arguments():
    scene = ls.Scene.from_dict(thesis_scene())
    with pytest.raises(ValueError, match="points"):
        compare_concepts(scene, points=1)
    with pytest.raises(ValueError, match="t_end"):
        compare_concepts(scene, t_end=-1.0)
    # Simulate options: checked once per concept before the runs (not a
    # row of the same message per concept).
    with pytest.raises(ValueError, match="rtol = -1 is invalid"):
        compare_concepts(scene, rtol=-1.0, progress=False)
    # (Moreau-Jean runs penalty flanks now: an ODE method on exact play is
    # the option every concept refuses.)
    with pytest.raises(ValueError, match=r"integrator = \"dopri5\" is invalid for backlash"):
        compare_concepts(scene.replace(backlash={"axial": 1e-4, "contact": "exact"}),
                         integrator="dopri5", progress=False)
    # An option that only some concepts refuse fails their rows only: the
    # rigid concept's default method between events is one-step (no order).
    frame = compare_concepts(scene, t_end=0.02, points=5, max_order=3, progress=False)
    errors = frame.set_index("concept")["error"]
    assert errors["rigid"].startswith("ValueError: max_order = 3 is invalid: must be 0 for "
                                      "rk_verner6")
    assert errors["flexible_nut"] is None and errors["flexible"] is None
    # Moreau's fixed steps over the study's t_end count against max_steps.
    with pytest.raises(ValueError, match="needs 100 steps, more than max_steps = 99"):
        compare_concepts(scene, t_end=0.1, integrator="moreau", dt=1e-3, max_steps=99,
                         progress=False)
    with pytest.raises(TypeError, match="bogus"):
        compare_concepts(scene, bogus=1, progress=False)
