"""Centerline shapes in the rotating and the lab frame.

The lab frame turns the rotating frame by phi(t) = int_0^t Omega dt
= Omega_0 t + a (1 - cos(2 pi f_d t)) / (2 pi f_d); points are measured from the axis, in units
of L: R(s) = (r_o + x(s), y(s)).
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd


def shapes_over_period(result, frames: int | None = None) -> pd.DataFrame:
    """The centerline at the samples of a simulated scene, in both frames (the shape figures).

    The lab frame turns the rotating one by the disk's angle, `Drive.angle`.

    Parameters
    ----------
    result : SceneResult
        A simulated scene (`rotbeam.runs.scene.simulate`).
    frames : int or None
        How many equispaced samples of the RMS window to draw; None: every sample.

    Returns
    -------
    pandas.DataFrame
        One row per node and frame: ``frame``, ``t_s`` [s] from the window's start, ``phase``
        (t f_d), ``s``, ``x_rot``, ``y_rot``, ``x_lab``, ``y_lab`` (units of L, from the axis)
        and ``phi`` [rad].
    """
    scene = result.scene
    grid = scene.model().grid
    r_o = scene.beam.hub_ratio
    d = scene.drive
    rows = []
    theta = result.dynamic.theta
    m = result.tau.size
    picks = range(m) if frames is None else np.linspace(0, m, frames, endpoint=False).astype(int)
    for frame, k in enumerate(picks):
        tau = result.tau[k]
        t = tau * scene.beam.T
        t_rel = t - result.tau[0] * scene.beam.T
        s, x, y = grid.full_shape(theta[k])
        X, Y = r_o + x, y
        phi = d.angle(float(t))
        c, sn = math.cos(phi), math.sin(phi)
        for j in range(s.size):
            rows.append({
                "frame": frame, "t_s": t_rel, "phase": t_rel * d.f_d, "s": s[j],
                "x_rot": X[j], "y_rot": Y[j],
                "x_lab": c * X[j] - sn * Y[j], "y_lab": sn * X[j] + c * Y[j],
                "phi": float(phi),
            })  # fmt: skip
    return pd.DataFrame(rows)
