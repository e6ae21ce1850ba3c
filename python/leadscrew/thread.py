"""Thread geometry and the closed-form mechanics of a power screw.

All quantities are SI: lengths in m, angles in rad, forces in N, torques in N*m.
The effective friction coefficient of a thread with included flank angle beta is
mu' = mu / cos(beta / 2). The bounds tan(alpha) < mu' < cot(alpha) of static
position holding and drivability are eq. (3.5), (3.7), (3.8) of the thesis.
"""

from __future__ import annotations

from . import _core
from ._core import Thread

__all__ = [
    "Thread",
    "raise_torque",
    "lower_torque",
    "efficiency",
    "is_self_locking",
    "is_drivable",
]


def raise_torque(
    thread: Thread,
    mu: float,
    load: float,
    collar_mu: float = 0.0,
    collar_diameter: float = 0.0,
) -> float:
    """Torque to move an axial load against its direction (to "raise" it).

    T = F r_m (tan(alpha) + mu') / (1 - mu' tan(alpha)) + F mu_c d_c / 2.

    Args:
        thread: the thread.
        mu: flank friction coefficient, >= 0.
        load: axial load magnitude F [N], >= 0.
        collar_mu: thrust-collar friction coefficient, >= 0.
        collar_diameter: mean collar diameter d_c [m], >= 0.

    Returns:
        The drive torque [N*m]; ``inf`` where no torque can move the load
        (mu' >= cot(alpha), see :func:`is_drivable`).

    Raises:
        ValueError: a value is negative or not finite.
    """
    return _core.raise_torque(thread, mu, load, collar_mu, collar_diameter)


def lower_torque(
    thread: Thread,
    mu: float,
    load: float,
    collar_mu: float = 0.0,
    collar_diameter: float = 0.0,
) -> float:
    """Torque to move an axial load with its direction (to "lower" it).

    T = F r_m (mu' - tan(alpha)) / (1 + mu' tan(alpha)) + F mu_c d_c / 2.

    Args:
        thread: the thread.
        mu: flank friction coefficient, >= 0.
        load: axial load magnitude F [N], >= 0.
        collar_mu: thrust-collar friction coefficient, >= 0.
        collar_diameter: mean collar diameter d_c [m], >= 0.

    Returns:
        The drive torque [N*m]: negative where the load back-drives the thread
        (it has to be held back), positive where the thread is self-locking.

    Raises:
        ValueError: a value is negative or not finite.
    """
    return _core.lower_torque(thread, mu, load, collar_mu, collar_diameter)


def efficiency(
    thread: Thread,
    mu: float,
    collar_mu: float = 0.0,
    collar_diameter: float = 0.0,
    backdrive: bool = False,
) -> float:
    """Efficiency of the thread (and collar), independent of the load.

    Forward: eta = F lead / (2 pi T_raise) = tan(alpha) / tan(alpha + rho') for
    a thread without collar friction. Back-driving (the axial load turns the
    screw): eta' = -2 pi T_lower / (F lead) = tan(alpha - rho') / tan(alpha).

    Args:
        thread: the thread.
        mu: flank friction coefficient, >= 0.
        collar_mu: thrust-collar friction coefficient, >= 0.
        collar_diameter: mean collar diameter [m], >= 0.
        backdrive: False for the forward efficiency, True for back-driving.

    Returns:
        The efficiency [1]. Forward: in (0, 1], 1 at mu = 0, 0 where the thread
        cannot be driven. Back-driving: <= 0 where the thread is self-locking.

    Raises:
        ValueError: a value is negative or not finite.
    """
    return _core.efficiency(thread, mu, collar_mu, collar_diameter, backdrive)


def is_self_locking(thread: Thread, mu: float) -> bool:
    """Static position holding under a pure axial load: tan(alpha) < mu' (eq. 3.5).

    Args:
        thread: the thread.
        mu: flank friction coefficient, >= 0.

    Returns:
        True if a pure axial load cannot turn the thread.

    Raises:
        ValueError: mu is negative or not finite.
    """
    return _core.is_self_locking(thread, mu)


def is_drivable(thread: Thread, mu: float) -> bool:
    """A pure drive torque can turn the thread: mu' < cot(alpha) (eq. 3.7).

    Args:
        thread: the thread.
        mu: flank friction coefficient, >= 0.

    Returns:
        True if a torque alone can drive the thread.

    Raises:
        ValueError: mu is negative or not finite.
    """
    return _core.is_drivable(thread, mu)
