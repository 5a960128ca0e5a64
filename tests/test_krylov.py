"""The collocation's GMRES (`rotbeam.solve.krylov.gmres`) against scipy's (an independent
implementation of the same algorithm and tolerance control) and against dense solves."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.sparse.linalg import LinearOperator
from scipy.sparse.linalg import gmres as scipy_gmres

from rotbeam.solve.krylov import gmres


def system(n: int, seed: int, spread: float = 1.0):
    """A nonsymmetric system with a Jacobi preconditioner: A, its diagonal, b."""
    rng = np.random.default_rng(seed)
    d = 1.0 + spread * rng.random(n) * 10.0
    A = np.diag(d) + rng.standard_normal((n, n)) * (0.6 / np.sqrt(n))
    A[np.arange(n - 1), np.arange(1, n)] += 2.0  # non-normal: a strong superdiagonal
    return A, np.diag(A).copy(), rng.standard_normal(n)


def scipy_iterations(A, diag, b, rtol, restart, maxiter):
    count = [0]
    pre = LinearOperator(A.shape, lambda r: r / diag)
    x, info = scipy_gmres(A, b, rtol=rtol, atol=0.0, restart=restart, maxiter=maxiter, M=pre,
                          callback=lambda _: count.__setitem__(0, count[0] + 1),
                          callback_type="pr_norm")  # fmt: skip
    return x, info, count[0]


@pytest.mark.parametrize("restart", [8, 30, 200], ids=["many restarts", "some", "none"])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_gmres_takes_scipys_iterations_to_the_same_answer(restart, seed):
    """Same Krylov spaces, same tolerance control: the same iteration count and iterates
    equal to rounding (the orthogonalisations differ: classical twice against modified)."""
    A, diag, b = system(150, seed)
    ours = gmres(lambda v: A @ v, lambda r: r / diag, b, rtol=1e-9, restart=restart, maxiter=40)
    x, info, count = scipy_iterations(A, diag, b, 1e-9, restart, 40)
    assert info == 0 and ours.converged
    assert ours.iterations == count
    np.testing.assert_allclose(ours.x, x, rtol=0, atol=1e-9 * np.abs(x).max())


def test_gmres_meets_its_tolerance_on_the_true_residual():
    """The residual it reports is the true one, within rtol; the answer is the dense solve's
    to the condition number times rtol."""
    A, diag, b = system(200, 3)
    solved = gmres(lambda v: A @ v, lambda r: r / diag, b, rtol=1e-6, restart=20, maxiter=50)
    measured = np.linalg.norm(b - A @ solved.x) / np.linalg.norm(b)
    assert solved.converged and measured <= 1e-6
    assert solved.residual == pytest.approx(measured, rel=1e-12)
    exact = np.linalg.solve(A, b)
    assert np.abs(solved.x - exact).max() <= 1e-6 * np.linalg.cond(A) * np.abs(exact).max()


def test_an_exact_preconditioner_solves_in_one_step():
    """P = A: the Krylov space of P^-1 A = I is invariant after one step (a breakdown that is
    the exact solution)."""
    A, _, b = system(60, 4)
    solved = gmres(lambda v: A @ v, lambda r: np.linalg.solve(A, r), b, rtol=1e-10)
    assert solved.converged and solved.iterations == 1
    np.testing.assert_allclose(A @ solved.x, b, rtol=0, atol=1e-12 * np.abs(b).max())


def test_too_few_iterations_say_so():
    """Out of restarts: not converged, the residual above rtol, the iterate finite."""
    A, diag, b = system(300, 5, spread=3.0)
    solved = gmres(lambda v: A @ v, lambda r: r / diag, b, rtol=1e-12, restart=3, maxiter=2)
    assert not solved.converged and solved.iterations == 6
    assert 1e-12 < solved.residual < 1.0 and np.all(np.isfinite(solved.x))


def test_a_singular_system_says_it_did_not_converge():
    """b outside the range of a singular A: not converged, no NaN, and the residual it reports
    is the true one (the iterate itself is rounding noise along the null space, as scipy's)."""
    A = np.diag([1.0, 2.0, 0.0, 3.0])
    b = np.ones(4)
    solved = gmres(lambda v: A @ v, lambda r: r, b, rtol=1e-8, restart=4, maxiter=3)
    assert not solved.converged and np.all(np.isfinite(solved.x))
    assert solved.residual == pytest.approx(np.linalg.norm(b - A @ solved.x) / 2.0, rel=1e-9)


def test_a_zero_right_hand_side_is_solved_by_zero():
    solved = gmres(lambda v: v, lambda r: r, np.zeros(5))
    assert solved.converged and solved.iterations == 0 and not solved.x.any()


def test_an_ill_conditioned_basis_stays_orthogonal():
    """Condition 1e6, one cycle as long as the system: a basis that loses orthogonality (one
    classical Gram-Schmidt pass: 171 steps, measured) needs more steps than scipy's modified
    Gram-Schmidt; ours takes as many (100)."""
    rng = np.random.default_rng(1)
    n = 100
    Q, _ = np.linalg.qr(rng.standard_normal((n, n)))
    A = Q @ np.diag(10.0 ** np.linspace(0.0, 6.0, n)) @ Q.T
    b = rng.standard_normal(n)
    ours = gmres(lambda v: A @ v, lambda r: r, b, rtol=1e-10, restart=n, maxiter=3)
    _, info, count = scipy_iterations(A, np.ones(n), b, 1e-10, n, 3)
    assert info == 0 and ours.converged
    assert ours.iterations <= count


def test_an_invariant_krylov_space_ends_the_solve():
    """A = diag(1, 1, 0), b = (1, 1, 1): the Krylov space is invariant after two steps and b
    is not in A's range, so restarting cannot help: two steps, not converged."""
    A = np.diag([1.0, 1.0, 0.0])
    solved = gmres(lambda v: A @ v, lambda r: r, np.ones(3), rtol=1e-8, restart=3, maxiter=3)
    assert not solved.converged and solved.iterations == 2
