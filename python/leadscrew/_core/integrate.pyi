"""
ODE integrators of the core
"""
from __future__ import annotations
import collections.abc
import numpy
import numpy.typing
import typing
__all__: list[str] = ['Integrator', 'OdeSystem', 'PythonOdeSystem', 'integrator_names', 'make_integrator']
class OdeSystem:
    """
    An ODE y' = f(t, y) with root functions g(t, y).
    """
    @property
    def quadrature_count(self) -> int:
        ...
    @property
    def root_count(self) -> int:
        ...
    @property
    def size(self) -> int:
        ...
class PythonOdeSystem(OdeSystem):
    """
    ODE system from Python callables.
    
    Args:
        fun: f(t, y) -> array of `size` values.
        size: number of states, >= 1.
        events: g(t, y) -> array of `root_count` values, or None.
        root_count: number of root functions, >= 0.
        quadrature_count: number of trailing states fun does not depend on
            (integrals of the others); CVODE leaves them out of its Newton
            matrix. 0 <= quadrature_count < size.
    """
    def __init__(self, fun: collections.abc.Callable, size: typing.SupportsInt | typing.SupportsIndex, events: typing.Any = None, root_count: typing.SupportsInt | typing.SupportsIndex = 0, quadrature_count: typing.SupportsInt | typing.SupportsIndex = 0) -> None:
        ...
class Integrator:
    """
    An ODE integrator (make it with make_integrator).
    
    initialize(system, t0, y0) allocates; reinitialize(t0, y0) restarts without
    allocating; advance(t_out, one_step=False) integrates towards t_out, never
    past it, stopping at the first root of the system's root functions, and
    returns (t, root_found, y).
    """
    def advance(self, t_out: typing.SupportsFloat | typing.SupportsIndex, one_step: bool = False) -> tuple[float, bool, typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]]:
        ...
    def advance_to_output(self, t_out: typing.SupportsFloat | typing.SupportsIndex, t_stop: typing.SupportsFloat | typing.SupportsIndex) -> tuple[float, bool, typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]]:
        """
        Like advance, but steps may pass t_out (never t_stop >= t_out) when the method interpolates output (see interpolates_output); returns (t, root_found, y) with y at t_out from the interpolant.
        """
    def dense_output(self, t: typing.SupportsFloat | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        The state at t within the last internal step (dense output).
        """
    def initialize(self, system: typing.Any, t0: typing.SupportsFloat | typing.SupportsIndex, y0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> None:
        ...
    def reinitialize(self, t0: typing.SupportsFloat | typing.SupportsIndex, y0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> None:
        ...
    @property
    def interpolates_output(self) -> bool:
        """
        True if output times need not end steps (the interpolant has the steps' order).
        """
    @property
    def name(self) -> str:
        ...
    @property
    def root_info(self) -> list[int]:
        """
        per root function: +1 rising, -1 falling, 0 not triggered
        """
    @property
    def stats(self) -> dict:
        ...
def integrator_names() -> list[str]:
    """
    Names of the integrators.
    """
def make_integrator(method: str, rtol: typing.SupportsFloat | typing.SupportsIndex = 1e-08, atol: typing.SupportsFloat | typing.SupportsIndex = 1e-10, max_step: typing.SupportsFloat | typing.SupportsIndex = 0.0, first_step: typing.SupportsFloat | typing.SupportsIndex = 0.0, max_steps: typing.SupportsInt | typing.SupportsIndex = 1000000, max_order: typing.SupportsInt | typing.SupportsIndex = 0, fixed_step: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> Integrator:
    """
    Make an integrator by name (see integrator_names). Raises ValueError for an unknown name or an invalid option.
    """
