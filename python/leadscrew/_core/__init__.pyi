"""
leadscrew numerical core (private: use the leadscrew package)
"""
from __future__ import annotations
import collections.abc
import numpy
import numpy.typing
import typing
from . import lcp
from . import integrate
__all__: list[str] = ['DerivedQuantities', 'DriveBatch', 'DriveBatchResult', 'DriveGeometry', 'DriveModel', 'DriveParameters', 'DriveStepper', 'Excitation', 'FrictionBlock', 'JammingError', 'NoEquilibriumError', 'NutOffScrewError', 'SimulationError', 'SimulationResult', 'Thread', 'block_integrators', 'check_drive_options', 'check_element_section', 'check_friction_law', 'check_nut_on_screw', 'cosim_variables', 'derive_drive', 'derived_quantities', 'derived_quantity_problem', 'drive_channel_units', 'drive_integrators', 'efficiency', 'efficiency_array', 'element_sections', 'first_derived_problem', 'friction_laws', 'integrate', 'is_drivable', 'is_drivable_array', 'is_self_locking', 'lcp', 'lower_torque', 'pooled_helper_count', 'preloaded_efficiency_array', 'raise_torque', 'read_core_spec', 'rigid_jamming_margins', 'scene_choices', 'simulate_block', 'simulate_drive', 'smallest_gear_ratio', 'spring_frequency_problem', 'write_core_spec']
class SimulationError(RuntimeError):
    """
    A solver failed during a simulation.
    
    Attributes:
        time: simulated time [s] at which it failed.
        reason: what failed (solver flag name, step size underflow, LCP failure, ...).
    """
class JammingError(SimulationError):
    """
    A self-locking drive jams dynamically (Painleve paradox).
    
    No consistent flank-contact mode exists. Attributes as SimulationError.
    """
class NutOffScrewError(SimulationError):
    """
    The nut ran off the screw: its end reached the screw's end.
    
    The run ends there (beyond it the thread no longer holds the nut); the
    end of a drive's travel, not a solver's failure. Attributes as
    SimulationError (``time``: when the nut's end reached the screw's).
    """
class NoEquilibriumError(ValueError):
    """
    A start in static equilibrium (``initial.state =
    'equilibrium'``) that the loads at t = 0 do not admit: holding them at rest
    takes a flank friction force beyond the friction cone (the loads drive the
    thread). A ValueError; the message gives the loads and the forces.
    """
class Thread:
    """
    Thread geometry of a power screw (immutable).
    
    Args:
        pitch: axial distance between neighbouring thread flanks [m], > 0.
        mean_diameter: mean (pitch) diameter d_m [m], > 0.
        starts: number of thread starts, integer >= 1.
        flank_angle: included thread angle beta [rad] in [0, pi): 0 square,
            29 deg Acme, 30 deg ISO metric trapezoidal.
        hand: "right" or "left"; "left" flips the sign of the screw relation.
    
    Raises:
        ValueError: a parameter is non-finite or out of range.
    """
    def __getstate__(self) -> tuple[float, float, int, float, str]:
        ...
    def __init__(self, pitch: typing.SupportsFloat | typing.SupportsIndex, mean_diameter: typing.SupportsFloat | typing.SupportsIndex, starts: typing.SupportsInt | typing.SupportsIndex = 1, flank_angle: typing.SupportsFloat | typing.SupportsIndex = 0.0, hand: str = 'right') -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def effective_mu(self, mu: typing.SupportsFloat | typing.SupportsIndex) -> float:
        """
        mu' = mu / cos(flank_angle / 2)
        """
    @property
    def flank_angle(self) -> float:
        """
        included flank angle [rad]
        """
    @property
    def hand(self) -> str:
        ...
    @property
    def hand_sign(self) -> float:
        """
        +1 right hand, -1 left hand
        """
    @property
    def lead(self) -> float:
        """
        starts * pitch [m]
        """
    @property
    def lead_angle(self) -> float:
        """
        atan(lead / (pi d_m)) [rad]
        """
    @property
    def lead_per_radian(self) -> float:
        """
        lead / (2 pi) [m/rad]
        """
    @property
    def mean_diameter(self) -> float:
        """
        mean diameter d_m [m]
        """
    @property
    def mean_radius(self) -> float:
        """
        mean radius r_m [m]
        """
    @property
    def pitch(self) -> float:
        """
        pitch [m]
        """
    @property
    def starts(self) -> int:
        """
        number of starts
        """
class Excitation:
    """
    A load as a function of time (C++ core).
    """
    @typing.overload
    def __call__(self, t: typing.SupportsFloat | typing.SupportsIndex) -> float:
        ...
    @typing.overload
    def __call__(self, t: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> numpy.typing.NDArray[numpy.float64]:
        ...
    def __init__(self, kind: str, parameters: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex] = [], times: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex] = [], values: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex] = []) -> None:
        ...
    def describe(self) -> str:
        ...
    @property
    def breakpoints(self) -> list[float]:
        ...
    @property
    def target_rms(self) -> float:
        """
        A random vibration's sqrt(integral of its PSD); 0 otherwise.
        """
class SimulationResult:
    def channel(self, name: str) -> typing.Any:
        """
        One channel as a new array, or None if there is no such channel.
        """
    @property
    def channel_names(self) -> list[str]:
        ...
    @property
    def channels(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def point_count(self) -> int:
        """
        The rows (time points), without converting them.
        """
    @property
    def checks(self) -> dict:
        ...
    @property
    def events(self) -> list:
        ...
    @property
    def friction(self) -> str:
        ...
    @property
    def integrator(self) -> str:
        ...
    @property
    def stats(self) -> dict:
        ...
    @property
    def time(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
class FrictionBlock:
    def __init__(self, mass: typing.SupportsFloat | typing.SupportsIndex, mu: typing.SupportsFloat | typing.SupportsIndex, g: typing.SupportsFloat | typing.SupportsIndex = 9.81, force: typing.Any = 0.0, initial_position: typing.SupportsFloat | typing.SupportsIndex = 0.0, initial_velocity: typing.SupportsFloat | typing.SupportsIndex = 0.0, mu_static: typing.SupportsFloat | typing.SupportsIndex | None = None, stiffness: typing.SupportsFloat | typing.SupportsIndex = 0.0, pull_speed: typing.SupportsFloat | typing.SupportsIndex = 0.0, transverse_velocity: typing.Any = None) -> None:
        ...
    @property
    def force(self) -> Excitation:
        ...
    @property
    def g(self) -> float:
        ...
    @property
    def initial_position(self) -> float:
        ...
    @property
    def initial_velocity(self) -> float:
        ...
    @property
    def mass(self) -> float:
        ...
    @property
    def mu(self) -> float:
        ...
    @property
    def mu_static(self) -> float:
        ...
    @property
    def normal_force(self) -> float:
        ...
    @property
    def pull_speed(self) -> float:
        ...
    @property
    def stiffness(self) -> float:
        ...
    @property
    def transverse_velocity(self) -> Excitation | None:
        ...
class DriveParameters:
    """
    Resolved drive parameters (SI); built by leadscrew.Scene.
    """
    backlash: str
    concept: str
    dc_motor: bool
    drive: str
    friction: str
    initial_state: str
    speed_controlled: bool
    support: str
    thread: Thread
    def __init__(self) -> None:
        ...
    @property
    def axial_force(self) -> Excitation:
        ...
    @axial_force.setter
    def axial_force(self, arg1: typing.Any) -> None:
        ...
    @property
    def base_acceleration(self) -> Excitation:
        ...
    @base_acceleration.setter
    def base_acceleration(self, arg1: typing.Any) -> None:
        ...
    @property
    def base_angular_acceleration(self) -> Excitation:
        ...
    @base_angular_acceleration.setter
    def base_angular_acceleration(self, arg1: typing.Any) -> None:
        ...
    @property
    def clearance(self) -> float:
        ...
    @clearance.setter
    def clearance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def contact_damping(self) -> float:
        ...
    @contact_damping.setter
    def contact_damping(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def contact_exponent(self) -> float:
        ...
    @contact_exponent.setter
    def contact_exponent(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def contact_penetration(self) -> float:
        ...
    @contact_penetration.setter
    def contact_penetration(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def contact_stiffness(self) -> float:
        ...
    @contact_stiffness.setter
    def contact_stiffness(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def damping_ratio(self) -> float:
        ...
    @damping_ratio.setter
    def damping_ratio(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def drive_speed(self) -> Excitation:
        ...
    @drive_speed.setter
    def drive_speed(self, arg1: typing.Any) -> None:
        ...
    @property
    def drive_torque(self) -> Excitation:
        ...
    @drive_torque.setter
    def drive_torque(self, arg1: typing.Any) -> None:
        ...
    @property
    def end_stop_damping(self) -> float:
        """
        the penalty stop's damping c in contact (0: an elastic stop, which gives back all it stores)
        """
    @end_stop_damping.setter
    def end_stop_damping(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def end_stop_lower(self) -> float:
        """
        the lower end stop's face: the load's axial position u_load where it touches, relative to the load's start (u_load at t = 0), < 0 (absent: no lower stop; give lower, upper or both)
        """
    @end_stop_lower.setter
    def end_stop_lower(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def end_stop_restitution(self) -> float:
        """
        Newton restitution coefficient e of an 'exact' stop's impacts, in [0, 1]: the load leaves at e times its approach speed; a rebound below the run's bounce_threshold closes the contact (the load held at the face while the forces press it there)
        """
    @end_stop_restitution.setter
    def end_stop_restitution(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def end_stop_stiffness(self) -> float:
        """
        the penalty stop's stiffness k (required with contact = 'penalty', absent with 'exact'): the static deflection under a held force F is F / k
        """
    @end_stop_stiffness.setter
    def end_stop_stiffness(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def end_stop_upper(self) -> float:
        """
        the upper end stop's face, relative to the load's start, > 0 (absent: no upper stop)
        """
    @end_stop_upper.setter
    def end_stop_upper(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def end_stops(self) -> str:
        """
        the section's choice ('none': no such section)
        """
    @end_stops.setter
    def end_stops(self, arg1: str) -> None:
        ...
    @property
    def friction_values(self) -> list[tuple[str, float]]:
        """
        the law's parameters besides mu and k_v, as (key, value) pairs
        """
    @friction_values.setter
    def friction_values(self, arg0: collections.abc.Sequence[tuple[str, typing.SupportsFloat | typing.SupportsIndex]]) -> None:
        ...
    @property
    def gear(self) -> str:
        """
        the gear stage between the rotor and the driven part: 'none', 'ideal' (gear_ratio rotor turns per turn of the driven part), 'lossy' (gear_efficiency, gear_efficiency_backdrive) or 'worm' (gear_lead_angle, gear_mu, gear_mu_static, gear_flank_angle)
        """
    @gear.setter
    def gear(self, arg1: str) -> None:
        ...
    @property
    def gear_efficiency(self) -> float:
        ...
    @gear_efficiency.setter
    def gear_efficiency(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def gear_efficiency_backdrive(self) -> float:
        ...
    @gear_efficiency_backdrive.setter
    def gear_efficiency_backdrive(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def gear_flank_angle(self) -> float:
        ...
    @gear_flank_angle.setter
    def gear_flank_angle(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def gear_lead_angle(self) -> float:
        ...
    @gear_lead_angle.setter
    def gear_lead_angle(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def gear_mu(self) -> float:
        ...
    @gear_mu.setter
    def gear_mu(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def gear_mu_static(self) -> float:
        ...
    @gear_mu_static.setter
    def gear_mu_static(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def gear_ratio(self) -> float:
        ...
    @gear_ratio.setter
    def gear_ratio(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def k_v(self) -> float:
        ...
    @k_v.setter
    def k_v(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def load_mass(self) -> float:
        ...
    @load_mass.setter
    def load_mass(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def load_spring(self) -> bool:
        """
        True if the model has the section
        """
    @load_spring.setter
    def load_spring(self, arg1: bool) -> None:
        ...
    @property
    def load_spring_damping(self) -> float:
        """
        the damper c in parallel with the spring
        """
    @load_spring_damping.setter
    def load_spring_damping(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def load_spring_preload(self) -> float:
        """
        the spring's preload P at the load's start (u_load = 0), positive along +x: the force on the load is -(P + k u_load) - c u_load', -P at the start (P > 0 balances an axial force of +P, a hatch's weight along +x; any sign)
        """
    @load_spring_preload.setter
    def load_spring_preload(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def load_spring_stiffness(self) -> float:
        """
        the spring's stiffness k: its force changes by k per metre of the load's travel
        """
    @load_spring_stiffness.setter
    def load_spring_stiffness(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def motor_back_emf_constant(self) -> float:
        ...
    @motor_back_emf_constant.setter
    def motor_back_emf_constant(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def motor_current_limit(self) -> float:
        ...
    @motor_current_limit.setter
    def motor_current_limit(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def motor_friction_torque(self) -> float:
        ...
    @motor_friction_torque.setter
    def motor_friction_torque(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def motor_inductance(self) -> float:
        ...
    @motor_inductance.setter
    def motor_inductance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def motor_resistance(self) -> float:
        ...
    @motor_resistance.setter
    def motor_resistance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def motor_torque_constant(self) -> float:
        ...
    @motor_torque_constant.setter
    def motor_torque_constant(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def motor_voltage(self) -> Excitation:
        ...
    @motor_voltage.setter
    def motor_voltage(self, arg1: typing.Any) -> None:
        ...
    @property
    def mu(self) -> float:
        ...
    @mu.setter
    def mu(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def nut_axial_damping(self) -> float:
        ...
    @nut_axial_damping.setter
    def nut_axial_damping(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def nut_axial_stiffness(self) -> float:
        ...
    @nut_axial_stiffness.setter
    def nut_axial_stiffness(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def nut_inertia(self) -> float:
        ...
    @nut_inertia.setter
    def nut_inertia(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def nut_length(self) -> float:
        ...
    @nut_length.setter
    def nut_length(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def nut_mass(self) -> float:
        ...
    @nut_mass.setter
    def nut_mass(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def nut_position(self) -> float:
        ...
    @nut_position.setter
    def nut_position(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def nut_preload(self) -> float:
        ...
    @nut_preload.setter
    def nut_preload(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def nut_preload_stiffness(self) -> float:
        ...
    @nut_preload_stiffness.setter
    def nut_preload_stiffness(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def nut_torsional_damping(self) -> float:
        ...
    @nut_torsional_damping.setter
    def nut_torsional_damping(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def nut_torsional_stiffness(self) -> float:
        ...
    @nut_torsional_stiffness.setter
    def nut_torsional_stiffness(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def play_position(self) -> float:
        ...
    @play_position.setter
    def play_position(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def restitution(self) -> float:
        ...
    @restitution.setter
    def restitution(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def rotor_angle(self) -> float:
        ...
    @rotor_angle.setter
    def rotor_angle(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def rotor_inertia(self) -> float:
        ...
    @rotor_inertia.setter
    def rotor_inertia(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def rotor_speed(self) -> float:
        ...
    @rotor_speed.setter
    def rotor_speed(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def screw_axial_damping(self) -> float:
        ...
    @screw_axial_damping.setter
    def screw_axial_damping(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def screw_axial_rigidity(self) -> float:
        ...
    @screw_axial_rigidity.setter
    def screw_axial_rigidity(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def screw_axial_stiffness(self) -> float:
        ...
    @screw_axial_stiffness.setter
    def screw_axial_stiffness(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def screw_inertia(self) -> float:
        ...
    @screw_inertia.setter
    def screw_inertia(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def screw_length(self) -> float:
        ...
    @screw_length.setter
    def screw_length(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def screw_mass(self) -> float:
        ...
    @screw_mass.setter
    def screw_mass(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def screw_torsional_damping(self) -> float:
        ...
    @screw_torsional_damping.setter
    def screw_torsional_damping(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def screw_torsional_rigidity(self) -> float:
        ...
    @screw_torsional_rigidity.setter
    def screw_torsional_rigidity(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def screw_torsional_stiffness(self) -> float:
        ...
    @screw_torsional_stiffness.setter
    def screw_torsional_stiffness(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def sections(self) -> dict:
        """
        the elements' sections present (element_section.hpp), by name: the values given by key (a scene's section as is; the rest take their defaults)
        """
    @sections.setter
    def sections(self, arg1: dict) -> None:
        ...
class DriveGeometry:
    """
    The scene's geometric and material inputs (SI), named <section>_<key> after its key paths; optional ones None where the scene leaves them out.
    """
    drive: str
    def __init__(self) -> None:
        ...
    @property
    def backlash_axial(self) -> float:
        ...
    @backlash_axial.setter
    def backlash_axial(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def backlash_contact(self) -> str:
        """
        'none' without a backlash section
        """
    @backlash_contact.setter
    def backlash_contact(self, arg1: str) -> None:
        ...
    @property
    def backlash_damping(self) -> float | None:
        ...
    @backlash_damping.setter
    def backlash_damping(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def backlash_exponent(self) -> float:
        ...
    @backlash_exponent.setter
    def backlash_exponent(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def backlash_penetration(self) -> float | None:
        ...
    @backlash_penetration.setter
    def backlash_penetration(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def backlash_stiffness(self) -> float | None:
        ...
    @backlash_stiffness.setter
    def backlash_stiffness(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def friction_mu(self) -> float:
        ...
    @friction_mu.setter
    def friction_mu(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def load_mass(self) -> float:
        ...
    @load_mass.setter
    def load_mass(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def nut_density(self) -> float:
        ...
    @nut_density.setter
    def nut_density(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def nut_length(self) -> float:
        ...
    @nut_length.setter
    def nut_length(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def nut_outer_radius(self) -> float:
        ...
    @nut_outer_radius.setter
    def nut_outer_radius(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def nut_poisson(self) -> float:
        ...
    @nut_poisson.setter
    def nut_poisson(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def nut_youngs_modulus(self) -> float:
        ...
    @nut_youngs_modulus.setter
    def nut_youngs_modulus(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def overrides_nut_axial_stiffness(self) -> float | None:
        ...
    @overrides_nut_axial_stiffness.setter
    def overrides_nut_axial_stiffness(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def overrides_nut_inertia(self) -> float | None:
        ...
    @overrides_nut_inertia.setter
    def overrides_nut_inertia(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def overrides_nut_mass(self) -> float | None:
        ...
    @overrides_nut_mass.setter
    def overrides_nut_mass(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def overrides_nut_torsional_stiffness(self) -> float | None:
        ...
    @overrides_nut_torsional_stiffness.setter
    def overrides_nut_torsional_stiffness(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def overrides_screw_axial_stiffness(self) -> float | None:
        ...
    @overrides_screw_axial_stiffness.setter
    def overrides_screw_axial_stiffness(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def overrides_screw_inertia(self) -> float | None:
        ...
    @overrides_screw_inertia.setter
    def overrides_screw_inertia(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def overrides_screw_mass(self) -> float | None:
        ...
    @overrides_screw_mass.setter
    def overrides_screw_mass(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def overrides_screw_torsional_stiffness(self) -> float | None:
        ...
    @overrides_screw_torsional_stiffness.setter
    def overrides_screw_torsional_stiffness(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def screw_density(self) -> float:
        ...
    @screw_density.setter
    def screw_density(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def screw_length(self) -> float:
        ...
    @screw_length.setter
    def screw_length(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def screw_poisson(self) -> float:
        ...
    @screw_poisson.setter
    def screw_poisson(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def screw_radius(self) -> float:
        ...
    @screw_radius.setter
    def screw_radius(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def screw_youngs_modulus(self) -> float:
        ...
    @screw_youngs_modulus.setter
    def screw_youngs_modulus(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def thread_flank_angle(self) -> float:
        ...
    @thread_flank_angle.setter
    def thread_flank_angle(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def thread_mean_diameter(self) -> float:
        ...
    @thread_mean_diameter.setter
    def thread_mean_diameter(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def thread_pitch(self) -> float:
        ...
    @thread_pitch.setter
    def thread_pitch(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def thread_starts(self) -> int:
        ...
    @thread_starts.setter
    def thread_starts(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
class DerivedQuantities:
    """
    What a DriveGeometry gives the model (derive_drive).
    """
    def apply_to(self, parameters: DriveParameters) -> None:
        """
        Set the masses, inertias, rigidities, stiffnesses and contact values of DriveParameters.
        """
    @property
    def derived(self) -> dict:
        """
        Scene.derived(): masses [kg], inertias [kg*m^2], rigidities [N, N*m^2], stiffnesses [N/m, N*m/rad] and with backlash the contact's values
        """
    @property
    def problem(self) -> typing.Any:
        """
        the key of the first quantity out of its range, or None
        """
    @property
    def quantities(self) -> dict:
        """
        every quantity with a range: tan_lead_angle, effective_mu, then derived's
        """
class DriveModel:
    """
    An assembled drive (immutable).
    """
    def __init__(self, parameters: DriveParameters) -> None:
        ...
    def initial_state(self) -> dict:
        """
        The state at t = 0 that initial.state asks for: dict with q and v (every coordinate and velocity, in coordinate_names' order), play [m], normal_force and friction_force [N] (the flank forces holding the loads: 0 for a relaxed start), iterations (Newton's). NoEquilibriumError where the loads at t = 0 have no static equilibrium.
        """
    @property
    def coordinate_names(self) -> list[str]:
        ...
    @property
    def degrees_of_freedom(self) -> int:
        ...
    @property
    def effective_mu(self) -> float:
        ...
    @property
    def mass(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def parameters(self) -> DriveParameters:
        ...
    @property
    def springs(self) -> list:
        ...
    @property
    def train_friction(self) -> typing.Any:
        """
        The train's friction stages (docs/physics/gear.md, "Friction stages"), None without: dict with motor_friction_torque [N m] (on the rotor), stage (a lossy or worm stage), the stage's efficiencies forward and backward in slip and at breakaway (a worm's from mu and mu_static; 1 without a stage), and self_locking (the backward one at breakaway <= 0).
        """
class DriveStepper:
    """
    A drive advanced piece by piece with its inputs held over each piece (model/drive_stepper.hpp): simulate_drive's event-driven run, its state kept.
    """
    def __init__(self, drive: DriveModel, integrator: str, smooth_integrator: str, rtol: typing.SupportsFloat | typing.SupportsIndex, atol: typing.SupportsFloat | typing.SupportsIndex, max_steps: typing.SupportsInt | typing.SupportsIndex, max_events: typing.SupportsInt | typing.SupportsIndex, max_step: typing.SupportsFloat | typing.SupportsIndex, first_step: typing.SupportsFloat | typing.SupportsIndex, bounce_threshold: typing.SupportsFloat | typing.SupportsIndex, max_order: typing.SupportsInt | typing.SupportsIndex) -> None:
        """
        The drive at t = 0; the options as simulate_drive's (integrator "": the model's default; "moreau" refused). ValueError for a bad option.
        """
    def advance(self, t: typing.SupportsFloat | typing.SupportsIndex) -> None:
        """
        Advance to t [s] >= time with the inputs held. SimulationError (the nut at the screw's end, a solver failure), JammingError; ValueError for t < time.
        """
    def channel(self, name: str) -> float:
        """
        The result channel at time (simulate's names, SI).
        """
    def channels(self) -> list[float]:
        """
        Every channel at time, in channel_names' order.
        """
    def input(self, name: str) -> float:
        """
        The input's value at time (SI).
        """
    def reset(self) -> None:
        """
        Back to t = 0 and the drive's own loads.
        """
    def set_input(self, name: str, value: typing.SupportsFloat | typing.SupportsIndex) -> None:
        """
        Set the input (input_names: "drive_torque" [N*m], "motor_voltage" [V] or "drive_speed" [rad/s], and "axial_force" [N]) to value from time on: held, but a speed ramps to value over the next advance (set before the first advance: the start speed). ValueError for an unknown name or a bad value.
        """
    @property
    def channel_names(self) -> list[str]:
        ...
    @property
    def events(self) -> list:
        """
        The events so far: (time [s], kind) tuples.
        """
    @property
    def input_names(self) -> list[str]:
        ...
    @property
    def stats(self) -> dict:
        """
        Counts so far, as Result.stats (wall_time 0).
        """
    @property
    def time(self) -> float:
        """
        The time reached [s].
        """
class DriveBatchResult:
    """
    What DriveBatch.run gives: samples and failures.
    """
    @property
    def failure_count(self) -> int:
        """
        Cases that failed (0: no need to read failures).
        """
    @property
    def failures(self) -> list[str]:
        """
        Per case: "none", "invalid_argument" (ValueError), "simulation" (SimulationError), "jamming" (JammingError) or "other" (RuntimeError).
        """
    @property
    def messages(self) -> list[str]:
        """
        Per case: the failure's message, "" where none.
        """
    @property
    def samples(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        (cases, channels, sample times) array; NaN in a failed case's rows.
        """
    @property
    def wall_time(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        Per case: the simulation's wall time [s, C++ clock], NaN where it failed.
        """
class DriveBatch:
    """
    Simulations of one drive that differ in a few scalar parameters (immutable).
    """
    def __init__(self, base: DriveParameters, parameters: collections.abc.Sequence[str], channels: collections.abc.Sequence[str], t_end: typing.SupportsFloat | typing.SupportsIndex, integrator: str, smooth_integrator: str, rtol: typing.SupportsFloat | typing.SupportsIndex, atol: typing.SupportsFloat | typing.SupportsIndex, dt: typing.SupportsFloat | typing.SupportsIndex, theta: typing.SupportsFloat | typing.SupportsIndex, t_eval: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], max_steps: typing.SupportsInt | typing.SupportsIndex, max_events: typing.SupportsInt | typing.SupportsIndex, max_step: typing.SupportsFloat | typing.SupportsIndex, first_step: typing.SupportsFloat | typing.SupportsIndex, bounce_threshold: typing.SupportsFloat | typing.SupportsIndex, max_order: typing.SupportsInt | typing.SupportsIndex, check: bool = True, dt_given: bool = True) -> None:
        """
        base: DriveParameters; parameters: the fields each case sets (numeric DriveParameters attributes; drive_torque, drive_speed, axial_force as constants); channels: the result channels to sample at t_eval; the rest as simulate_drive (integrator "": each case's default). ValueError for a bad request.
        """
    def run(self, values: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]", "flags.c_contiguous"], workers: typing.SupportsInt | typing.SupportsIndex = 1) -> DriveBatchResult:
        """
        Simulate one case per row of values (cases, parameters): a DriveBatchResult. A failed case sets its row's failure and message. workers: threads that share the rows, >= 1 (capped at the row count; 1: the calling thread only); the result is the same for every count. ValueError for a wrong width or workers < 1.
        """
    @property
    def channels(self) -> list[str]:
        ...
    @property
    def parameter_count(self) -> int:
        ...
def block_integrators(arg0: str) -> list[str]:
    ...
def check_drive_options(drive: DriveModel, t_end: typing.SupportsFloat | typing.SupportsIndex, integrator: str, smooth_integrator: str, rtol: typing.SupportsFloat | typing.SupportsIndex, atol: typing.SupportsFloat | typing.SupportsIndex, dt: typing.SupportsFloat | typing.SupportsIndex, theta: typing.SupportsFloat | typing.SupportsIndex, t_eval: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], max_steps: typing.SupportsInt | typing.SupportsIndex, max_events: typing.SupportsInt | typing.SupportsIndex, max_step: typing.SupportsFloat | typing.SupportsIndex, first_step: typing.SupportsFloat | typing.SupportsIndex, bounce_threshold: typing.SupportsFloat | typing.SupportsIndex, max_order: typing.SupportsInt | typing.SupportsIndex, check: bool = True, dt_given: bool = True, progress: typing.Any = None) -> None:
    """
    The checks simulate_drive makes of these options before it integrates, without simulating: ValueError naming the option, its value and the valid range.
    """
def check_element_section(name: str, values: dict, context: DriveParameters) -> None:
    """
    The Scene's check of the section `name` (its values checked field by field, with their defaults) across its fields and the sections `context` gives (concept, drive, initial_state, ...): ValueError naming the key path, the value and what is allowed.
    """
def check_friction_law(name: str, values: collections.abc.Sequence[tuple[str, typing.SupportsFloat | typing.SupportsIndex]], prefix: str = 'friction.') -> None:
    """
    Raises ValueError naming '<prefix><key>', the value and the range where the law `name` does not take `values` ((key, value) pairs): an unknown key, a missing required one, a value out of range or below the key it may not fall below (mu_static >= mu).
    """
def check_nut_on_screw(drive: str, nut_position: typing.SupportsFloat | typing.SupportsIndex, nut_length: typing.SupportsFloat | typing.SupportsIndex, screw_length: typing.SupportsFloat | typing.SupportsIndex, explain: bool = True) -> None:
    """
    ValueError naming nut.position unless the whole nut is on the screw: nut_length / 2 < nut_position < screw_length - nut_length / 2 [m].
    """
def cosim_variables(parameters: DriveParameters) -> list:
    """
    The variables the FMU shows of the drive (model/cosim.hpp): dicts with name, reference, kind (input, output, parameter), boolean, unit, start, description.
    """
def derive_drive(geometry: DriveGeometry) -> DerivedQuantities:
    """
    Masses, inertias, rigidities and stiffnesses of a DriveGeometry (thesis eq. 4.17, 4.18, 4.24), overrides applied; never raises (a value out of range: problem).
    """
def derived_quantities() -> list:
    """
    The derived quantities with their texts, units, ranges and overrides, in order.
    """
def derived_quantity_problem(key: str, value: typing.SupportsFloat | typing.SupportsIndex) -> typing.Any:
    """
    None if value is in the quantity's range, else what it must be.
    """
def drive_channel_units() -> dict:
    """
    The SI unit of every result channel a drive may write, by name ("m", "N*m", "J", "" for the flag stick), as the core's elements declare them; not the coordinates' pairs u_<body>, v_<body>, phi_<body>, omega_<body> beyond u_load, v_load, phi_drive and omega_drive.
    """
def drive_integrators(parameters: DriveParameters) -> list[str]:
    ...
def efficiency(thread: Thread, mu: typing.SupportsFloat | typing.SupportsIndex, collar_mu: typing.SupportsFloat | typing.SupportsIndex = 0.0, collar_diameter: typing.SupportsFloat | typing.SupportsIndex = 0.0, backdrive: bool = False) -> float:
    ...
def efficiency_array(thread: Thread, mu: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
    """
    efficiency(thread, m) [1] for each m of the array mu [1] (forward, no collar); ValueError for a negative or non-finite m.
    """
def element_sections() -> list:
    """
    The elements' scene sections (the registry, element_section.hpp): name, doc, presence_attribute and fields (key, unit, doc, kind, presence, default, default_doc, low, high, low_open, high_open, choices, attribute).
    """
def first_derived_problem(values: collections.abc.Sequence[tuple[str, typing.SupportsFloat | typing.SupportsIndex]]) -> typing.Any:
    """
    The key of the first of the (key, value) pairs out of its quantity's range, or None.
    """
def friction_laws() -> list:
    """
    The friction laws of the registry (cpp/src/friction/registry.cpp): per law its name, what it is, its parameters (key, unit, doc, default, default_from, range, at_least) and which integrators fit (time_stepping: Moreau-Jean; ode: the ODE methods).
    """
def is_drivable(thread: Thread, mu: typing.SupportsFloat | typing.SupportsIndex) -> bool:
    ...
def is_drivable_array(thread: Thread, mu: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
    """
    is_drivable(thread, m) for each m of the array mu [1]; ValueError for a negative or non-finite m.
    """
def is_self_locking(thread: Thread, mu: typing.SupportsFloat | typing.SupportsIndex) -> bool:
    ...
def lower_torque(thread: Thread, mu: typing.SupportsFloat | typing.SupportsIndex, load: typing.SupportsFloat | typing.SupportsIndex, collar_mu: typing.SupportsFloat | typing.SupportsIndex = 0.0, collar_diameter: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> float:
    ...
def pooled_helper_count() -> int:
    """
    Helper threads the process's pool has started so far (the batch's workers
    beyond the calling thread; asleep between calls).
    """
def preloaded_efficiency_array(thread: Thread, mu: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], load: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], preload: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
    """
    The steady raising efficiency of the rigid drive with a preloaded nut, F tan a / [(F + P) tan(a + rho') + P tan(rho' - a)] [1], elementwise over mu [1], load F [N] and preload P [N] (docs/physics/preloaded_nut.md); ValueError for a negative or non-finite value.
    """
def raise_torque(thread: Thread, mu: typing.SupportsFloat | typing.SupportsIndex, load: typing.SupportsFloat | typing.SupportsIndex, collar_mu: typing.SupportsFloat | typing.SupportsIndex = 0.0, collar_diameter: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> float:
    ...
def read_core_spec(text: str) -> tuple[DriveParameters, dict]:
    """
    (DriveParameters, options dict) from a core spec's TOML text. ValueError naming the key for a bad spec.
    """
def rigid_jamming_margins(thread: Thread, kappa: typing.SupportsFloat | typing.SupportsIndex, inertia: typing.SupportsFloat | typing.SupportsIndex, mass: typing.SupportsFloat | typing.SupportsIndex) -> dict:
    """
    The rigid drive's two dynamic jamming (Painleve) inequalities for the friction factor kappa (mu' for exact Coulomb): lhs1, rhs1, jams1, lhs2, rhs2, jams2 [kg*m^2], mass1 [kg] and inertia2 [kg*m^2] (inf where never).
    """
def scene_choices() -> list[tuple[str, list[str]]]:
    """
    (key path, names) of the scene's choices the model's enumerations give.
    """
def simulate_block(block: FrictionBlock, t_end: typing.SupportsFloat | typing.SupportsIndex, friction: str, integrator: str, law: collections.abc.Mapping[str, typing.SupportsFloat | typing.SupportsIndex], rtol: typing.SupportsFloat | typing.SupportsIndex, atol: typing.SupportsFloat | typing.SupportsIndex, dt: typing.SupportsFloat | typing.SupportsIndex, theta: typing.SupportsFloat | typing.SupportsIndex, t_eval: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], max_steps: typing.SupportsInt | typing.SupportsIndex, max_events: typing.SupportsInt | typing.SupportsIndex, max_step: typing.SupportsFloat | typing.SupportsIndex, first_step: typing.SupportsFloat | typing.SupportsIndex, max_order: typing.SupportsInt | typing.SupportsIndex, check: bool = True, progress: typing.Any = None) -> SimulationResult:
    ...
def simulate_drive(drive: DriveModel, t_end: typing.SupportsFloat | typing.SupportsIndex, integrator: str, smooth_integrator: str, rtol: typing.SupportsFloat | typing.SupportsIndex, atol: typing.SupportsFloat | typing.SupportsIndex, dt: typing.SupportsFloat | typing.SupportsIndex, theta: typing.SupportsFloat | typing.SupportsIndex, t_eval: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], max_steps: typing.SupportsInt | typing.SupportsIndex, max_events: typing.SupportsInt | typing.SupportsIndex, max_step: typing.SupportsFloat | typing.SupportsIndex, first_step: typing.SupportsFloat | typing.SupportsIndex, bounce_threshold: typing.SupportsFloat | typing.SupportsIndex, max_order: typing.SupportsInt | typing.SupportsIndex, check: bool = True, dt_given: bool = True, progress: typing.Any = None) -> SimulationResult:
    """
    Simulate the drive (leadscrew.simulate's drive path); progress: None or a callable of the simulated time, called about every 0.1 s of wall time (Ctrl-C is checked there too).
    """
def spring_frequency_problem(drive: ...) -> typing.Any:
    """
    None, or what is wrong with a spring of the drive: its part's natural angular frequency sqrt(k / m) not finite or above 1e12 rad/s.
    """
def write_core_spec(parameters: DriveParameters, integrator: str, smooth_integrator: str, rtol: typing.SupportsFloat | typing.SupportsIndex, atol: typing.SupportsFloat | typing.SupportsIndex, max_steps: typing.SupportsInt | typing.SupportsIndex, max_events: typing.SupportsInt | typing.SupportsIndex, max_step: typing.SupportsFloat | typing.SupportsIndex, first_step: typing.SupportsFloat | typing.SupportsIndex, bounce_threshold: typing.SupportsFloat | typing.SupportsIndex, max_order: typing.SupportsInt | typing.SupportsIndex) -> str:
    """
    The core spec (TOML text, model/core_spec.hpp) of the parameters and the run's options. ValueError for a callable load.
    """
smallest_gear_ratio: float = 0.0001
