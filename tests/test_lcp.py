"""LCP solvers (issue 3): every method through one interface, against closed
forms, an exact rational Lemke and brute-force enumeration (tests/helpers)."""

import math

import numpy as np
import pytest

import leadscrew.lcp as lcp
from leadscrew import _core
from helpers import lcp_problems, lcp_reference

METHODS = lcp.METHODS
TOL = 1e-12


def check_claim(result, M, q, tol=TOL):
    """A 'solved' result must verifiably solve the LCP; w must be M z + q."""
    M = np.asarray(M, dtype=float)
    q = np.asarray(q, dtype=float)
    assert np.isfinite(result.z).all() and np.isfinite(result.residual)
    scale = 1.0 + (np.abs(q).max() if q.size else 0.0) + (np.abs(M) @ np.abs(result.z)).max(initial=0.0)
    np.testing.assert_allclose(result.w, M @ result.z + q, rtol=0, atol=1e-13 * scale)
    if result.status == "solved":
        assert result.residual <= tol
        assert result.z.min() >= -tol and result.w.min() >= -tol
        assert abs(result.z @ result.w) <= tol * (1 + np.abs(result.z).sum() + np.abs(result.w).sum())
    assert result.residual == pytest.approx(lcp.complementarity_residual(result.z, result.w), abs=0)


@pytest.mark.parametrize("method", METHODS)
def test_two_by_two_closed_form(method):
    M, q = [[2.0, 1.0], [1.0, 2.0]], [-5.0, -6.0]
    result = lcp.solve(M, q, method=method)
    assert result.status == "solved" and result.solved
    np.testing.assert_allclose(result.z, [4.0 / 3.0, 7.0 / 3.0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(result.w, [0.0, 0.0], atol=1e-12)
    check_claim(result, M, q)


@pytest.mark.parametrize("method", METHODS)
def test_nonnegative_q_gives_zero(method):
    q = [0.0, 1.0, 3.0]
    result = lcp.solve(np.eye(3) + 0.1, q, method=method)
    assert result.status == "solved"
    np.testing.assert_array_equal(result.z, 0.0)
    np.testing.assert_array_equal(result.w, q)


@pytest.mark.parametrize("method", METHODS)
def test_empty_problem(method):
    result = lcp.solve(np.zeros((0, 0)), np.zeros(0), method=method)
    assert result.status == "solved" and result.z.shape == (0,) and result.residual == 0.0


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("n", range(1, 11))
def test_murty_solution(method, n):
    M, q = lcp_reference.murty_problem(n)
    result = lcp.solve(M, q, method=method)
    assert result.status == "solved"
    expected = np.zeros(n)
    expected[-1] = 2.0**n
    np.testing.assert_allclose(result.z, expected, rtol=0, atol=1e-9)
    expected_w = np.array([2.0**i for i in range(1, n)] + [0.0])
    np.testing.assert_allclose(result.w, expected_w, rtol=0, atol=1e-9)
    check_claim(result, M, q)


def test_murty_lemke_pivot_count_is_two_to_the_n():
    """Murty (1978, 1988 ch. 6): Lemke's method with covering vector e needs 2^n
    pivots on this family. Compared pivot by pivot with an exact-arithmetic
    Lemke and with the closed form, and the growth rate fitted."""
    counts = []
    for n in range(1, 11):
        M, q = lcp_reference.murty_problem(n)
        result = lcp.solve(M, q, method="lemke")
        z_exact, pivots_exact, status_exact = lcp_reference.lemke_exact(M, q)
        assert status_exact == "solved"
        assert [float(x) for x in z_exact] == result.z.tolist()
        assert result.iterations == pivots_exact == 2**n
        counts.append(result.iterations)
    slope, _ = np.polyfit(np.arange(1, 11), np.log2(counts), 1)
    assert slope == pytest.approx(1.0, abs=1e-12)  # doubling per added variable


def test_lemke_pivot_budget():
    M, q = lcp_reference.murty_problem(10)
    result = lcp.solve(M, q, method="lemke", max_iter=100)
    assert result.status == "max_iterations" and result.iterations == 100
    check_claim(result, M, q)
    assert result.residual > TOL


@pytest.mark.parametrize("method", METHODS)
def test_many_solutions(method):
    """M = [[1,1],[1,1]], q = (-1,-1): every z >= 0 with z1 + z2 = 1 solves it."""
    M, q = [[1.0, 1.0], [1.0, 1.0]], [-1.0, -1.0]
    result = lcp.solve(M, q, method=method)
    assert result.status == "solved"
    assert result.z.sum() == pytest.approx(1.0, abs=1e-12)
    assert result.residual <= TOL
    check_claim(result, M, q)


@pytest.mark.parametrize("method", METHODS)
def test_no_solution(method):
    """M = [[-1]], q = (-1): w = -z - 1 < 0 for every z >= 0."""
    M, q = [[-1.0]], [-1.0]
    result = lcp.solve(M, q, method=method)
    assert result.status != "solved"
    expected = {"lemke": "ray_termination", "pgs": "singular", "newton_fb": "singular",
                "enumerate": "no_solution"}
    assert result.status == expected[method]
    check_claim(result, M, q)


def test_no_solution_for_infeasible_psd():
    """M = [[0, 1], [-1, 0]] (PSD, skew) with q = (-1, -1): w2 = -z1 - 1 < 0, so
    no solution; Lemke must end on a ray and nobody may claim solved."""
    M, q = [[0.0, 1.0], [-1.0, 0.0]], [-1.0, -1.0]
    assert lcp.solve(M, q, method="lemke").status == "ray_termination"
    assert lcp.solve(M, q, method="enumerate").status in ("no_solution", "singular")
    for method in METHODS:
        result = lcp.solve(M, q, method=method)
        assert result.status != "solved"
        check_claim(result, M, q)


def test_cyclic_degenerate_p_matrix():
    """A P-matrix with cyclic structure and tied q: every ratio test ties."""
    M = np.array([[1.0, 2.0, 0.0], [0.0, 1.0, 2.0], [2.0, 0.0, 1.0]])
    q = -np.ones(3)
    expected = np.full(3, 1.0 / 3.0)  # M e / 3 = e: z = e/3 gives w = 0
    for method in METHODS:
        result = lcp.solve(M, q, method=method)
        if method != "pgs":  # PGS may not converge on this non-H-matrix
            assert result.status == "solved"
        if result.solved:
            np.testing.assert_allclose(result.z, expected, atol=1e-12)
        check_claim(result, M, q)


SIZES = range(1, 17)
SEEDS = range(3)


@pytest.fixture(scope="module")
def family_seeds():
    # Seeds derived from a stable name hash (hash() of str varies by process).
    return {name: sum(map(ord, name)) for name in lcp_problems.FAMILIES}


def make_problem(family, n, seed, family_seeds):
    rng = np.random.default_rng([family_seeds[family], n, seed])
    return lcp_problems.FAMILIES[family](n, rng)


@pytest.mark.parametrize("family", sorted(lcp_problems.FAMILIES))
@pytest.mark.parametrize("n", SIZES)
def test_random_problems(family, n, family_seeds):
    """Every method's 'solved' verifies; Lemke solves all of them (P-matrix or
    feasible PSD); solutions agree with enumerate where unique (P, n <= 12)."""
    for seed in SEEDS:
        M, q = make_problem(family, n, seed, family_seeds)
        results = {m: lcp.solve(M, q, method=m) for m in METHODS if m != "enumerate" or n <= 12}
        for result in results.values():
            check_claim(result, M, q)
        assert results["lemke"].status == "solved", (family, n, seed)
        if family in lcp_problems.P_MATRIX_FAMILIES:
            assert results["newton_fb"].status == "solved", (family, n, seed)
            if n <= 12:
                reference = results["enumerate"]
                assert reference.status == "solved"
                for method, result in results.items():
                    if result.solved:
                        np.testing.assert_allclose(
                            result.z, reference.z, rtol=1e-8, atol=1e-9, err_msg=method
                        )


@pytest.mark.parametrize("family", sorted(lcp_problems.FAMILIES))
@pytest.mark.parametrize("n", range(1, _core.lcp.MAX_FIXED_LEMKE_SIZE + 1))
def test_fixed_size_lemke_matches_generic_path(family, n, family_seeds):
    """For n <= 8 lemke runs on a fixed-size tableau: the same pivots and the
    same bits as the size-generic code path, and enumerate's answer where the
    solution is unique."""
    for seed in range(6):
        M, q = make_problem(family, n, 10 + seed, family_seeds)
        fixed = lcp.solve(M, q, method="lemke")
        z, w, status, iterations, residual = _core.lcp.solve_lemke_generic(
            np.asfortranarray(M), q, TOL, 0
        )
        assert (fixed.status, fixed.iterations) == (status, iterations), (family, n, seed)
        assert fixed.z.tobytes() == np.asarray(z).tobytes()
        assert fixed.w.tobytes() == np.asarray(w).tobytes()
        assert fixed.residual == residual
        assert fixed.status == "solved"
        check_claim(fixed, M, q)
        if family in lcp_problems.P_MATRIX_FAMILIES:
            reference = lcp.solve(M, q, method="enumerate")
            np.testing.assert_allclose(fixed.z, reference.z, rtol=1e-8, atol=1e-9)


@pytest.mark.parametrize("n", range(1, 9))
def test_enumerate_against_brute_force(n, family_seeds):
    """The C++ enumerate finds one of the basic solutions that an independent
    numpy brute force lists (unique for P-matrices)."""
    for family in ("pd_nonsym", "triangular_p", "degenerate_psd"):
        M, q = make_problem(family, n, 0, family_seeds)
        solutions = lcp_reference.all_solutions_by_bases(M, q)
        result = lcp.solve(M, q, method="enumerate")
        assert result.status == "solved"
        assert any(np.allclose(result.z, s, atol=1e-8) for s in solutions)
        if family in lcp_problems.P_MATRIX_FAMILIES:
            assert all(np.allclose(solutions[0], s, atol=1e-8) for s in solutions)


@pytest.mark.parametrize("n", [3, 6, 9])
def test_lemke_matches_exact_arithmetic(n, family_seeds):
    """Same pivot count and solution as the exact rational Lemke (P-matrices:
    the path is unique when no ratio ties)."""
    for family in ("pd_nonsym", "degenerate_p"):
        M, q = make_problem(family, n, 1, family_seeds)
        result = lcp.solve(M, q, method="lemke")
        z_exact, pivots, status = lcp_reference.lemke_exact(M, q)
        assert status == "solved" and result.status == "solved"
        assert result.iterations == pivots
        np.testing.assert_allclose(result.z, [float(x) for x in z_exact], rtol=1e-12, atol=1e-13)


def test_pgs_warm_start_and_relaxation():
    rng = np.random.default_rng(7)
    A = rng.normal(size=(8, 8))
    M = A @ A.T + 8 * np.eye(8)  # well conditioned SPD
    q = rng.normal(size=8) * 5
    cold = lcp.solve(M, q, method="pgs")
    assert cold.status == "solved" and cold.iterations > 1
    warm = lcp.solve(M, q, method="pgs", z0=cold.z)
    assert warm.status == "solved" and warm.iterations <= 1
    sor = lcp.solve(M, q, method="pgs", relaxation=1.3)
    assert sor.status == "solved"
    np.testing.assert_allclose(sor.z, cold.z, atol=1e-10)
    under = lcp.solve(M, q, method="pgs", relaxation=0.5)
    assert under.status == "solved" and under.iterations > cold.iterations
    # A warm start with negative entries is projected onto z >= 0 first.
    assert lcp.solve(M, q, method="pgs", z0=-np.ones(8)).status == "solved"


def test_pgs_budget_and_singular_diagonal():
    M, q = lcp_reference.murty_problem(3)
    assert lcp.solve(M, q, method="pgs", max_iter=1).status == "max_iterations"
    result = lcp.solve([[0.0, 1.0], [1.0, 1.0]], [-1.0, -1.0], method="pgs")
    assert result.status == "singular" and result.iterations == 0


def test_newton_warm_start():
    M = np.array([[4.0, 1.0, 0.0], [1.0, 3.0, 1.0], [0.0, 1.0, 2.0]])
    q = np.array([-1.0, 2.0, -3.0])
    cold = lcp.solve(M, q, method="newton_fb")
    assert cold.status == "solved"
    warm = lcp.solve(M, q, method="newton_fb", z0=cold.z)
    assert warm.status == "solved" and warm.iterations == 0
    np.testing.assert_allclose(warm.z, cold.z, atol=1e-14)


def test_enumerate_budget():
    M, q = lcp_reference.murty_problem(6)  # the solution has index set {6}: mask 32
    assert lcp.solve(M, q, method="enumerate", max_iter=32).status == "max_iterations"
    result = lcp.solve(M, q, method="enumerate", max_iter=33)
    assert result.status == "solved" and result.iterations == 33


def test_looser_tol_is_honoured():
    M = np.array([[2.0, 1.0], [1.0, 2.0]])
    q = np.array([-5.0, -6.0])
    tight = lcp.solve(M, q, method="pgs", tol=1e-14)
    loose = lcp.solve(M, q, method="pgs", tol=1e-4)
    assert loose.solved and loose.residual <= 1e-4
    assert loose.iterations < tight.iterations


def test_default_max_iterations():
    assert lcp.default_max_iterations("lemke", 10) == 1000 + 2**11
    assert lcp.default_max_iterations("pgs", 5) == 10000
    assert lcp.default_max_iterations("newton_fb", 5) == 100
    assert lcp.default_max_iterations("enumerate", 12) == 4096


def test_result_is_a_plain_record():
    result = lcp.solve([[1.0]], [-2.0])
    assert result.method == "lemke" and result.z.tolist() == [2.0] and result.iterations == 2
    assert isinstance(result.residual, float) and result.status in lcp.STATUSES


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(M=[[1.0, 2.0]], q=[1.0]), "M"),
        (dict(M=[1.0, 2.0], q=[1.0, 2.0]), "M"),
        (dict(M=np.eye(2), q=[1.0]), "q"),
        (dict(M=np.eye(2), q=[[1.0, 2.0]]), "q"),
        (dict(M=[[1.0, math.nan], [0.0, 1.0]], q=[1.0, 1.0]), r"M\[0, 1\]"),
        (dict(M=np.eye(2), q=[1.0, math.inf]), r"q\[1\]"),
        (dict(M=np.eye(2), q=[-1.0, 1.0], z0=[1.0]), "z0"),
        (dict(M=np.eye(2), q=[-1.0, 1.0], z0=[1.0, math.nan], method="pgs"), r"z0\[1\]"),
        (dict(M=np.eye(2), q=[-1.0, 1.0], tol=0.0), "tol"),
        (dict(M=np.eye(2), q=[-1.0, 1.0], tol=math.nan), "tol"),
        (dict(M=np.eye(2), q=[-1.0, 1.0], max_iter=0), "max_iter"),
        (dict(M=np.eye(2), q=[-1.0, 1.0], max_iter=2.5), "max_iter"),
        (dict(M=np.eye(2), q=[-1.0, 1.0], relaxation=2.0), "relaxation"),
        (dict(M=np.eye(2), q=[-1.0, 1.0], relaxation=0.0), "relaxation"),
        (dict(M=np.eye(2), q=[-1.0, 1.0], method="simplex"), "method"),
        (dict(M=np.eye(13), q=-np.ones(13), method="enumerate"), "M"),
    ],
)
def test_bad_input_names_the_argument(kwargs, name):
    with pytest.raises(ValueError, match="^" + name):
        lcp.solve(**kwargs)


@pytest.mark.parametrize("method", METHODS)
def test_bad_input_every_method(method):
    with pytest.raises(ValueError, match=r"^M\[1, 0\] = nan"):
        lcp.solve([[1.0, 0.0], [math.nan, 1.0]], [1.0, 1.0], method=method)


def test_residual_function():
    assert lcp.complementarity_residual([1.0, 0.0], [0.0, 2.0]) == 0.0
    assert lcp.complementarity_residual([1.0, 0.5], [0.0, 2.0]) == 0.5
    assert lcp.complementarity_residual([-1.0, 0.0], [0.0, 2.0]) == 2.0  # |min| + negativity
    with pytest.raises(ValueError, match="^w"):
        lcp.complementarity_residual([1.0], [1.0, 2.0])
    # A non-finite pair is no solution (min and max alone would drop a NaN).
    assert lcp.complementarity_residual([math.nan, 0.0], [0.0, 2.0]) == math.inf
    assert lcp.complementarity_residual([0.0, 1.0], [math.inf, 0.0]) == math.inf
