// The variables a co-simulation interface shows of a drive (the FMI 2.0 FMU
// of cpp/fmu/, whose modelDescription.xml leadscrew.fmi writes from the same
// table): the inputs held over a communication step, the outputs (result
// channels) and the parameters that may be set before the run starts (the
// friction law's, the masses and inertias, the springs' stiffness overrides).
#pragma once

#include <string>
#include <vector>

#include "leadscrew/model/drive.hpp"

namespace leadscrew::model {

struct CosimVariable {
  enum class Kind { input, output, parameter };
  std::string name;
  unsigned reference = 0;  // FMI value reference, unique
  Kind kind = Kind::output;
  bool boolean = false;    // else a real
  std::string unit;        // SI ("N.m", "kg.m2", ...; "" for a pure number)
  double start = 0.0;      // inputs: the load at t = 0; parameters: the value
  std::string description;
};

// The drive's variables: inputs drive_torque (a torque-controlled drive;
// drive_speed a speed-controlled one; the first input of an element that
// drives the rotor, element_section.hpp's RotorDrive: a DC motor's
// motor_voltage) and axial_force; outputs u_load, v_load, phi_drive,
// omega_drive, normal_force, friction_force, stick (boolean),
// friction_loss, the rotor-driving element's output (a DC motor's
// current) and the torque where it is no input, then every channel the
// drive's elements declare (stop_force, ...); parameters the friction
// law's (mu, k_v, mu_static, ...), the masses and inertias and, for a
// flexible concept, the springs' stiffness overrides (0: from the
// geometry), then the present sections' numbers marked as co-simulation
// parameters (SectionField::cosim: a DC motor's constants).
std::vector<CosimVariable> cosim_variables(const DriveParameters& parameters);

// Sets the parameter with value reference `reference` (InvalidArgument if
// it is none of cosim_variables' parameters).
void set_cosim_parameter(DriveParameters& parameters, unsigned reference, double value);

}  // namespace leadscrew::model
