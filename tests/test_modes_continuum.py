"""Flapwise frequencies with a hub (r_o > 0): the discrete model against the continuum
eigenproblem solved independently with scipy's solve_bvp (collocation, adaptive mesh).

No published hub > 0 table could be read in this project (see test_modes_published.py), so the
continuum problem is the reference; it is itself checked against the published hub-0 table.

    w'''' - (n0 w')' = W^2 w,  n0 = lam^2 [r_o (1 - s) + (1 - s^2)/2],
    w(0) = w'(0) = 0,  w''(1) = 0,  w'''(1) = 0   (n0(1) = 0),  normalised by w(1) = 1.
"""

import numpy as np
import pytest
from scipy.integrate import solve_bvp

from rotbeam.model.modes import dimensionless_frequencies


def continuum_first_frequency(lam: float, hub: float) -> float:
    def n0(s):
        return lam**2 * (hub * (1 - s) + (1 - s**2) / 2)

    def dn0(s):
        return lam**2 * (-hub - s)

    def f(s, y, p):
        w2 = p[0]
        # y = (w, w', w'', w''');  w'''' = W^2 w + n0 w'' + n0' w'
        return np.vstack([y[1], y[2], y[3], w2 * y[0] + n0(s) * y[2] + dn0(s) * y[1]])

    def bc(ya, yb, p):
        return np.array([ya[0], ya[1], yb[2], yb[3], yb[0] - 1.0])

    s = np.linspace(0, 1, 50)
    guess = np.vstack([s**2, 2 * s, 2 + 0 * s, 0 * s])
    w2_0 = 1.8751040687**4 + 1.2 * lam**2 * (1 + 2 * hub)
    sol = solve_bvp(f, bc, s, guess, p=[w2_0], tol=1e-10, max_nodes=200000)
    assert sol.success, sol.message
    return float(np.sqrt(sol.p[0]))


def extrapolated(lam, hub):
    w80, w160 = (dimensionless_frequencies(lam, hub, 1, N, softening=False)[0] for N in (80, 160))
    return w160 + (w160 - w80) / 3


def test_continuum_reference_matches_published_hub0():
    # Wright et al. (1982) via Bir (2009), Table 3a: lam = 4 -> 5.585, lam = 10 -> 11.202
    assert continuum_first_frequency(4.0, 0.0) == pytest.approx(5.585, abs=1e-3)
    assert continuum_first_frequency(10.0, 0.0) == pytest.approx(11.202, abs=1e-3)


@pytest.mark.parametrize("hub", [0.5, 1.0, 2.875])
@pytest.mark.parametrize("lam", [1.0, 4.0, 10.0])
def test_discrete_flapwise_with_hub_matches_continuum(lam, hub):
    ref = continuum_first_frequency(lam, hub)
    assert extrapolated(lam, hub) == pytest.approx(ref, rel=5e-5)
    # and the plain N = 40 result is within its second-order error
    assert dimensionless_frequencies(lam, hub, 1, 40, softening=False)[0] == pytest.approx(
        ref, rel=2e-3
    )
