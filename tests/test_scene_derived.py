"""Scene.derived() from the core's derivation (model/drive_geometry.hpp)
against the closed forms of tests/helpers/drive_derivation.py, and the rules
the core checks once for the scene and the model alike: the ranges of the
derived quantities, the nut on the screw, the rigid drive's jamming
inequalities and the names of the enumerations."""

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import leadscrew as ls
from leadscrew import _core
from helpers.drive_derivation import derived_reference, thread_reference
from helpers.rigid_drive_reference import RigidDrive
from helpers.scenes import thesis_scene

REL = 1e-13  # the reference sums and multiplies in another order


def assert_matches(scene_dict, rel=REL):
    scene = ls.Scene.from_dict(scene_dict)
    derived = scene.derived()
    reference = derived_reference(scene.to_dict())
    assert list(derived) == list(reference)  # the same keys, in Scene.derived()'s order
    for key, value in reference.items():
        assert derived[key] == pytest.approx(value, rel=rel, abs=0.0), key
    return derived


def test_thesis_drive_against_the_closed_forms():
    d = assert_matches(thesis_scene())
    # Table 5.1's screw (r 10 mm, 0.5 m, steel) and nut (POM, r_o 12 mm, 20 mm):
    # m_S = 7850 pi 1e-4 0.5, E_M A_M / l_M = 2e9 pi 44e-6 / 0.02.
    assert d["screw_mass"] == pytest.approx(7850 * math.pi * 1e-4 * 0.5, rel=1e-14)
    assert d["nut_axial_stiffness"] == pytest.approx(2e9 * math.pi * 44e-6 / 0.02, rel=1e-14)
    assert d["screw_axial_stiffness"] == 0.0 == d["screw_torsional_stiffness"]
    assert "contact_stiffness" not in d


@pytest.mark.parametrize("key", ["screw_mass", "screw_inertia", "nut_mass", "nut_inertia",
                                 "screw_axial_stiffness", "screw_torsional_stiffness",
                                 "nut_axial_stiffness", "nut_torsional_stiffness"])
def test_each_override_replaces_its_quantity_alone(key):
    base = ls.Scene.from_dict(thesis_scene(backlash={"axial": 1e-4, "contact": "bistop"}))
    given = 1.2345 * (base.derived()[key] or 1e6)
    d = assert_matches(thesis_scene(backlash={"axial": 1e-4, "contact": "bistop"},
                                    overrides={key: given}))
    assert d[key] == given
    # An overridden mass carries into what depends on it (inertia, contact damping).
    changed = {k for k, v in d.items() if v != base.derived()[k]}
    follows = {"screw_mass": {"screw_inertia"}, "nut_mass": {"nut_inertia", "contact_damping"},
               "nut_axial_stiffness": {"contact_stiffness", "contact_damping"}}
    assert changed == {key} | follows.get(key, set())


@pytest.mark.parametrize("drive, carried", [("screw", "nut_mass"), ("nut", "screw_mass")])
@pytest.mark.parametrize("contact, exponent", [("bistop", 1.5), ("bistop", 1.0),
                                               ("bistop", 2.5), ("cubic", 3.0),
                                               ("exact", 1.5)])
def test_contact_defaults(drive, carried, contact, exponent):
    scene = thesis_scene(drive=drive, backlash={"axial": 2e-4, "contact": contact,
                                                "exponent": exponent})
    d = assert_matches(scene)
    d0 = d["contact_penetration"]
    assert d0 == 2e-6  # c_a / 100
    e = exponent if contact == "bistop" else 1.0
    # The contact's force at d_0 is the nut's spring force k_M d_0.
    assert d["contact_stiffness"] * d0**e == pytest.approx(d["nut_axial_stiffness"] * d0,
                                                           rel=1e-12)
    # Critical damping of k_M with the load and the translating part.
    m = 1.0 + d[carried]
    assert d["contact_damping"] == pytest.approx(2 * math.sqrt(d["nut_axial_stiffness"] * m),
                                                 rel=1e-12)


def test_contact_limits_and_overrides():
    # The penetration of full damping is at least 1e-7 m (c_a / 100 below it).
    d = assert_matches(thesis_scene(backlash={"axial": 1e-6}))
    assert d["contact_penetration"] == 1e-7
    d = assert_matches(thesis_scene(backlash={"axial": 1e-5 * (1 + 1e-9)}))
    assert d["contact_penetration"] == 1e-5 * (1 + 1e-9) / 100
    # Without play (exact, 0 m) the values are there, as for any backlash section.
    assert_matches(thesis_scene(backlash={"axial": 0.0}))
    given = {"stiffness": 3e9, "damping": 0.0, "penetration": 5e-7}
    d = assert_matches(thesis_scene(backlash={"axial": 1e-4, "contact": "bistop", **given}))
    assert (d["contact_stiffness"], d["contact_damping"], d["contact_penetration"]) == (
        3e9, 0.0, 5e-7)
    # A given stiffness sets the default damping; a given penetration the default stiffness.
    d = assert_matches(thesis_scene(backlash={"axial": 1e-4, "contact": "bistop",
                                              "stiffness": 3e9}))
    assert d["contact_damping"] == pytest.approx(
        2 * math.sqrt(3e9 * 1e-6**0.5 * (1.0 + d["nut_mass"])), rel=1e-12)
    d = assert_matches(thesis_scene(backlash={"axial": 1e-4, "contact": "cubic",
                                              "penetration": 5e-7}))
    assert d["contact_stiffness"] == d["nut_axial_stiffness"]


def test_a_thin_walled_nut_and_a_massless_load():
    r_s, r_o = 10e-3, 10e-3 * (1 + 1e-12)
    # r_o^4 - r_S^4 from the squares loses digits by the condition number
    # (r_o^4 + r_S^4) / (r_o^4 - r_S^4), about 5e11 here: a few ulps of it.
    condition = (r_o**4 + r_s**4) / ((r_o - r_s) * (r_o + r_s) * (r_o**2 + r_s**2))
    d = assert_matches(thesis_scene(nut={"outer_radius": r_o}, load={"mass": 0.0},
                                    backlash={"axial": 1e-4}),
                       rel=8 * 2.0**-52 * condition)
    assert 0.0 < d["nut_mass"] < 1e-12 and d["contact_damping"] > 0.0


@pytest.mark.parametrize("changes, key", [
    ({"nut": {"outer_radius": 1e300}}, "nut_mass"),
    ({"screw": {"density": 1.0, "radius": 1e-170}}, "screw_mass"),
    ({"thread": {"pitch": 1e-9}}, "tan_lead_angle"),
    ({"thread": {"pitch": 1e5, "starts": 100}}, "tan_lead_angle"),
])
def test_the_core_names_the_quantity_out_of_range(changes, key):
    """derive_drive never raises: it names the first quantity out of its
    range, which the scene turns into a message naming the inputs."""
    d = thesis_scene(concept="flexible", **changes)
    scene_data = {**ls.Scene.from_dict(thesis_scene(concept="flexible")).to_dict()}
    for section, values in changes.items():
        scene_data[section] = {**scene_data[section], **values}
    derivation = _core.derive_drive(ls.scene._geometry(scene_data))
    assert derivation.problem == key
    value = derivation.quantities[key]
    assert _core.derived_quantity_problem(key, value) is not None
    with pytest.raises(ValueError, match=r"is invalid: with it .* comes to "):
        ls.Scene.from_dict(d).derived()


def test_the_quantities_ranges():
    assert _core.derived_quantity_problem("tan_lead_angle", 1e-6) is None
    assert _core.derived_quantity_problem("tan_lead_angle", 1e6) is None
    assert _core.derived_quantity_problem("tan_lead_angle", 1e6 * (1 + 1e-15)) == "in [1e-06, 1e+06]"
    assert _core.derived_quantity_problem("nut_mass", 0.0) == "a finite number > 0"
    assert _core.derived_quantity_problem("contact_damping", 0.0) is None
    assert _core.derived_quantity_problem("contact_damping", -0.0) is None
    assert _core.derived_quantity_problem("contact_damping", -1e-300) == "a finite number >= 0"
    assert _core.derived_quantity_problem("screw_axial_stiffness", math.inf) is not None
    assert _core.derived_quantity_problem("effective_mu", math.nan) is not None
    with pytest.raises(ValueError, match="no derived quantity"):
        _core.derived_quantity_problem("mass", 1.0)
    keys = [q["key"] for q in _core.derived_quantities()]
    assert keys[:2] == ["tan_lead_angle", "effective_mu"]
    assert keys[2:] == list(derived_reference(thesis_scene(backlash={"axial": 1e-4})))


def test_the_thread_quantities():
    d = thesis_scene(thread={"pitch": 2e-3, "starts": 3, "flank_angle": math.radians(30)},
                     friction={"mu": 0.2})
    scene = ls.Scene.from_dict(d)
    quantities = _core.derive_drive(ls.scene._geometry(scene.to_dict())).quantities
    for key, value in thread_reference(scene.to_dict()).items():
        assert quantities[key] == pytest.approx(value, rel=1e-15)
    assert quantities["effective_mu"] == pytest.approx(scene.model().effective_mu, rel=1e-15)


def test_apply_to_feeds_the_model_the_derived_values():
    scene = ls.Scene.from_dict(thesis_scene(concept="flexible",
                                            backlash={"axial": 1e-4, "contact": "bistop"}))
    parameters = scene.model().parameters
    for key, value in scene.derived().items():
        assert getattr(parameters, key) == value, key


lengths = st.floats(1e-3, 1.0)
moduli = st.floats(1e7, 1e12)
densities = st.floats(100.0, 2e4)
poissons = st.floats(-0.9, 0.5)


@st.composite
def geometries(draw):
    r_s = draw(st.floats(1e-3, 0.1))
    nut_length = draw(st.floats(1e-3, 0.2))
    screw_length = draw(st.floats(2.5 * nut_length, 2.0))
    scene = thesis_scene(
        drive=draw(st.sampled_from(["screw", "nut"])),
        screw={"radius": r_s, "length": screw_length, "youngs_modulus": draw(moduli),
               "poisson": draw(poissons), "density": draw(densities)},
        nut={"outer_radius": r_s * draw(st.floats(1.01, 5.0)), "length": nut_length,
             "youngs_modulus": draw(moduli), "poisson": draw(poissons),
             "density": draw(densities), "position": screw_length / 2},
        load={"mass": draw(st.floats(0.0, 100.0))})
    if draw(st.booleans()):
        contact = draw(st.sampled_from(["exact", "bistop", "cubic"]))
        backlash = {"axial": draw(st.floats(0.0, 1e-3)), "contact": contact,
                    "exponent": draw(st.floats(1.0, 10.0))}
        for key, values in (("stiffness", st.floats(1e3, 1e12)), ("damping", st.floats(0.0, 1e4)),
                            ("penetration", st.floats(1e-8, 1e-4))):
            if draw(st.booleans()):
                backlash[key] = draw(values)
        scene["backlash"] = backlash
    overrides = {}
    for key in ("screw_mass", "screw_inertia", "nut_mass", "nut_inertia",
                "screw_axial_stiffness", "screw_torsional_stiffness", "nut_axial_stiffness",
                "nut_torsional_stiffness"):
        if draw(st.integers(0, 3)) == 0:
            overrides[key] = draw(st.floats(1e-6, 1e9))
    scene["overrides"] = overrides
    return scene


@settings(max_examples=300, deadline=None, derandomize=True)
@given(scene=geometries())
def test_derived_equals_the_closed_forms_over_random_geometry(scene):
    # The contact's exponents make d_0^(1 - e) d_0^(e - 1) differ from 1 by a
    # few ulps of each power (up to e = 10).
    assert_matches(scene, rel=1e-12)


@pytest.mark.parametrize("drive, end", [("screw", "drive end"), ("nut", "load end")])
def test_the_nut_on_the_screw_is_one_rule(drive, end):
    """The scene and the model check the same rule (the core's), with the
    scene's message naming what the position is measured from."""
    _core.check_nut_on_screw(drive, 0.0101, 0.02, 0.5)
    _core.check_nut_on_screw(drive, 0.4899, 0.02, 0.5)
    for position in (0.01, 0.49, 0.6, -0.1):
        with pytest.raises(ValueError, match=rf"the screw's {end} for drive = '{drive}': the "
                                             r"whole nut on the screw; nut.length = 0.02, "
                                             r"screw.length = 0.5\)$"):
            _core.check_nut_on_screw(drive, position, 0.02, 0.5)
        with pytest.raises(ValueError, match=r"= \(0.01, 0.49\): the whole nut on the screw$"):
            _core.check_nut_on_screw(drive, position, 0.02, 0.5, explain=False)


@pytest.mark.parametrize("mu, J, m", [(0.3, 6.265376e-5, 1.003870), (0.3, 1e-9, 1e3),
                                      (5.0, 1e-3, 1e-6), (0.0, 1e-5, 1.0)])
def test_the_jamming_margins_against_the_rigid_reference(mu, J, m):
    """The rigid reference's mode denominators Delta_+ = rhs1 - lhs1 and
    Delta_- = tan^2(a) (rhs2 - lhs2): a drive jams where one is <= 0."""
    thread = ls.Thread(0.2 if mu == 5.0 else 1e-3, 20e-3)
    reference = RigidDrive(lead=thread.lead, mean_radius=10e-3, mu=mu, rotor_inertia=J,
                           screw_inertia=0.0, screw_mass=0.0, nut_inertia=0.0, nut_mass=0.0,
                           load_mass=m)
    jm = _core.rigid_jamming_margins(thread, thread.effective_mu(mu), J, m)
    tan_a = reference.tan_alpha
    scale = J + m * 1e-4
    assert jm["rhs1"] - jm["lhs1"] == pytest.approx(reference.delta(1.0), rel=1e-9, abs=1e-14 * scale)
    assert tan_a**2 * (jm["rhs2"] - jm["lhs2"]) == pytest.approx(reference.delta(-1.0), rel=1e-9,
                                                                 abs=1e-14 * scale)
    assert jm["jams1"] == (reference.delta(1.0) <= 0.0)
    assert jm["jams2"] == (reference.delta(-1.0) <= 0.0)


def test_the_scene_takes_the_enumerations_names_from_the_core():
    choices = dict(_core.scene_choices())
    assert choices == {"concept": ["rigid", "flexible_nut", "flexible"],
                       "drive": ["screw", "nut"], "screw.support": ["both_ends", "drive_end"],
                       "backlash.contact": ["exact", "bistop", "cubic"],
                       "initial.state": ["relaxed", "equilibrium"]}
    schema = ls.scene.SCHEMA
    fields = {"concept": schema["concept"], "drive": schema["drive"],
              "screw.support": schema["screw"]["support"],
              "backlash.contact": schema["backlash"]["contact"],
              "initial.state": schema["initial"]["state"]}
    for path, names in choices.items():
        assert fields[path].choices == tuple(names)
        for name in names:  # each one the core parses
            parameters = _core.DriveParameters()
            attribute = {"concept": "concept", "drive": "drive", "screw.support": "support",
                         "backlash.contact": "backlash", "initial.state": "initial_state"}[path]
            setattr(parameters, attribute, name)
            assert getattr(parameters, attribute) == name
