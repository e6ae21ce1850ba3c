"""leadscrew: multibody simulation of lead-screw drives.

SI units throughout (m, kg, s, N, N*m, Pa, rad).
"""

from . import integrate, lcp, scene, scenes, studies, units
from .errors import JammingError, NoEquilibriumError, SimulationError, StudyWarning
from .excitation import Constant, Excitation, Sine, Table
from .models import FrictionBlock
from .scene import Scene
from .simulation import Event, Result, simulate
from .thread import (
    Thread,
    efficiency,
    is_drivable,
    is_self_locking,
    lower_torque,
    raise_torque,
)

__version__ = "0.1.0"

__all__ = [
    "Thread",
    "raise_torque",
    "lower_torque",
    "efficiency",
    "is_self_locking",
    "is_drivable",
    "Excitation",
    "Constant",
    "Sine",
    "Table",
    "FrictionBlock",
    "Scene",
    "simulate",
    "Result",
    "Event",
    "SimulationError",
    "JammingError",
    "NoEquilibriumError",
    "StudyWarning",
    "integrate",
    "lcp",
    "scene",
    "scenes",
    "studies",
    "units",
    "__version__",
]
