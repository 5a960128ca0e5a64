"""A legend over curves that fill their panel's height stands in a band above them
(`rotbeam.report.style.legend_in_headroom`: Fig. 3b's time series, the surrogate comparison's
resonance peaks) and covers no point; the control, matplotlib's own upper-right legend on the
same panel, covers some, so that the check can fail."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from rotbeam.report.style import legend_in_headroom  # noqa: E402


def covered_points(place) -> int:
    """How many points of two sines that fill the panel lie inside the legend `place` draws."""
    fig, ax = plt.subplots(figsize=(3.6, 3.0))
    t = np.linspace(0.0, 26.0, 4000)
    ax.plot(t, 0.34 * np.cos(2.0 * np.pi * t / 1.7), label="dyn.")
    ax.plot(t, 0.05 * np.sin(2.0 * np.pi * t / 1.7), "--", label="QS")
    place(ax)
    fig.canvas.draw()
    box = ax.get_legend().get_window_extent()
    xy = np.concatenate([ax.transData.transform(line.get_xydata()) for line in ax.get_lines()])
    plt.close(fig)
    return sum(box.contains(*p) for p in xy)


def test_legend_in_headroom_covers_no_point():
    assert covered_points(lambda ax: legend_in_headroom(ax, 0.2, ncol=2)) == 0
    assert covered_points(lambda ax: ax.legend(loc="upper right")) > 0  # the control
