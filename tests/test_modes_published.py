"""Natural frequencies of the rotating uniform cantilever against published tables.

Checks :func:`rotbeam.modes.dimensionless_frequencies` (second-order finite differences) against
published flapwise (out-of-plane, centrifugally stiffened) frequencies of a uniform Euler-Bernoulli
cantilever.

Conventions (those of the package): ``w = omega T`` and ``lam = Omega T`` with
``T = sqrt(rho A L^4 / (E I))``; ``hub_ratio = R_o / L`` (axis-to-clamp distance over beam length).

Sources (only numbers we actually read are used; each table below says where we read it):

* **Wright et al. (1982), via Bir (2009).**  Wright, A. D., Smith, C. E., Thresher, R. W. and
  Wang, J. L. C., "Vibration modes of centrifugally stiffened beams", ASME J. Appl. Mech. 49(1)
  (1982) 197-202 (author list as cited in ref. [3] of
  https://jrstan.basu.ac.ir/article_2485.html).  Read as reprinted in the "analytical" column of
  Table 3a of Bir, G. S., "Blades and Towers Modal Analysis Code (BModes): Verification of Blade
  Modal Analysis Capability", AIAA 2009-1035 (NREL/CP-500-44749), as transcribed in the public
  repository SMI-Lab-Inha/pybmodes, file tests/fem/test_rotating_uniform_blade.py (commit
  ecf2a5f4ff577c8a5106381f170482d84be2296c).  Hub radius 0, modes 1-2 (mode 3 is also there).
  Conversion: Bir's beam has L = 31.623 m, m = 100 kg/m, EI = 1e8 N m^2, so T = 1.000014 s and his
  rad/s values ARE w and lam (the 1.4e-5 relative offset is far below the 3 printed decimals; no
  factor applied).
* **Hamza-Cherif and Houmat (2004).**  Hamza-Cherif, S. M. and Houmat, A., "Natural frequencies of
  rotating cantilever flexible beams by using the p-version of the finite element method", 24th
  Congress of the International Council of the Aeronautical Sciences (ICAS), Table 2, p. 6
  (slenderness ratio 70).  Read as transcribed in the public repository octave-user/mboct-fem-pkg,
  file inst/fem_tests.m, test 60 (commit c8f460c44969c6e4602910d6220cdb49f5cd348e), arrays
  ``mu_ref`` and ``omegax_ref_flapwise``.  That test converts ``mu = Omega sqrt(rho A L^4/EI)`` and
  ``omegax = omega sqrt(rho A L^4/EI)``, i.e. exactly lam and w; the beam root is on the axis
  (hub 0).  Their chordwise column is NOT used: it includes stretching coupling at slenderness 70
  and does not satisfy w_in^2 = w_flap^2 - lam^2 (e.g. 3.6195 vs sqrt(4.1373^2 - 4) = 3.6218).

Tolerances (applied to the Richardson extrapolation ``w_160 + (w_160 - w_80) / 3``):

* Wright/Bir prints 3 decimals.  Rounding alone allows 5e-4, and the lam = 0 mode-2 entry 22.035
  sits 5.1e-4 above the converged 22.0345 (double rounding), so we allow one unit of the last
  printed digit, ``atol = 1e-3`` (2.8e-4 relative at w = 3.5).
* Hamza-Cherif/Houmat prints 4 decimals but is itself a p-FEM result: 7.3603 (lam = 6) is 0.7
  units of the last digit below Wright/Bir's 7.360 and the converged 7.36037, and 51.0805
  (lam = 50) is 1.35e-5 relative above the converged value.  We use ``rtol = 5e-5``.

The convergence check compares the error against the published value at N = 40, 80, 160: each
doubling must cut it by a factor >= 2.5 unless the finer error is already inside the table's
resolution (then it cannot be resolved against the table).  A table-independent check asks the
same of the successive differences w_40 - w_80 and w_80 - w_160.

Hub radius > 0: no published table with a hub offset could be located and read (searched: Banerjee
2000, Yoo & Shin 1998, Wang & Wereley 2004, Bazoune 2005, Ozgumus & Kaya, Hodges & Rutkowski
1981, test suites of public FE/beam codes).  No hub > 0 numbers are invented here; the hub > 0 tests
at the end only check model-internal identities (in-plane/flapwise relation, stiffening by the
offset) and are marked as such.
"""

from __future__ import annotations

import functools

import numpy as np
import pytest

from rotbeam.model.modes import dimensionless_frequencies

GRIDS = (40, 80, 160)
N_MODES = 2
MIN_RATIO = 2.5

# Wright et al. (1982) via Bir (2009) Table 3a, hub 0: (lam, w_1, w_2), printed to 3 decimals.
WRIGHT_HUB0 = (
    (0.0, 3.516, 22.035),
    (1.0, 3.682, 22.181),
    (2.0, 4.137, 22.615),
    (3.0, 4.797, 23.320),
    (4.0, 5.585, 24.273),
    (5.0, 6.450, 25.446),
    (6.0, 7.360, 26.809),
    (7.0, 8.300, 28.334),
    (8.0, 9.257, 29.995),
    (9.0, 10.226, 31.771),
    (10.0, 11.202, 33.640),
    (11.0, 12.184, 35.589),
    (12.0, 13.170, 37.603),
)
WRIGHT_ATOL = 1.0e-3

# Hamza-Cherif & Houmat (2004) Table 2 via mboct-fem-pkg, hub 0: (lam, w_1), 4 decimals.
HAMZA_CHERIF_HUB0 = (
    (2.0, 4.1373),
    (4.0, 5.5850),
    (6.0, 7.3603),
    (8.0, 9.2568),
    (10.0, 11.2023),
    (50.0, 51.0805),
)
HAMZA_CHERIF_RTOL = 5.0e-5


def _cases() -> list:
    """(lam, hub_ratio, mode, published w, absolute tolerance) for every table entry."""
    cases = []
    for lam, *ws in WRIGHT_HUB0:
        for mode, w in enumerate(ws, start=1):
            cases.append(
                pytest.param(lam, 0.0, mode, w, WRIGHT_ATOL, id=f"wright82-lam{lam:g}-mode{mode}")
            )
    for lam, w in HAMZA_CHERIF_HUB0:
        cases.append(
            pytest.param(
                lam, 0.0, 1, w, HAMZA_CHERIF_RTOL * w, id=f"hamzacherif04-lam{lam:g}-mode1"
            )
        )
    return cases


CASES = _cases()


@functools.cache
def _frequencies(lam: float, hub_ratio: float, n: int, softening: bool) -> tuple[float, ...]:
    w = np.asarray(
        dimensionless_frequencies(lam, hub_ratio, n_modes=N_MODES, N=n, softening=softening),
        dtype=float,
    )
    assert w.shape == (N_MODES,), f"expected {N_MODES} frequencies, got shape {w.shape}"
    assert np.all(np.isfinite(w)) and np.all(np.diff(w) > 0), f"not finite/ascending: {w}"
    return tuple(float(v) for v in w)


def _sequence(lam: float, hub_ratio: float, mode: int, softening: bool = False) -> list[float]:
    """w of the given mode on the grids N = 40, 80, 160."""
    return [_frequencies(lam, hub_ratio, n, softening)[mode - 1] for n in GRIDS]


def _richardson(seq: list[float]) -> float:
    """Second-order Richardson extrapolation from N = 80 and N = 160."""
    return seq[2] + (seq[2] - seq[1]) / 3.0


@pytest.mark.parametrize(("lam", "hub_ratio", "mode", "w_pub", "atol"), CASES)
def test_flapwise_extrapolated_matches_published(lam, hub_ratio, mode, w_pub, atol):
    seq = _sequence(lam, hub_ratio, mode)
    w_ex = _richardson(seq)
    assert abs(w_ex - w_pub) <= atol, (
        f"lam={lam}, hub={hub_ratio}, mode {mode}: extrapolated {w_ex:.6f} vs published "
        f"{w_pub} (|diff| {abs(w_ex - w_pub):.2e} > {atol:.2e}); N=40,80,160 gave {seq}"
    )


@pytest.mark.parametrize(("lam", "hub_ratio", "mode", "w_pub", "atol"), CASES)
def test_flapwise_error_against_published_shrinks(lam, hub_ratio, mode, w_pub, atol):
    seq = _sequence(lam, hub_ratio, mode)
    errors = [abs(w - w_pub) for w in seq]
    for i in range(len(GRIDS) - 1):
        e_c, e_f = errors[i], errors[i + 1]
        # Below the table's resolution the error cannot be resolved any further.
        assert e_f <= e_c / MIN_RATIO or e_f <= atol, (
            f"lam={lam}, mode {mode}: error {e_c:.3e} (N={GRIDS[i]}) -> {e_f:.3e} "
            f"(N={GRIDS[i + 1]}), "
            f"cut by less than {MIN_RATIO} and still above the table resolution {atol:.1e}"
        )


@pytest.mark.parametrize(("lam", "hub_ratio", "mode", "w_pub", "atol"), CASES)
def test_flapwise_self_convergence_second_order(lam, hub_ratio, mode, w_pub, atol):
    seq = _sequence(lam, hub_ratio, mode)
    d1, d2 = seq[0] - seq[1], seq[1] - seq[2]
    assert d1 * d2 > 0 and abs(d1) >= MIN_RATIO * abs(d2), (
        f"lam={lam}, mode {mode}: successive differences {d1:.3e}, {d2:.3e} "
        f"(ratio {d1 / d2 if d2 else float('inf'):.2f}) are not those of a converging "
        f"second-order scheme"
    )


@pytest.mark.parametrize(("lam", "hub_ratio", "mode", "w_pub", "atol"), CASES)
def test_inplane_plus_lam_squared_matches_published_flapwise(lam, hub_ratio, mode, w_pub, atol):
    """Continuum identity w_in^2 = w_flap^2 - lam^2, checked against the flapwise table.

    The tolerance ``atol`` on w translates into ``2 w atol + atol^2`` on w^2.
    """
    seq = _sequence(lam, hub_ratio, mode, softening=True)
    w_in = _richardson(seq)
    lhs = w_in**2 + lam**2
    tol2 = 2.0 * w_pub * atol + atol**2
    assert abs(lhs - w_pub**2) <= tol2, (
        f"lam={lam}, mode {mode}: w_in^2 + lam^2 = {lhs:.6f} vs published w^2 = {w_pub**2:.6f} "
        f"(|diff| {abs(lhs - w_pub**2):.2e} > {tol2:.2e}); in-plane N=40,80,160 gave {seq}"
    )


# --- hub > 0: model-internal checks only (no published hub-offset table was found) -------------


@pytest.mark.parametrize("hub_ratio", [0.5, 1.0])
@pytest.mark.parametrize("mode", [1, 2])
def test_hub_offset_inplane_identity_not_published(hub_ratio, mode):
    """Not a published value: the model's own in-plane and flapwise results at hub > 0 must obey
    w_in^2 + lam^2 = w_flap^2 after extrapolation (relative 1e-4 on w^2)."""
    lam = 6.0
    w_flap = _richardson(_sequence(lam, hub_ratio, mode))
    w_in = _richardson(_sequence(lam, hub_ratio, mode, softening=True))
    assert w_in**2 + lam**2 == pytest.approx(w_flap**2, rel=1e-4)


@pytest.mark.parametrize("mode", [1, 2])
def test_hub_offset_stiffens_not_published(mode):
    """Not a published value: at fixed lam > 0 the centrifugal tension grows with the hub offset,
    so every flapwise frequency grows with hub_ratio (and equals the hub-0 value at lam = 0)."""
    lam = 6.0
    w = [_richardson(_sequence(lam, r, mode)) for r in (0.0, 0.5, 1.0)]
    assert w[0] < w[1] < w[2], w
    w0 = [_richardson(_sequence(0.0, r, mode)) for r in (0.0, 1.0)]
    assert w0[1] == pytest.approx(w0[0], rel=1e-9), w0
