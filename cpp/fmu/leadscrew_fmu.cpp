// The FMI 2.0 co-simulation FMU of a drive: one generic binary for every
// scene, which reads the scene's core spec from the FMU's resources/core.toml
// (leadscrew.fmi.export_fmu writes it with modelDescription.xml) and runs it
// on model::DriveStepper: the inputs held over a communication step (no
// input interpolation), events and stick/slip located exactly inside it.
// The variables are model::cosim_variables' (the same table as the XML's).
// SUNDIALS is linked statically: the binary needs only the C and C++
// runtimes.
#include <cmath>
#include <cstdarg>
#include <cstring>
#include <exception>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>

#include "fmi2.h"
#include "leadscrew/core/errors.hpp"
#include "leadscrew/core/validate.hpp"
#include "leadscrew/model/core_spec.hpp"
#include "leadscrew/model/cosim.hpp"
#include "leadscrew/model/drive_stepper.hpp"

namespace {

using leadscrew::model::CosimVariable;

enum class Phase { instantiated, initialization, stepping, failed, terminated };

struct Instance {
  std::string name;
  fmi2CallbackFunctions callbacks{};
  bool logging = false;
  leadscrew::model::CoreSpec spec;        // as read from resources/
  leadscrew::model::DriveParameters parameters;  // with the parameters set
  std::map<unsigned, CosimVariable> variables;
  std::map<unsigned, double> inputs;     // the held values
  // The inputs the importer has set: the others follow the scene's loads
  // (a sine or table load of the scene stays one until the importer sets
  // that input; the C API's stepper does the same).
  std::set<unsigned> set_inputs;
  std::unique_ptr<leadscrew::model::DriveStepper> stepper;
  Phase phase = Phase::instantiated;
  double last_successful_time = 0.0;

  void log(fmi2Status status, const char* category, const std::string& message) const {
    if (callbacks.logger)
      callbacks.logger(callbacks.componentEnvironment, name.c_str(), status, category, "%s",
                       message.c_str());
  }
  fmi2Status error(const std::string& message) {
    log(fmi2Error, "logStatusError", message);
    return fmi2Error;
  }
  void index() {
    variables.clear();
    inputs.clear();
    set_inputs.clear();
    for (const CosimVariable& v : leadscrew::model::cosim_variables(parameters)) {
      variables[v.reference] = v;
      if (v.kind == CosimVariable::Kind::input) inputs[v.reference] = v.start;
    }
  }
};

// resources/ from the resource location, a file URI ("file:///path/",
// "file:/path"), its %XX escapes decoded.
std::string resource_path(const char* location) {
  std::string uri = location ? location : "";
  if (uri.rfind("file://", 0) == 0)
    uri = uri.substr(7);
  else if (uri.rfind("file:", 0) == 0)
    uri = uri.substr(5);
  if (uri.rfind("localhost/", 0) == 0) uri = uri.substr(9);
  std::string path;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size()) {
      path += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      path += uri[i];
    }
  }
  if (!path.empty() && path.back() != '/') path += '/';
  return path;
}

Instance* instance(fmi2Component c) { return static_cast<Instance*>(c); }

// Runs body; the core's exceptions become fmi2Error with the message logged.
template <class Body>
fmi2Status guarded(Instance* self, Body body) {
  if (!self) return fmi2Error;
  try {
    return body();
  } catch (const std::exception& e) {
    return self->error(e.what());
  } catch (...) {
    return self->error("unknown error");
  }
}

const CosimVariable* find(Instance* self, fmi2ValueReference vr) {
  const auto at = self->variables.find(vr);
  return at == self->variables.end() ? nullptr : &at->second;
}

fmi2Status unknown_reference(Instance* self, fmi2ValueReference vr) {
  return self->error("value reference " + std::to_string(vr) + " is not a variable of this FMU");
}

// `call` (e.g. "fmi2GetReal") was given a reference of another type, or of
// none: names the variable and the call that takes it.
fmi2Status wrong_type(Instance* self, fmi2ValueReference vr, const std::string& call) {
  const CosimVariable* v = find(self, vr);
  if (!v) return unknown_reference(self, vr);
  const std::string type = v->boolean ? "Boolean" : "Real";
  const std::string access = call.compare(0, 7, "fmi2Set") == 0 ? "fmi2Set" : "fmi2Get";
  return self->error("value reference " + std::to_string(vr) + " is " + v->name + ", a " + type +
                     " variable: " + call + " does not take it (" + access + type + " does)");
}

fmi2Status unsupported(fmi2Component c, const char* what) {
  if (c) instance(c)->log(fmi2Error, "logStatusError", std::string(what) + " is not supported");
  return fmi2Error;
}

// Reads each variable (all of the type `boolean` says) through `read`;
// `call` names the function for a reference of another type.
template <class T, class Read>
fmi2Status get_values(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, T value[],
                      bool boolean, const char* call, Read read) {
  Instance* self = instance(c);
  return guarded(self, [&] {
    for (size_t i = 0; i < nvr; ++i) {
      const CosimVariable* v = find(self, vr[i]);
      if (!v || v->boolean != boolean) return wrong_type(self, vr[i], call);
      value[i] = read(*self, *v);
    }
    return fmi2OK;
  });
}

// The drive has reals and one boolean: a call of another type (`call`)
// takes no reference.
fmi2Status no_variable(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       const char* call) {
  Instance* self = instance(c);
  if (!self) return fmi2Error;
  return nvr == 0 ? fmi2OK : wrong_type(self, vr[0], call);
}

// A status query of which the FMU answers the kind `served` alone.
template <class T, class Answer>
fmi2Status status_query(fmi2Component c, fmi2StatusKind kind, fmi2StatusKind served, T* value,
                        const char* function, Answer answer) {
  Instance* self = instance(c);
  if (!self || !value) return fmi2Error;
  if (kind != served) return unsupported(c, function);
  *value = answer(*self);
  return fmi2OK;
}

}  // namespace

extern "C" {

const char* fmi2GetTypesPlatform(void) { return "default"; }
const char* fmi2GetVersion(void) { return "2.0"; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean logging_on, size_t, const fmi2String[]) {
  if (!c) return fmi2Error;
  instance(c)->logging = logging_on != fmi2False;
  return fmi2OK;
}

fmi2Component fmi2Instantiate(fmi2String instance_name, fmi2Type fmu_type, fmi2String guid,
                              fmi2String resource_location,
                              const fmi2CallbackFunctions* functions, fmi2Boolean,
                              fmi2Boolean logging_on) {
  auto self = std::make_unique<Instance>();
  self->name = instance_name ? instance_name : "";
  if (functions) self->callbacks = *functions;
  self->logging = logging_on != fmi2False;
  if (fmu_type != fmi2CoSimulation) {
    self->log(fmi2Error, "logStatusError", "this FMU is for co-simulation only");
    return nullptr;
  }
  try {
    const std::string resources = resource_path(resource_location);
    // The binary is generic: the export's GUID is in its resources, and a
    // modelDescription.xml of another export does not run this one's spec.
    std::ifstream guid_file(resources + "guid");
    std::string expected;
    std::getline(guid_file, expected);
    if (!guid_file || expected != (guid ? guid : ""))
      throw std::invalid_argument("the GUID " + std::string(guid ? guid : "(null)") +
                                  " is not this FMU's (" +
                                  (expected.empty() ? "resources/guid missing" : expected) +
                                  "): its modelDescription.xml and resources come from two "
                                  "exports");
    self->spec = leadscrew::model::read_core_spec_file(resources + "core.toml");
    self->parameters = self->spec.parameters;
    self->index();
  } catch (const std::exception& e) {
    self->log(fmi2Error, "logStatusError", e.what());
    return nullptr;
  }
  return self.release();
}

void fmi2FreeInstance(fmi2Component c) { delete instance(c); }

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean, fmi2Real, fmi2Real start_time,
                               fmi2Boolean, fmi2Real) {
  Instance* self = instance(c);
  if (!self) return fmi2Error;
  if (start_time != 0.0)
    return self->error("startTime = " + leadscrew::format_value(start_time) +
                       " is invalid: the drive starts at t = 0 (its initial state)");
  return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
  Instance* self = instance(c);
  if (!self) return fmi2Error;
  self->phase = Phase::initialization;
  return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
  Instance* self = instance(c);
  return guarded(self, [&] {
    // The drive with the parameters set (DriveModel checks them, naming each).
    self->stepper =
        std::make_unique<leadscrew::model::DriveStepper>(self->parameters, self->spec.options);
    // The inputs set so far hold from t = 0 (a speed is the one the drive
    // starts at): the outputs at t = 0 are theirs.
    for (const unsigned reference : self->set_inputs)
      self->stepper->set_input(self->variables[reference].name, self->inputs[reference]);
    self->phase = Phase::stepping;
    self->last_successful_time = 0.0;
    return fmi2OK;
  });
}

fmi2Status fmi2Terminate(fmi2Component c) {
  if (!c) return fmi2Error;
  instance(c)->phase = Phase::terminated;
  return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component c) {
  Instance* self = instance(c);
  return guarded(self, [&] {
    self->stepper.reset();
    self->parameters = self->spec.parameters;
    self->index();
    self->phase = Phase::instantiated;
    return fmi2OK;
  });
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       fmi2Real value[]) {
  return get_values(c, vr, nvr, value, false, "fmi2GetReal",
                    [](Instance& self, const CosimVariable& v) {
    if (v.kind == CosimVariable::Kind::input)
      return self.stepper && !self.set_inputs.count(v.reference) ? self.stepper->input(v.name)
                                                                 : self.inputs[v.reference];
    if (v.kind == CosimVariable::Kind::parameter) {
      // The current value: a parameter that follows another (mu_static
      // follows mu unless set) changes with it.
      // (A parameter set out of range reads as set: it is refused where the
      // initialization ends.)
      try {
        for (const CosimVariable& w : leadscrew::model::cosim_variables(self.parameters))
          if (w.reference == v.reference) return w.start;
      } catch (const leadscrew::InvalidArgument&) {
      }
      return v.start;
    }
    return self.stepper ? self.stepper->channel(v.name) : 0.0;
  });
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Boolean value[]) {
  return get_values(c, vr, nvr, value, true, "fmi2GetBoolean",
                    [](Instance& self, const CosimVariable& v) {
    return self.stepper && self.stepper->channel(v.name) != 0.0 ? fmi2True : fmi2False;
  });
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Integer[]) {
  return no_variable(c, vr, nvr, "fmi2GetInteger");
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         fmi2String[]) {
  return no_variable(c, vr, nvr, "fmi2GetString");
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       const fmi2Real value[]) {
  Instance* self = instance(c);
  return guarded(self, [&] {
    for (size_t i = 0; i < nvr; ++i) {
      const CosimVariable* v = find(self, vr[i]);
      if (!v || v->boolean) return wrong_type(self, vr[i], "fmi2SetReal");
      if (v->kind == CosimVariable::Kind::output)
        return self->error("variable " + v->name + " is an output: it cannot be set");
      if (v->kind == CosimVariable::Kind::parameter) {
        if (self->stepper)
          return self->error("parameter " + v->name +
                             " is fixed once the initialization ends (fmi2Reset to change it)");
        leadscrew::model::set_cosim_parameter(self->parameters, v->reference, value[i]);
        self->variables[v->reference].start = value[i];
        continue;
      }
      if (!std::isfinite(value[i]))
        return self->error("input " + v->name + " = " + leadscrew::format_value(value[i]) +
                           " is invalid: must be finite");
      self->inputs[v->reference] = value[i];
      self->set_inputs.insert(v->reference);
    }
    return fmi2OK;
  });
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Integer[]) {
  return no_variable(c, vr, nvr, "fmi2SetInteger");
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Boolean[]) {
  return no_variable(c, vr, nvr, "fmi2SetBoolean");
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         const fmi2String[]) {
  return no_variable(c, vr, nvr, "fmi2SetString");
}

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate*) {
  return unsupported(c, "fmi2GetFMUstate");
}
fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate) {
  return unsupported(c, "fmi2SetFMUstate");
}
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate*) {
  return unsupported(c, "fmi2FreeFMUstate");
}
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate, size_t*) {
  return unsupported(c, "fmi2SerializedFMUstateSize");
}
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate, fmi2Byte[], size_t) {
  return unsupported(c, "fmi2SerializeFMUstate");
}
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte[], size_t, fmi2FMUstate*) {
  return unsupported(c, "fmi2DeSerializeFMUstate");
}
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference[], size_t,
                                        const fmi2ValueReference[], size_t, const fmi2Real[],
                                        fmi2Real[]) {
  return unsupported(c, "fmi2GetDirectionalDerivative");
}
fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t,
                                       const fmi2Integer[], const fmi2Real[]) {
  return unsupported(c, "fmi2SetRealInputDerivatives (inputs are held over a step)");
}
fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t,
                                        const fmi2Integer[], fmi2Real[]) {
  return unsupported(c, "fmi2GetRealOutputDerivatives");
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real current_communication_point,
                      fmi2Real communication_step_size, fmi2Boolean) {
  Instance* self = instance(c);
  if (!self) return fmi2Error;
  if (self->phase == Phase::failed)
    return self->error("doStep after a failure: the run stopped at t = " +
                       leadscrew::format_value(self->stepper ? self->stepper->time()
                                                             : self->last_successful_time) +
                       " s (fmi2Reset starts it again)");
  if (self->phase != Phase::stepping || !self->stepper)
    return self->error("doStep outside the stepping phase (after fmi2ExitInitializationMode)");
  const double now = self->stepper->time();
  if (std::abs(current_communication_point - now) > 1e-9 * std::max(1.0, std::abs(now)))
    return self->error("currentCommunicationPoint = " + leadscrew::format_value(current_communication_point) +
                       " is not the FMU's time " + leadscrew::format_value(now));
  if (!(communication_step_size > 0.0))
    return self->error("communicationStepSize = " + leadscrew::format_value(communication_step_size) +
                       " is invalid: must be > 0");
  const fmi2Status status = guarded(self, [&] {
    for (const unsigned reference : self->set_inputs)
      self->stepper->set_input(self->variables[reference].name, self->inputs[reference]);
    self->stepper->advance(now + communication_step_size);
    return fmi2OK;
  });
  if (status != fmi2OK)
    self->phase = Phase::failed;
  else
    self->last_successful_time = self->stepper->time();
  return status;
}

fmi2Status fmi2CancelStep(fmi2Component c) { return unsupported(c, "fmi2CancelStep"); }

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind, fmi2Status*) {
  return unsupported(c, "fmi2GetStatus");
}
fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind kind, fmi2Real* value) {
  return status_query(c, kind, fmi2LastSuccessfulTime, value, "this fmi2GetRealStatus kind",
                      [](const Instance& self) { return self.last_successful_time; });
}
fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind, fmi2Integer*) {
  return unsupported(c, "fmi2GetIntegerStatus");
}
fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind kind, fmi2Boolean* value) {
  return status_query(c, kind, fmi2Terminated, value, "this fmi2GetBooleanStatus kind",
                      [](const Instance& self) {
                        return self.phase == Phase::failed ? fmi2True : fmi2False;
                      });
}
fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind, fmi2String*) {
  return unsupported(c, "fmi2GetStringStatus");
}

}  // extern "C"
