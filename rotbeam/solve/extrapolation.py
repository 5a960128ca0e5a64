"""Richardson extrapolation of a quantity computed on two grids."""

from __future__ import annotations

import numpy as np


def richardson(
    fine: float | np.ndarray, coarse: float | np.ndarray, ratio: float, order: int = 2
) -> float | np.ndarray:
    """The limit h -> 0 of a quantity whose error is C h^order, from two grids.

    Parameters
    ----------
    fine, coarse : float or numpy.ndarray
        The quantity on the fine grid and on the coarse one.
    ratio : float
        Coarse spacing over fine spacing (N_fine / N_coarse), > 1.
    order : int
        Order of the leading error term (2 for the discrete elastica).

    Returns
    -------
    float or numpy.ndarray
        (q fine - coarse) / (q - 1), q = ratio^order.
    """
    q = ratio**order
    return (q * fine - coarse) / (q - 1.0)
