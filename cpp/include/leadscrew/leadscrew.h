/*
 * leadscrew.h: the C API of leadscrew, a simulator of lead-screw drives
 * (exact Coulomb friction, thread backlash, flexible screw and nut).
 *
 * A drive is created from a *core spec*: a TOML text (or file) that holds the
 * drive as the core runs it, every value an SI number and every default and
 * derived value explicit. The Python package writes it from any scene file:
 *
 *     leadscrew scene resolve my_drive.toml -o core.toml
 *     python3 -c "import leadscrew as ls; ls.scenes.load('default').to_core_toml('core.toml')"
 *
 * and the format is described in the file itself (sections [drive],
 * [thread], [friction], [parameters], [loads.*], [options]; a key left out
 * takes the core's default, an unknown key is an error).
 *
 * The drive is advanced in pieces: set its inputs, advance to a time, read its
 * result channels there. Inputs are held constant over each advance (they
 * start as the spec's loads, any constant, sine or table, until set). Events
 * (stick/slip, flank impacts, the nut at the screw's end) are located exactly
 * inside each piece by the event-driven scheme (or the spec's integrator), and
 * the complete state is kept between calls: N calls cost about one run.
 *
 * Errors: every function that can fail returns a status (LEADSCREW_OK = 0 or
 * one of the codes below; a create function returns NULL) and never lets an
 * exception or a signal out. leadscrew_last_error() then gives the reason as
 * text, naming the key, input, channel or event. After a failure of
 * leadscrew_advance (the nut reached the screw's end, a solver failed, the
 * drive jammed) the drive stays at the time of the failure and refuses to
 * advance until leadscrew_reset.
 *
 * Units: SI (m, kg, s, N, N*m, rad, rad/s, J). Link with -lleadscrew (the
 * library and this header ship with the Python package:
 * leadscrew.get_library(), leadscrew.get_include()). A drive handle is not
 * thread-safe; different handles may be used from different threads.
 */
#ifndef LEADSCREW_LEADSCREW_H
#define LEADSCREW_LEADSCREW_H

#if defined(_WIN32)
#define LEADSCREW_API __declspec(dllexport)
#elif defined(__GNUC__)
#define LEADSCREW_API __attribute__((visibility("default")))
#else
#define LEADSCREW_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Status codes. */
#define LEADSCREW_OK 0
#define LEADSCREW_INVALID_ARGUMENT 1 /* bad spec, name, value or time (ValueError in Python) */
#define LEADSCREW_SIMULATION_ERROR 2 /* the run failed: the screw's end, a solver, max_steps */
#define LEADSCREW_JAMMING 3          /* the drive jams dynamically (Painleve paradox) */
#define LEADSCREW_ERROR 4            /* anything else (out of memory, ...) */

/* An opaque drive. */
typedef struct leadscrew_drive leadscrew_drive;

/* The library's version, e.g. "0.1.0". */
LEADSCREW_API const char* leadscrew_version(void);

/* The text of the last error of this thread ("" if none yet). Valid until the
   thread's next call into the library. */
LEADSCREW_API const char* leadscrew_last_error(void);

/* A drive at t = 0 from a core spec's TOML text, or from a core spec file.
   NULL on error (leadscrew_last_error says why: the TOML, a key, a value out
   of its range). */
LEADSCREW_API leadscrew_drive* leadscrew_drive_from_toml(const char* text);
LEADSCREW_API leadscrew_drive* leadscrew_drive_from_file(const char* path);

/* Frees the drive (NULL is allowed). */
LEADSCREW_API void leadscrew_drive_free(leadscrew_drive* drive);

/* Sets an input to `value` from the current time on: the drive's,
   "drive_torque" [N*m] (a torque-controlled drive), "motor_voltage" [V] (a
   DC motor) or "drive_speed" [rad/s] (a speed-controlled drive), and
   "axial_force" [N]. A torque, a voltage and the force are held; a
   prescribed speed is not stepped (that is an infinite acceleration): it
   ramps linearly from the current speed to `value` over the next
   leadscrew_advance, then holds. An unknown name (the message lists the
   drive's) and a non-finite value are LEADSCREW_INVALID_ARGUMENT. */
LEADSCREW_API int leadscrew_set_input(leadscrew_drive* drive, const char* name, double value);
/* The input's value at the current time. */
LEADSCREW_API int leadscrew_get_input(leadscrew_drive* drive, const char* name, double* value);

/* Advances to time t [s] >= the current time with the inputs held. */
LEADSCREW_API int leadscrew_advance(leadscrew_drive* drive, double t);

/* The current time [s] (NAN for a NULL drive). */
LEADSCREW_API double leadscrew_time(const leadscrew_drive* drive);

/* A result channel at the current time, by name: the channels of Python's
   leadscrew.simulate ("u_load" [m], "v_load" [m/s], "phi_drive" [rad],
   "omega_drive" [rad/s], "drive_torque" [N*m], "axial_force" [N],
   "normal_force" [N], "friction_force" [N], "slip_velocity" [m/s], "stick"
   (1 or 0), "friction_loss" [J], "energy_residual" [J], ...). */
LEADSCREW_API int leadscrew_get_channel(leadscrew_drive* drive, const char* name, double* value);
/* The number of channels and the name of channel i (NULL out of range). */
LEADSCREW_API int leadscrew_channel_count(const leadscrew_drive* drive);
LEADSCREW_API const char* leadscrew_channel_name(const leadscrew_drive* drive, int i);

/* The number of events so far (stick/slip changes, impacts). */
LEADSCREW_API long leadscrew_event_count(const leadscrew_drive* drive);

/* Back to t = 0: the initial state, the spec's loads, no failure. */
LEADSCREW_API int leadscrew_reset(leadscrew_drive* drive);

#ifdef __cplusplus
}
#endif

#endif /* LEADSCREW_LEADSCREW_H */
