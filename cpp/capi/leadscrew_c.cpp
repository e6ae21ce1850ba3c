// The C API (leadscrew/leadscrew.h) over model::DriveStepper and the core
// spec: every call catches what the core throws and turns it into a status
// and the thread's last error text.
#include "leadscrew/leadscrew.h"

#include <cmath>
#include <exception>
#include <memory>
#include <new>
#include <string>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/model/core_spec.hpp"
#include "leadscrew/model/drive_stepper.hpp"

struct leadscrew_drive {
  std::unique_ptr<leadscrew::model::DriveStepper> stepper;
};

namespace {

thread_local std::string last_error;

int fail(int status, const std::string& message) {
  try {
    last_error = message;
  } catch (...) {  // no memory for the text
  }
  return status;
}

// Runs body, mapping the core's exceptions to status codes.
template <class Body>
int guarded(Body body) {
  try {
    body();
    return LEADSCREW_OK;
  } catch (const leadscrew::JammingError& e) {
    return fail(LEADSCREW_JAMMING, e.what());
  } catch (const leadscrew::SimulationError& e) {
    return fail(LEADSCREW_SIMULATION_ERROR, e.what());
  } catch (const std::invalid_argument& e) {
    return fail(LEADSCREW_INVALID_ARGUMENT, e.what());
  } catch (const std::bad_alloc&) {
    return fail(LEADSCREW_ERROR, "out of memory");
  } catch (const std::exception& e) {
    return fail(LEADSCREW_ERROR, e.what());
  } catch (...) {
    return fail(LEADSCREW_ERROR, "unknown error");
  }
}

bool null_argument(const void* pointer, const char* what) {
  if (pointer) return false;
  fail(LEADSCREW_INVALID_ARGUMENT, std::string(what) + " is NULL");
  return true;
}

leadscrew_drive* create(const leadscrew::model::CoreSpec& spec) {
  auto drive = std::make_unique<leadscrew_drive>();
  drive->stepper = std::make_unique<leadscrew::model::DriveStepper>(spec.parameters, spec.options);
  return drive.release();
}

}  // namespace

extern "C" {

const char* leadscrew_version(void) { return "0.1.0"; }

const char* leadscrew_last_error(void) { return last_error.c_str(); }

leadscrew_drive* leadscrew_drive_from_toml(const char* text) {
  if (null_argument(text, "text")) return nullptr;
  leadscrew_drive* drive = nullptr;
  guarded([&] { drive = create(leadscrew::model::read_core_spec(text)); });
  return drive;
}

leadscrew_drive* leadscrew_drive_from_file(const char* path) {
  if (null_argument(path, "path")) return nullptr;
  leadscrew_drive* drive = nullptr;
  guarded([&] { drive = create(leadscrew::model::read_core_spec_file(path)); });
  return drive;
}

void leadscrew_drive_free(leadscrew_drive* drive) { delete drive; }

int leadscrew_set_input(leadscrew_drive* drive, const char* name, double value) {
  if (null_argument(drive, "drive") || null_argument(name, "name"))
    return LEADSCREW_INVALID_ARGUMENT;
  return guarded([&] { drive->stepper->set_input(name, value); });
}

int leadscrew_get_input(leadscrew_drive* drive, const char* name, double* value) {
  if (null_argument(drive, "drive") || null_argument(name, "name") ||
      null_argument(value, "value"))
    return LEADSCREW_INVALID_ARGUMENT;
  return guarded([&] { *value = drive->stepper->input(name); });
}

int leadscrew_advance(leadscrew_drive* drive, double t) {
  if (null_argument(drive, "drive")) return LEADSCREW_INVALID_ARGUMENT;
  return guarded([&] { drive->stepper->advance(t); });
}

double leadscrew_time(const leadscrew_drive* drive) {
  return drive ? drive->stepper->time() : NAN;
}

int leadscrew_get_channel(leadscrew_drive* drive, const char* name, double* value) {
  if (null_argument(drive, "drive") || null_argument(name, "name") ||
      null_argument(value, "value"))
    return LEADSCREW_INVALID_ARGUMENT;
  return guarded([&] { *value = drive->stepper->channel(name); });
}

int leadscrew_channel_count(const leadscrew_drive* drive) {
  return drive ? static_cast<int>(drive->stepper->channel_names().size()) : 0;
}

const char* leadscrew_channel_name(const leadscrew_drive* drive, int i) {
  if (!drive || i < 0) return nullptr;
  const auto& names = drive->stepper->channel_names();
  return static_cast<std::size_t>(i) < names.size() ? names[static_cast<std::size_t>(i)].c_str()
                                                     : nullptr;
}

long leadscrew_event_count(const leadscrew_drive* drive) {
  return drive ? static_cast<long>(drive->stepper->events().size()) : 0;
}

int leadscrew_reset(leadscrew_drive* drive) {
  if (null_argument(drive, "drive")) return LEADSCREW_INVALID_ARGUMENT;
  return guarded([&] { drive->stepper->reset(); });
}

}  // extern "C"
