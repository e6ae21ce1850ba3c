"""
LCP solvers (private: use leadscrew.lcp)
"""
from __future__ import annotations
import numpy
import numpy.typing
import typing
__all__: list[str] = ['MAX_ENUMERATE_SIZE', 'MAX_FIXED_LEMKE_SIZE', 'complementarity_residual', 'contact_lcp', 'contact_state', 'default_max_iterations', 'friction_lcp', 'friction_state', 'single_friction_lcp', 'single_friction_state', 'solve', 'solve_lemke_generic']
def complementarity_residual(z: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], w: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]) -> float:
    """
    max_i |min(z_i, w_i)| + max(0, -min z) + max(0, -min w)
    """
def contact_lcp(delassus: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]", "flags.f_contiguous"], free_acceleration: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], mu: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]) -> tuple:
    """
    The 3n-LCP of n planar contacts with friction; returns (A, b).
    """
def contact_state(z: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], w: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], mu: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]) -> tuple:
    """
    (lambda_N, lambda_T, g_N'', g_T'') from a solution of contact_lcp.
    """
def default_max_iterations(method: str, n: typing.SupportsInt | typing.SupportsIndex) -> int:
    """
    The iteration budget that max_iter 0 stands for.
    """
def friction_lcp(delassus: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]", "flags.f_contiguous"], free_acceleration: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], mu: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], normal_force: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]) -> tuple:
    """
    The 2n-LCP of n coupled friction contacts; returns (A, b).
    """
def friction_state(z: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], w: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], mu: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], normal_force: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]) -> tuple:
    """
    (lambda_T, g_T'') from a solution of friction_lcp.
    """
def single_friction_lcp(delassus: typing.SupportsFloat | typing.SupportsIndex, free_acceleration: typing.SupportsFloat | typing.SupportsIndex, mu: typing.SupportsFloat | typing.SupportsIndex, normal_force: typing.SupportsFloat | typing.SupportsIndex) -> tuple:
    """
    Thesis eq. (3.10)-(3.14) for one contact; returns (A, b).
    """
def single_friction_state(z: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], w: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], mu: typing.SupportsFloat | typing.SupportsIndex, normal_force: typing.SupportsFloat | typing.SupportsIndex) -> tuple:
    """
    (lambda_T, g_T'') from a solution of single_friction_lcp.
    """
def solve(M: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]", "flags.f_contiguous"], q: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], method: str, tol: typing.SupportsFloat | typing.SupportsIndex, max_iter: typing.SupportsInt | typing.SupportsIndex, z0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"] | None, relaxation: typing.SupportsFloat | typing.SupportsIndex) -> tuple:
    """
    Solve the LCP (M, q); returns (z, w, status, iterations, residual). max_iter 0 is the method's default; z0 None starts cold.
    """
def solve_lemke_generic(M: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]", "flags.f_contiguous"], q: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], tol: typing.SupportsFloat | typing.SupportsIndex, max_iter: typing.SupportsInt | typing.SupportsIndex) -> tuple:
    """
    Lemke on its size-generic code path, also for n <= 8 (where solve runs the fixed-size one), without the NaN/inf scan; for tests. Returns (z, w, status, iterations, residual).
    """
MAX_ENUMERATE_SIZE: int = 12
MAX_FIXED_LEMKE_SIZE: int = 8
