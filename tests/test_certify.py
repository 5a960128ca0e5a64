"""The certification module's decisions (`rotbeam.solve.certify`): a stable collocated orbit
certified without time stepping, an unstable one refused, a window whose orbit is unstable
flagged, and the push off an unstable orbit.  Small grids (N = 12) keep them fast."""

from __future__ import annotations

import numpy as np
import pytest

from rotbeam.model.elastica import DiscreteElastica
from rotbeam.model.params import Beam, Dimensionless, Drive, Effects
from rotbeam.solve.certify import (
    LEAVE_FRACTION,
    STATUS_UNSTABLE,
    OrbitVerdict,
    certify_orbit,
    certify_window,
    monodromy_certificate,
    reported_multipliers,
)
from rotbeam.solve.floquet import FloquetResult, beam_floquet
from rotbeam.solve.numerics import Numerics
from rotbeam.solve.periodic import solve_periodic_adaptive
from rotbeam.solve.spectral import trig_interpolate

N = 12


@pytest.fixture(scope="module")
def orbit():
    """The collocated orbit at 5 rad/s, 2 Hz (far below resonance: |mu|max ~ 0.66, certified)."""
    dl = Dimensionless.from_physical(Beam(), Drive(omega0=5.0, f_d=2.0), Effects())
    model = DiscreteElastica(dl, N)
    res = solve_periodic_adaptive(model, tail_tol=Numerics().tail_tol)
    assert res.converged
    return model, res


def _shrink_unit_circle(monkeypatch):
    """|mu|max above 0.5 counts as unstable: the beam's damped orbits become 'unstable' ones."""
    monkeypatch.setattr(FloquetResult, "stable", property(lambda s: s.max_abs < 0.5))
    monkeypatch.setattr(FloquetResult, "unstable", property(lambda s: s.max_abs > 0.5))


def test_stable_orbit_is_certified_without_time_stepping(orbit):
    """The verdict is decided (status 0) with the certified message; its certificate is the one
    recomputed from a separate Floquet pass, and its transient is the certificate's offset."""
    model, res = orbit
    num = Numerics(N=N)
    verdict = certify_orbit(model, num, res)
    assert verdict.decided and verdict.status == 0 and verdict.periodic is res
    assert verdict.message.startswith(f"collocation orbit (M={res.M}, harmonic tail ")
    assert "certified by the monodromy (monodromy offset estimate" in verdict.message
    assert verdict.message.endswith("stable)") and verdict.floquet.stable
    cert = monodromy_certificate(
        beam_floquet(model, res.theta, res.theta_t), res.theta, num.ss_tol, max(model.dl.omega, 1)
    )
    assert cert.certified and verdict.certificate.certified
    assert verdict.transient == verdict.certificate.offset <= num.ss_tol / 10
    # the reported multipliers stand to floquet_tol, the candidate's only to the verdict
    assert verdict.floquet.spread <= num.floquet_tol


def test_time_certification_leaves_the_orbit_to_time_stepping(orbit):
    """certify: time: no certificate, the orbit undecided, time stepping starts on it."""
    model, res = orbit
    verdict = certify_orbit(model, Numerics(N=N, certify="time"), res)
    assert not verdict.decided and verdict.message == "" and verdict.certificate is None
    assert verdict.on_orbit and not verdict.unstable
    z = np.concatenate([res.theta[0], res.theta_t[0]])
    assert verdict.march_start(z, 1.0) is z  # not pushed


def test_unstable_orbit_is_refused(orbit, monkeypatch):
    """An orbit whose candidate check finds it unstable is never certified: left to time stepping
    (pushed off it) with integrate, status STATUS_UNSTABLE and the words without."""
    model, res = orbit
    _shrink_unit_circle(monkeypatch)
    left = certify_orbit(model, Numerics(N=N), res)
    assert not left.decided and left.unstable and not left.on_orbit
    assert left.certificate is None and left.message == ""
    alone = certify_orbit(model, Numerics(N=N, integrate=False), res)
    assert alone.decided and alone.status == STATUS_UNSTABLE
    assert alone.message.endswith("(not a steady state: the orbit is unstable)")


def test_window_on_an_unstable_orbit_is_flagged(orbit, monkeypatch):
    """A steady window of several periods gets the multipliers of its last period's samples:
    stable, status 0; counted unstable, STATUS_UNSTABLE and the slow-transient words."""
    model, res = orbit
    num = Numerics(N=N, certify="time")
    m = num.samples_per_period
    last = trig_interpolate(res.theta, m)
    undecided = OrbitVerdict(None, None)
    ok = certify_window(model, num, undecided, 0, "steady after 5 periods", 5, last)
    assert ok.status == 0 and ok.floquet.stable
    assert ok.message.startswith("steady after 5 periods; Floquet |mu|max = ")
    _shrink_unit_circle(monkeypatch)
    bad = certify_window(model, num, undecided, 0, "steady after 5 periods", 5, last)
    assert bad.status == STATUS_UNSTABLE
    assert "but the orbit reached is unstable (a slow transient" in bad.message
    assert bad.floquet.max_abs == pytest.approx(ok.floquet.max_abs, rel=1e-6)  # same samples


def test_window_that_verified_the_orbit_keeps_its_multipliers(orbit):
    """One period verified the collocated orbit: the orbit's multipliers are reported (not the
    window's), and a failed window keeps its status and message, the reason prefixed."""
    model, res = orbit
    num = Numerics(N=N, certify="time")
    verdict = certify_orbit(model, num, res)
    last = trig_interpolate(res.theta, num.samples_per_period)
    one = certify_window(model, num, verdict, 0, "verified", 1, last)
    expected = reported_multipliers(model, res, verdict.floquet, num.floquet_tol)
    assert one.status == 0 and one.message.startswith("verified; Floquet |mu|max")
    np.testing.assert_array_equal(one.floquet.monodromy, expected.monodromy)
    several = certify_window(model, num, verdict, 0, "steady", 3, last)  # the window's own
    assert not np.array_equal(several.floquet.monodromy, expected.monodromy)
    failed_orbit = OrbitVerdict(res, verdict.floquet, message="not certified (x); ")
    failed = certify_window(model, num, failed_orbit, 1, "no steady state", 7, last)
    assert failed.status == 1 and failed.message.startswith("not certified (x); no steady state")


def test_push_off_an_unstable_orbit_along_its_leading_direction():
    """Phi = diag(1.5, 0.5, 0.2, 0.1): the leading Floquet vector is e_0, scaled to
    max |v_theta| = 1, so the push is LEAVE_FRACTION x size along it; a stable orbit is not
    pushed."""
    mu = np.array([1.5, 0.5, 0.2, 0.1], dtype=complex)
    unstable = OrbitVerdict(None, FloquetResult(np.diag(mu.real), 12, 0.0))
    z = np.array([0.3, -0.2, 1.0, 2.0])
    pushed = unstable.march_start(z, 2.0)
    np.testing.assert_allclose(np.abs(pushed - z), [LEAVE_FRACTION * 2.0, 0, 0, 0], atol=1e-15)
    stable = OrbitVerdict(None, FloquetResult(np.diag(mu.real / 2), 12, 0.0))
    assert stable.march_start(z, 2.0) is z


def test_steady_asks_certify_and_computes_no_output():
    """rotbeam/solve/steady.py takes from floquet only the result's type (the multipliers come
    from the certification module), and evaluates no midspan deflection (the runs do)."""
    import ast
    import dataclasses
    import inspect

    import rotbeam.solve.steady as steady

    source = inspect.getsource(steady)
    nodes = list(ast.walk(ast.parse(source)))
    imported = {
        (node.module, alias.name)
        for node in nodes
        if isinstance(node, ast.ImportFrom)
        for alias in node.names
    }
    assert {name for module, name in imported if module == "floquet"} == {"FloquetResult"}
    assert ("certify", "certify_orbit") in imported and ("certify", "certify_window") in imported
    assert not [n for n in nodes if isinstance(n, ast.Attribute) and n.attr == "midspan"]
    assert not [n for n in nodes if isinstance(n, ast.keyword) and n.arg == "y_m"]
    assert "y_m" not in {f.name for f in dataclasses.fields(steady.SteadyState)}
