#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "leadscrew/core/errors.hpp"
#include "leadscrew/model/core_spec.hpp"
#include "leadscrew/model/cosim.hpp"
#include "leadscrew/model/drive.hpp"
#include "leadscrew/model/drive_batch.hpp"
#include "leadscrew/model/drive_equilibrium.hpp"
#include "leadscrew/model/drive_geometry.hpp"
#include "leadscrew/model/drive_simulation.hpp"
#include "leadscrew/model/drive_stepper.hpp"

namespace py = pybind11;

namespace leadscrew::bindings {

namespace {

// The options of simulate_drive and simulate_drive_batch from their keyword
// arguments (the same list, leadscrew.simulate's).
model::DriveSimulationOptions drive_options(double t_end, const std::string& integrator,
                                            const std::string& smooth_integrator, double rtol,
                                            double atol, double dt, double theta,
                                            std::vector<double> t_eval, long max_steps,
                                            long max_events, double max_step, double first_step,
                                            double bounce_threshold, int max_order, bool check,
                                            bool dt_given = true) {
  model::DriveSimulationOptions options;
  options.check = check;
  options.dt_given = dt_given;
  options.integrator = integrator;
  options.smooth_integrator = smooth_integrator;
  options.integrator_options =
      integrator_options(rtol, atol, max_steps, max_step, first_step, max_order);
  options.dt = dt;
  options.theta = theta;
  options.max_events = max_events;
  options.bounce_threshold = bounce_threshold;
  options.output.t_end = t_end;
  options.output.t_eval = std::move(t_eval);
  return options;
}

// Binds m.<name>(drive, t_end, integrator, ..., max_order) as body(drive,
// options): the keywords of simulate_drive, shared by the calls that take them.
template <class Body>
void def_drive_call(py::module_& m, const char* name, Body body, const char* doc) {
  m.def(
      name,
      [body](const model::DriveModel& drive, double t_end, const std::string& integrator,
             const std::string& smooth_integrator, double rtol, double atol, double dt,
             double theta, std::vector<double> t_eval, long max_steps, long max_events,
             double max_step, double first_step, double bounce_threshold, int max_order,
             bool check, bool dt_given, py::object progress) {
        return body(drive,
                    drive_options(t_end, integrator, smooth_integrator, rtol, atol, dt, theta,
                                  std::move(t_eval), max_steps, max_events, max_step,
                                  first_step, bounce_threshold, max_order, check, dt_given),
                    std::move(progress));
      },
      py::arg("drive"), py::arg("t_end"), py::arg("integrator"), py::arg("smooth_integrator"),
      py::arg("rtol"), py::arg("atol"), py::arg("dt"), py::arg("theta"), py::arg("t_eval"),
      py::arg("max_steps"), py::arg("max_events"), py::arg("max_step"), py::arg("first_step"),
      py::arg("bounce_threshold"), py::arg("max_order"), py::arg("check") = true,
      py::arg("dt_given") = true, py::arg("progress") = py::none(), doc);
}

// The derivation from geometry and the rules of the scene's inputs
// (model/drive_geometry.hpp).
void bind_drive_geometry(py::module_& m) {
  using model::DriveGeometry;
  py::class_<DriveGeometry> geometry(
      m, "DriveGeometry",
      "The scene's geometric and material inputs (SI), named <section>_<key> after its key "
      "paths; optional ones None where the scene leaves them out.");
  geometry.def(py::init<>())
      .def_property(
          "drive", [](const DriveGeometry& g) { return model::drive_name(g.drive); },
          [](DriveGeometry& g, const std::string& v) { g.drive = model::parse_drive(v); })
      .def_property(
          "backlash_contact",
          [](const DriveGeometry& g) { return model::backlash_contact_name(g.backlash_contact); },
          [](DriveGeometry& g, const std::string& v) {
            g.backlash_contact = model::parse_backlash_contact(v);
          },
          "'none' without a backlash section");
#define LEADSCREW_FIELD(name) geometry.def_readwrite(#name, &DriveGeometry::name)
  LEADSCREW_FIELD(thread_pitch);
  LEADSCREW_FIELD(thread_mean_diameter);
  LEADSCREW_FIELD(thread_starts);
  LEADSCREW_FIELD(thread_flank_angle);
  LEADSCREW_FIELD(friction_mu);
  LEADSCREW_FIELD(screw_radius);
  LEADSCREW_FIELD(screw_length);
  LEADSCREW_FIELD(screw_density);
  LEADSCREW_FIELD(screw_youngs_modulus);
  LEADSCREW_FIELD(screw_poisson);
  LEADSCREW_FIELD(nut_outer_radius);
  LEADSCREW_FIELD(nut_length);
  LEADSCREW_FIELD(nut_density);
  LEADSCREW_FIELD(nut_youngs_modulus);
  LEADSCREW_FIELD(nut_poisson);
  LEADSCREW_FIELD(load_mass);
  LEADSCREW_FIELD(backlash_axial);
  LEADSCREW_FIELD(backlash_exponent);
  LEADSCREW_FIELD(backlash_stiffness);
  LEADSCREW_FIELD(backlash_damping);
  LEADSCREW_FIELD(backlash_penetration);
  LEADSCREW_FIELD(overrides_screw_mass);
  LEADSCREW_FIELD(overrides_screw_inertia);
  LEADSCREW_FIELD(overrides_nut_mass);
  LEADSCREW_FIELD(overrides_nut_inertia);
  LEADSCREW_FIELD(overrides_screw_axial_stiffness);
  LEADSCREW_FIELD(overrides_screw_torsional_stiffness);
  LEADSCREW_FIELD(overrides_nut_axial_stiffness);
  LEADSCREW_FIELD(overrides_nut_torsional_stiffness);
#undef LEADSCREW_FIELD
}

// DerivedQuantities and the queries about them and the scene's inputs.
void bind_derived_quantities(py::module_& m) {
  using model::DerivedQuantities;
  auto as_dict = [](const std::vector<std::pair<std::string, double>>& values) {
    py::dict out;
    for (const auto& [key, value] : values) out[py::str(key)] = value;
    return out;
  };
  py::class_<DerivedQuantities>(m, "DerivedQuantities",
                                "What a DriveGeometry gives the model (derive_drive).")
      .def_property_readonly(
          "derived", [as_dict](const DerivedQuantities& d) { return as_dict(d.derived()); },
          "Scene.derived(): masses [kg], inertias [kg*m^2], rigidities [N, N*m^2], "
          "stiffnesses [N/m, N*m/rad] and with backlash the contact's values")
      .def_property_readonly(
          "quantities",
          [as_dict](const DerivedQuantities& d) { return as_dict(d.quantities()); },
          "every quantity with a range: tan_lead_angle, effective_mu, then derived's")
      .def_property_readonly(
          "problem",
          [](const DerivedQuantities& d) -> py::object {
            const model::DerivedQuantity* q = model::first_out_of_range(d.quantities());
            if (q == nullptr) return py::none();
            return py::str(q->key);
          },
          "the key of the first quantity out of its range, or None")
      .def("apply_to", &DerivedQuantities::apply_to, py::arg("parameters"),
           "Set the masses, inertias, rigidities, stiffnesses and contact values of "
           "DriveParameters.");
  m.def("derive_drive", &model::derive, py::arg("geometry"),
        "Masses, inertias, rigidities and stiffnesses of a DriveGeometry (thesis eq. 4.17, "
        "4.18, 4.24), overrides applied; never raises (a value out of range: problem).");
  m.def(
      "derived_quantities",
      []() {
        py::list out;
        for (const model::DerivedQuantity& q : model::derived_quantities()) {
          py::dict entry;
          entry["key"] = q.key;
          entry["text"] = q.text;
          entry["unit"] = q.unit;
          entry["low"] = q.low;
          entry["low_open"] = q.low_open;
          entry["high"] = q.high;
          entry["override"] = q.override_key;
          out.append(entry);
        }
        return out;
      },
      "The derived quantities with their texts, units, ranges and overrides, in order.");
}

// The rules a scene's inputs must satisfy, for the Scene's checks.
void bind_scene_rules(py::module_& m) {
  m.def(
      "derived_quantity_problem",
      [](const std::string& key, double value) -> py::object {
        const model::DerivedQuantity* q = model::find_derived_quantity(key);
        if (q == nullptr) throw InvalidArgument("no derived quantity " + key);
        const std::string problem = q->problem(value);
        if (problem.empty()) return py::none();
        return py::str(problem);
      },
      py::arg("key"), py::arg("value"),
      "None if value is in the quantity's range, else what it must be.");
  m.def(
      "first_derived_problem",
      [](const std::vector<std::pair<std::string, double>>& values) -> py::object {
        const model::DerivedQuantity* q = model::first_out_of_range(values);
        if (q == nullptr) return py::none();
        return py::str(q->key);
      },
      py::arg("values"),
      "The key of the first of the (key, value) pairs out of its quantity's range, or None.");
  m.def(
      "check_nut_on_screw",
      [](const std::string& drive, double nut_position, double nut_length, double screw_length,
         bool explain) {
        model::require_nut_on_screw(model::parse_drive(drive), nut_position, nut_length,
                                    screw_length, explain);
      },
      py::arg("drive"), py::arg("nut_position"), py::arg("nut_length"),
      py::arg("screw_length"), py::arg("explain") = true,
      "ValueError naming nut.position unless the whole nut is on the screw: nut_length / 2 < "
      "nut_position < screw_length - nut_length / 2 [m].");
  m.def(
      "rigid_jamming_margins",
      [](const Thread& thread, double kappa, double inertia, double mass) {
        const model::JammingMargins j = model::rigid_jamming_margins(thread, kappa, inertia, mass);
        py::dict out;
        out["lhs1"] = j.lhs1;
        out["rhs1"] = j.rhs1;
        out["jams1"] = j.jams1;
        out["lhs2"] = j.lhs2;
        out["rhs2"] = j.rhs2;
        out["jams2"] = j.jams2;
        out["mass1"] = j.mass1;
        out["inertia2"] = j.inertia2;
        return out;
      },
      py::arg("thread"), py::arg("kappa"), py::arg("inertia"), py::arg("mass"),
      "The rigid drive's two dynamic jamming (Painleve) inequalities for the friction factor "
      "kappa (mu' for exact Coulomb): lhs1, rhs1, jams1, lhs2, rhs2, jams2 [kg*m^2], mass1 "
      "[kg] and inertia2 [kg*m^2] (inf where never).");
  m.def(
      "spring_frequency_problem",
      [](const model::DriveModel& drive) -> py::object {
        const std::string problem = model::spring_frequency_problem(drive);
        if (problem.empty()) return py::none();
        return py::str(problem);
      },
      py::arg("drive"),
      "None, or what is wrong with a spring of the drive: its part's natural angular "
      "frequency sqrt(k / m) not finite or above 1e12 rad/s.");
  m.def("scene_choices", &model::scene_choices,
        "(key path, names) of the scene's choices the model's enumerations give.");
}

}  // namespace

namespace {

// The elements' sections (element_section.hpp): the registry as dicts, the
// Scene's check of one, DriveParameters.sections and each section's
// attributes (its presence, its numbers).
model::ElementSection to_section(const model::SectionType& type, const py::dict& values) {
  model::ElementSection section;
  section.present = true;
  for (const auto& [key_handle, value] : values) {
    const std::string key = py::str(key_handle);
    const int index = type.field_index(key);
    if (index < 0) {
      std::string names;
      for (const model::SectionField& f : type.fields)
        names += (names.empty() ? "" : ", ") + std::string(f.key);
      throw InvalidArgument(std::string(type.name) + "." + key + " is not a known key; " +
                            type.name + " takes " + names);
    }
    const bool is_choice =
        type.fields[static_cast<std::size_t>(index)].kind == model::SectionField::Kind::choice;
    try {
      if (is_choice)
        section.choices.emplace_back(key, py::cast<std::string>(value));
      else
        section.numbers.emplace_back(key, py::cast<double>(value));
    } catch (const py::cast_error&) {
      throw InvalidArgument(std::string(type.name) + "." + key + " = " +
                            std::string(py::repr(value)) + " is invalid: must be " +
                            (is_choice ? "a name (str)" : "a number (SI)"));
    }
  }
  return section;
}

py::dict field_entry(const model::SectionField& f) {
  using Presence = model::SectionField::Presence;
  const bool is_choice = f.kind == model::SectionField::Kind::choice;
  py::dict entry;
  entry["key"] = f.key;
  entry["unit"] = f.unit;
  entry["doc"] = f.doc;
  entry["kind"] = is_choice ? "choice" : "float";
  entry["presence"] = f.presence == Presence::required   ? "required"
                      : f.presence == Presence::optional ? "optional"
                                                         : "default";
  entry["default"] = is_choice ? py::object(py::str(f.choices.front()))
                               : py::object(py::float_(f.value));
  entry["default_doc"] = f.default_doc;
  entry["low"] = f.low;
  entry["high"] = f.high;
  entry["low_open"] = f.low_open;
  entry["high_open"] = f.high_open;
  entry["choices"] = f.choices;
  entry["attribute"] = f.attribute ? py::object(py::str(f.attribute)) : py::object(py::none());
  return entry;
}

// The registry as dicts and the Scene's check of one section.
void bind_section_queries(py::module_& m) {
  using model::DriveParameters;
  m.def(
      "element_sections",
      []() {
        py::list sections;
        for (const model::SectionType& type : model::element_section_types()) {
          if (type.scene != nullptr) continue;  // (its fields in another scene section)
          py::list fields;
          for (const model::SectionField& f : type.fields) fields.append(field_entry(f));
          py::dict section;
          section["name"] = type.name;
          section["doc"] = type.doc;
          section["fields"] = fields;
          section["presence_attribute"] = type.presence_attribute();
          sections.append(section);
        }
        return sections;
      },
      "The elements' scene sections (the registry, element_section.hpp): name, doc, "
      "presence_attribute and fields (key, unit, doc, kind, presence, default, default_doc, "
      "low, high, low_open, high_open, choices, attribute).");
  m.def(
      "check_element_section",
      [](const std::string& name, const py::dict& values, const DriveParameters& context) {
        const model::SectionType& type = model::element_section_type(name);
        model::check_element_section(name, to_section(type, values), context);
      },
      py::arg("name"), py::arg("values"), py::arg("context"),
      "The Scene's check of the section `name` (its values checked field by field, with "
      "their defaults) across its fields and the sections `context` gives (concept, drive, "
      "initial_state, ...): ValueError naming the key path, the value and what is allowed.");
}

// One section's attributes on DriveParameters: its presence (a flag or a
// choice), its numbers and its inputs.
void bind_section_attributes(py::class_<model::DriveParameters>& parameters,
                             const model::SectionType* t) {
  using model::DriveParameters;
  const model::SectionType& type = *t;
  if (type.flag != nullptr)
    parameters.def_property(
        type.flag,
        [t](const DriveParameters& p) { return model::find_section(p, t->name) != nullptr; },
        [t](DriveParameters& p, bool present) {
          model::set_section_presence(p, *t, present ? "true" : "false");
        },
        "True if the model has the section");
  else
    parameters.def_property(
        type.presence_attribute().c_str(),
        [t](const DriveParameters& p) { return model::section_presence(p, *t); },
        [t](DriveParameters& p, const std::string& v) { model::set_section_presence(p, *t, v); },
        "the section's choice ('none': no such section)");
  for (std::size_t i = 0; i < type.fields.size(); ++i) {
    const model::SectionField& f = type.fields[i];
    if (f.kind != model::SectionField::Kind::number || f.attribute == nullptr) continue;
    const int index = static_cast<int>(i);
    parameters.def_property(
        f.attribute,
        [t, index](const DriveParameters& p) { return model::section_number(p, *t, index); },
        [t, index](DriveParameters& p, double v) { model::set_section_number(p, *t, index, v); },
        f.doc);
  }
  for (std::size_t i = 0; i < type.inputs.size(); ++i) {
    const int index = static_cast<int>(i);
    const std::string path = type.key_path(type.inputs[i].key);
    parameters.def_property(
        type.inputs[i].name,
        [t, index](const DriveParameters& p) -> Excitation {
          return model::section_input(p, *t, index);
        },
        [t, index, path](DriveParameters& p, py::handle v) {
          model::set_section_input(p, *t, index, to_excitation(v, path));
        },
        type.inputs[i].doc);
  }
}

void bind_element_sections(py::module_& m, py::class_<model::DriveParameters>& parameters) {
  using model::DriveParameters;
  bind_section_queries(m);
  parameters.def_property(
      "sections",
      [](const DriveParameters& p) {
        py::dict out;
        for (const auto& [name, section] : p.sections) {
          if (!section.present || model::element_section_type(name).scene != nullptr) continue;
          py::dict values;
          for (const auto& [key, value] : section.numbers) values[py::str(key)] = value;
          for (const auto& [key, value] : section.choices) values[py::str(key)] = value;
          out[py::str(name)] = values;
        }
        return out;
      },
      [](DriveParameters& p, const py::dict& sections) {
        // (A section carried in another scene section, by its attributes,
        // stays: the DC motor's.)
        model::ElementSections out;
        for (const auto& [name, section] : p.sections)
          if (model::element_section_type(name).scene != nullptr) out[name] = section;
        for (const auto& [name, values] : sections) {
          const model::SectionType& type = model::element_section_type(py::str(name));
          out[type.name] = to_section(type, py::cast<py::dict>(values));
        }
        p.sections = std::move(out);
      },
      "the elements' scene sections present (element_section.hpp), by name: the values given "
      "by key (a scene's section as is; the rest take their defaults)");
  for (const model::SectionType& type : model::element_section_types())
    bind_section_attributes(parameters, &type);
}

}  // namespace

namespace {

void bind_drive_parameters(py::module_& m) {
  using model::DriveParameters;
  py::class_<DriveParameters> parameters(m, "DriveParameters",
                                         "Resolved drive parameters (SI); built by leadscrew.Scene.");
  parameters.def(py::init<>())
      .def_property(
          "concept", [](const DriveParameters& p) { return model::concept_name(p.concept); },
          [](DriveParameters& p, const std::string& v) { p.concept = model::parse_concept(v); })
      .def_property(
          "drive", [](const DriveParameters& p) { return model::drive_name(p.drive); },
          [](DriveParameters& p, const std::string& v) { p.drive = model::parse_drive(v); })
      .def_property(
          "support", [](const DriveParameters& p) { return model::support_name(p.support); },
          [](DriveParameters& p, const std::string& v) { p.support = model::parse_support(v); })
      .def_property(
          "backlash",
          [](const DriveParameters& p) { return model::backlash_contact_name(p.backlash); },
          [](DriveParameters& p, const std::string& v) {
            p.backlash = model::parse_backlash_contact(v);
          })
      .def_property(
          "friction", [](const DriveParameters& p) { return p.friction; },
          [](DriveParameters& p, const std::string& v) {
            friction::law_type(v);  // raises for an unknown law
            p.friction = v;
          })
      .def_readwrite("friction_values", &DriveParameters::friction_values,
                     "the law's parameters besides mu and k_v, as (key, value) pairs")
      .def_property(
          "initial_state",
          [](const DriveParameters& p) { return model::initial_state_name(p.initial_state); },
          [](DriveParameters& p, const std::string& v) {
            p.initial_state = model::parse_initial_state(v);
          })
      .def_readwrite("thread", &DriveParameters::thread)
      .def_property(
          "drive_torque", [](const DriveParameters& p) { return p.drive_torque; },
          [](DriveParameters& p, py::handle v) { p.drive_torque = to_excitation(v, "loads.drive_torque"); })
      .def_property(
          "drive_speed", [](const DriveParameters& p) { return p.drive_speed; },
          [](DriveParameters& p, py::handle v) { p.drive_speed = to_excitation(v, "loads.drive_speed"); })
      .def_property(
          "axial_force", [](const DriveParameters& p) { return p.axial_force; },
          [](DriveParameters& p, py::handle v) { p.axial_force = to_excitation(v, "loads.axial_force"); })
      .def_property(
          "base_acceleration", [](const DriveParameters& p) { return p.base_acceleration; },
          [](DriveParameters& p, py::handle v) {
            p.base_acceleration = to_excitation(v, "loads.base_acceleration");
          })
      .def_property(
          "base_angular_acceleration",
          [](const DriveParameters& p) { return p.base_angular_acceleration; },
          [](DriveParameters& p, py::handle v) {
            p.base_angular_acceleration = to_excitation(v, "loads.base_angular_acceleration");
          })
      .def_property(
          "transverse_slip_velocity",
          [](const DriveParameters& p) { return p.transverse_slip_velocity; },
          [](DriveParameters& p, py::handle v) {
            p.transverse_slip_velocity = to_excitation(v, "loads.transverse_slip_velocity");
          });
  for (const model::ScalarField& field : model::scalar_fields())
    parameters.def_readwrite(field.name, field.member);
  parameters.def_readwrite("speed_controlled", &DriveParameters::speed_controlled);
  parameters.def_property(
      "gear", [](const DriveParameters& p) { return model::gear_type_name(p.gear); },
      [](DriveParameters& p, const std::string& v) { p.gear = model::parse_gear_type(v); },
      "the gear stage between the rotor and the driven part: 'none', 'ideal' (gear_ratio "
      "rotor turns per turn of the driven part), 'lossy' (gear_efficiency, "
      "gear_efficiency_backdrive) or 'worm' (gear_lead_angle, gear_mu, gear_mu_static, "
      "gear_flank_angle)");
  bind_element_sections(m, parameters);
  bind_drive_geometry(m);
  bind_derived_quantities(m);
  bind_scene_rules(m);
}

void bind_drive_model(py::module_& m) {
  using model::DriveParameters;
  py::class_<model::DriveModel>(m, "DriveModel", "An assembled drive (immutable).")
      .def(py::init<DriveParameters>(), py::arg("parameters"))
      .def_property_readonly("coordinate_names", &model::DriveModel::coordinate_names)
      .def_property_readonly("mass", [](const model::DriveModel& d) { return d.mass(); })
      .def_property_readonly("degrees_of_freedom",
                             [](const model::DriveModel& d) {
                               return static_cast<int>(d.independent().size()) -
                                      (d.parameters().speed_controlled ? 1 : 0);
                             })
      .def_property_readonly("springs",
                             [](const model::DriveModel& d) {
                               py::list out;
                               for (const auto& s : d.springs()) {
                                 double derivative = 0.0;
                                 py::dict entry;
                                 entry["name"] = s.name;
                                 entry["stiffness"] = d.spring_stiffness(
                                     s, d.parameters().nut_position, &derivative);
                                 entry["damping"] = s.damping;
                                 out.append(entry);
                               }
                               return out;
                             })
      .def_property_readonly("effective_mu", &model::DriveModel::effective_mu)
      .def_property_readonly(
          "train_friction",
          [](const model::DriveModel& d) -> py::object {
            const model::elements::TrainFriction* f = d.train_friction();
            if (!f) return py::none();
            py::dict out;
            out["motor_friction_torque"] = f->motor_friction;
            out["stage"] = f->stage;
            out["efficiency"] = f->efficiency;
            out["efficiency_backdrive"] = f->efficiency_backdrive;
            out["efficiency_static"] = f->efficiency_static;
            out["efficiency_backdrive_static"] = f->efficiency_backdrive_static;
            out["self_locking"] = f->self_locking();
            return out;
          },
          "The train's friction stages (docs/physics/gear.md, \"Friction stages\"), None "
          "without: dict with motor_friction_torque [N m] (on the rotor), stage (a lossy or "
          "worm stage), the stage's efficiencies forward and backward in slip and at "
          "breakaway (a worm's from mu and mu_static; 1 without a stage), and self_locking "
          "(the backward one at breakaway <= 0).")
      .def(
          "initial_state",
          [](const model::DriveModel& d) {
            const model::DriveStart start = model::initial_state(d);
            py::dict out;
            out["q"] = start.q;
            out["v"] = start.v;
            out["play"] = start.play;
            out["normal_force"] = start.normal_force;
            out["friction_force"] = start.friction_force;
            out["iterations"] = start.iterations;
            return out;
          },
          "The state at t = 0 that initial.state asks for: dict with q and v (every "
          "coordinate and velocity, in coordinate_names' order), play [m], normal_force and "
          "friction_force [N] (the flank forces holding the loads: 0 for a relaxed start), "
          "iterations (Newton's). NoEquilibriumError where the loads at t = 0 have no static "
          "equilibrium.")
      .def_property_readonly("parameters", &model::DriveModel::parameters);
}

void bind_drive_queries(py::module_& m) {
  m.def("drive_integrators", &model::drive_integrators, py::arg("parameters"));
  m.def(
      "drive_channel_units",
      [] {
        py::dict units;
        for (const auto& [name, unit] : model::drive_channel_units()) units[py::str(name)] = unit;
        return units;
      },
      "The SI unit of every result channel a drive may write, by name (\"m\", \"N*m\", "
      "\"J\", \"\" for the flag stick), as the core's elements declare them; not the "
      "coordinates' pairs u_<body>, v_<body>, phi_<body>, omega_<body> beyond u_load, v_load, "
      "phi_drive and omega_drive.");
  m.attr("smallest_gear_ratio") = model::elements::kSmallestGearRatio;
  def_drive_call(
      m, "simulate_drive",
      [](const model::DriveModel& drive, const model::DriveSimulationOptions& options,
         py::object progress) {
        PythonMonitor monitor(std::move(progress));
        MonitorScope scope(&monitor);
        py::gil_scoped_release release;
        return model::simulate(drive, options);
      },
      "Simulate the drive (leadscrew.simulate's drive path); progress: None or a callable "
      "of the simulated time, called about every 0.1 s of wall time (Ctrl-C is checked "
      "there too).");
  def_drive_call(
      m, "check_drive_options",
      [](const model::DriveModel& drive, const model::DriveSimulationOptions& options,
         const py::object&) { model::check_simulation_options(drive, options); },
      "The checks simulate_drive makes of these options before it integrates, without "
      "simulating: ValueError naming the option, its value and the valid range.");
}

void bind_core_spec(py::module_& m) {
  using model::DriveParameters;
  m.def(
      "write_core_spec",
      [](const DriveParameters& parameters, const std::string& integrator,
         const std::string& smooth_integrator, double rtol, double atol, long max_steps,
         long max_events, double max_step, double first_step, double bounce_threshold,
         int max_order) {
        return model::write_core_spec(
            parameters, drive_options(1.0, integrator, smooth_integrator, rtol, atol, 1e-4, 0.5,
                                      {}, max_steps, max_events, max_step, first_step,
                                      bounce_threshold, max_order, true));
      },
      py::arg("parameters"), py::arg("integrator"), py::arg("smooth_integrator"),
      py::arg("rtol"), py::arg("atol"), py::arg("max_steps"), py::arg("max_events"),
      py::arg("max_step"), py::arg("first_step"), py::arg("bounce_threshold"),
      py::arg("max_order"),
      "The core spec (TOML text, model/core_spec.hpp) of the parameters and the run's "
      "options. ValueError for a callable load.");
  m.def(
      "read_core_spec",
      [](const std::string& text) {
        const model::CoreSpec spec = model::read_core_spec(text);
        const integrate::IntegratorOptions& o = spec.options.integrator_options;
        py::dict options;
        options["integrator"] = spec.options.integrator;
        options["smooth_integrator"] = spec.options.smooth_integrator;
        options["rtol"] = o.rtol;
        options["atol"] = o.atol;
        options["max_steps"] = o.max_steps;
        options["max_events"] = spec.options.max_events;
        options["max_step"] = o.max_step;
        options["first_step"] = o.first_step;
        options["max_order"] = o.max_order;
        options["bounce_threshold"] = spec.options.bounce_threshold;
        return py::make_tuple(spec.parameters, options);
      },
      py::arg("text"),
      "(DriveParameters, options dict) from a core spec's TOML text. ValueError naming the "
      "key for a bad spec.");

  m.def(
      "cosim_variables",
      [](const DriveParameters& parameters) {
        py::list out;
        for (const model::CosimVariable& v : model::cosim_variables(parameters)) {
          py::dict entry;
          entry["name"] = v.name;
          entry["reference"] = v.reference;
          entry["kind"] = v.kind == model::CosimVariable::Kind::input    ? "input"
                          : v.kind == model::CosimVariable::Kind::output ? "output"
                                                                         : "parameter";
          entry["boolean"] = v.boolean;
          entry["unit"] = v.unit;
          entry["start"] = v.start;
          entry["description"] = v.description;
          out.append(entry);
        }
        return out;
      },
      py::arg("parameters"),
      "The variables the FMU shows of the drive (model/cosim.hpp): dicts with name, "
      "reference, kind (input, output, parameter), boolean, unit, start, description.");
}

void bind_drive_stepper(py::module_& m) {
  py::class_<model::DriveStepper>(
      m, "DriveStepper",
      "A drive advanced piece by piece with its inputs held over each piece "
      "(model/drive_stepper.hpp): simulate_drive's event-driven run, its state kept.")
      .def(py::init([](const model::DriveModel& drive, const std::string& integrator,
                       const std::string& smooth_integrator, double rtol, double atol,
                       long max_steps, long max_events, double max_step, double first_step,
                       double bounce_threshold, int max_order) {
             model::DriveSimulationOptions options =
                 drive_options(1.0, integrator, smooth_integrator, rtol, atol, 1e-4, 0.5, {},
                               max_steps, max_events, max_step, first_step, bounce_threshold,
                               max_order, false);
             return std::make_unique<model::DriveStepper>(drive.parameters(), options);
           }),
           py::arg("drive"), py::arg("integrator"), py::arg("smooth_integrator"),
           py::arg("rtol"), py::arg("atol"), py::arg("max_steps"), py::arg("max_events"),
           py::arg("max_step"), py::arg("first_step"), py::arg("bounce_threshold"),
           py::arg("max_order"),
           "The drive at t = 0; the options as simulate_drive's (integrator \"\": the "
           "model's default; \"moreau\" refused). ValueError for a bad option.")
      .def_property_readonly("time", &model::DriveStepper::time, "The time reached [s].")
      .def_property_readonly("input_names", &model::DriveStepper::input_names)
      .def_property_readonly("channel_names", &model::DriveStepper::channel_names)
      .def("advance", &model::DriveStepper::advance, py::arg("t"),
           py::call_guard<py::gil_scoped_release>(),
           "Advance to t [s] >= time with the inputs held. SimulationError (the nut at the "
           "screw's end, a solver failure), JammingError; ValueError for t < time.")
      .def("set_input", &model::DriveStepper::set_input, py::arg("name"), py::arg("value"),
           "Set the input (input_names: \"drive_torque\" [N*m], \"motor_voltage\" [V] or "
           "\"drive_speed\" [rad/s], and \"axial_force\" [N]) to value from time on: held, "
           "but a speed ramps to value over the next advance (set before the first advance: "
           "the start speed). ValueError for an unknown name or a bad value.")
      .def("input", &model::DriveStepper::input, py::arg("name"),
           "The input's value at time (SI).")
      .def("channel", &model::DriveStepper::channel, py::arg("name"),
           "The result channel at time (simulate's names, SI).")
      .def("channels", &model::DriveStepper::channels,
           "Every channel at time, in channel_names' order.")
      .def_property_readonly(
          "events",
          [](const model::DriveStepper& s) {
            py::list out;
            for (const integrate::Event& e : s.events()) out.append(py::make_tuple(e.time, e.kind));
            return out;
          },
          "The events so far: (time [s], kind) tuples.")
      .def_property_readonly(
          "stats",
          [](const model::DriveStepper& s) { return stats_dict(s.stats()); },
          "Counts so far, as Result.stats (wall_time 0).")
      .def("reset", &model::DriveStepper::reset, "Back to t = 0 and the drive's own loads.");
}

void bind_drive_batch(py::module_& m) {
  using model::DriveParameters;
  py::class_<model::DriveBatchResult>(m, "DriveBatchResult",
                                      "What DriveBatch.run gives: samples and failures.")
      .def_property_readonly(
          "samples",
          [](const model::DriveBatchResult& r) {
            py::array_t<double> out({static_cast<py::ssize_t>(r.samples.rows()),
                                     static_cast<py::ssize_t>(r.channel_count),
                                     static_cast<py::ssize_t>(r.time_count)});
            std::copy(r.samples.data(), r.samples.data() + r.samples.size(),
                      out.mutable_data());
            return out;
          },
          "(cases, channels, sample times) array; NaN in a failed case's rows.")
      .def_property_readonly(
          "failures",
          [](const model::DriveBatchResult& r) {
            std::vector<std::string> names;
            for (model::CaseFailure f : r.failures) names.push_back(model::case_failure_name(f));
            return names;
          },
          "Per case: \"none\", \"invalid_argument\" (ValueError), \"simulation\" "
          "(SimulationError), \"jamming\" (JammingError) or \"other\" (RuntimeError).")
      .def_property_readonly("failure_count", &model::DriveBatchResult::failure_count,
                             "Cases that failed (0: no need to read failures).")
      .def_readonly("messages", &model::DriveBatchResult::messages,
                    "Per case: the failure's message, \"\" where none.")
      .def_readonly("wall_time", &model::DriveBatchResult::wall_time,
                    "Per case: the simulation's wall time [s, C++ clock], NaN where it failed.");

  py::class_<model::DriveBatch>(
      m, "DriveBatch",
      "Simulations of one drive that differ in a few scalar parameters (immutable).")
      .def(py::init([](DriveParameters base, const std::vector<std::string>& parameters,
                       std::vector<std::string> channels, double t_end,
                       const std::string& integrator, const std::string& smooth_integrator,
                       double rtol, double atol, double dt, double theta,
                       std::vector<double> t_eval, long max_steps, long max_events,
                       double max_step, double first_step, double bounce_threshold,
                       int max_order, bool check, bool dt_given) {
             return model::DriveBatch(
                 std::move(base), parameters, std::move(channels),
                 drive_options(t_end, integrator, smooth_integrator, rtol, atol, dt, theta,
                               std::move(t_eval), max_steps, max_events, max_step,
                               first_step, bounce_threshold, max_order, check, dt_given));
           }),
           py::arg("base"), py::arg("parameters"), py::arg("channels"), py::arg("t_end"),
           py::arg("integrator"), py::arg("smooth_integrator"), py::arg("rtol"),
           py::arg("atol"), py::arg("dt"), py::arg("theta"), py::arg("t_eval"),
           py::arg("max_steps"), py::arg("max_events"), py::arg("max_step"),
           py::arg("first_step"), py::arg("bounce_threshold"), py::arg("max_order"),
           py::arg("check") = true, py::arg("dt_given") = true,
           "base: DriveParameters; parameters: the fields each case sets (numeric "
           "DriveParameters attributes; drive_torque, drive_speed, axial_force as "
           "constants); channels: the result channels to sample at t_eval; the rest as "
           "simulate_drive (integrator \"\": each case's default). ValueError for a bad "
           "request.")
      .def_property_readonly("parameter_count", &model::DriveBatch::parameter_count)
      .def_property_readonly("channels", &model::DriveBatch::channels)
      .def(
          "run",
          [](const model::DriveBatch& batch, const Eigen::Ref<const model::BatchValues>& values,
             int workers) {
            py::gil_scoped_release release;  // for the whole batch
            return batch.run(values, workers);
          },
          py::arg("values"), py::arg("workers") = 1,
          "Simulate one case per row of values (cases, parameters): a DriveBatchResult. A "
          "failed case sets its row's failure and message. workers: threads that share the "
          "rows, >= 1 (capped at the row count; 1: the calling thread only); the result is "
          "the same for every count. ValueError for a wrong width or workers < 1.");
}

}  // namespace

// The drive's classes and functions, in the order their signatures name them.
void bind_drive(py::module_& m) {
  bind_drive_parameters(m);
  bind_drive_model(m);
  bind_drive_queries(m);
  bind_core_spec(m);
  bind_drive_stepper(m);
  bind_drive_batch(m);
}

}  // namespace leadscrew::bindings
