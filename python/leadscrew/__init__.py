"""leadscrew: multibody simulation of lead-screw drives.

SI units throughout (m, kg, s, N, N*m, Pa, rad).
"""

from . import core_spec, fmi, integrate, lcp, plotting, profiles, scene, scenes, studies, units
from .errors import (JammingError, NoEquilibriumError, NutOffScrewError, SimulationError,
                     StudyWarning, WriteError)
from .excitation import Constant, Excitation, Sine, Table
from .excitation_sampled import Measured, RandomVibration
from .models import FrictionBlock
from .scene import Scene
from .scene_schema import describe_schema, friction_laws
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


def get_include() -> str:
    """The directory of the C API's header ``leadscrew.h`` (for ``cc -I``).

    Returns:
        The absolute path of the directory inside the installed package.

    Raises:
        FileNotFoundError: the package was installed without the C API.
    """
    return _shipped("include", "leadscrew.h")


def get_library() -> str:
    """The path of the shared library ``libleadscrew.so`` (the C API,
    ``leadscrew.h``): link a C program with it, e.g.
    ``cc prog.c -I$(get_include()) $(get_library()) -Wl,-rpath,<its directory>``.

    Returns:
        The absolute path of the library inside the installed package.

    Raises:
        FileNotFoundError: the package was installed without the C API.
    """
    return _shipped("lib", "libleadscrew.so", directory=False)


def _shipped(folder: str, name: str, directory: bool = True) -> str:
    import os

    where = os.path.join(os.path.dirname(os.path.abspath(__file__)), folder)
    path = os.path.join(where, name)
    if not os.path.isfile(path):
        raise FileNotFoundError(f"{path} does not exist: this installation of leadscrew has "
                                f"no C API (build and install the package with CMake's "
                                f"LEADSCREW_BUILD_CAPI=ON, the default)")
    return where if directory else path


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
    "RandomVibration",
    "Measured",
    "FrictionBlock",
    "Scene",
    "describe_schema",
    "friction_laws",
    "simulate",
    "Result",
    "Event",
    "SimulationError",
    "JammingError",
    "NutOffScrewError",
    "NoEquilibriumError",
    "StudyWarning",
    "WriteError",
    "core_spec",
    "fmi",
    "integrate",
    "lcp",
    "plotting",
    "profiles",
    "scene",
    "scenes",
    "studies",
    "units",
    "get_include",
    "get_library",
    "__version__",
]
