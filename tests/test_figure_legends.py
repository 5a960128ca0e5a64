"""Readers' details of the figures: a legend covers no curve, every drawn style has a legend
entry, no marker reaches past its axes, no two texts overlap, Fig. 7's h/L colours are distinct
and readable on white, and every y_m axis says its unit.

The figures are drawn from small inputs built here (a one-mode resonance for Fig. 4, sines for
the time series, the config's Fig. 7 grid of beams with a collapse-shaped E*), caught before
they are written.  Each check has a control, a figure drawn to break it, so that it can fail."""

import itertools
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402
import yaml  # noqa: E402
from matplotlib.colors import to_rgba  # noqa: E402
from matplotlib.text import Text  # noqa: E402

from rotbeam.model.params import Beam  # noqa: E402
from rotbeam.paper import figures  # noqa: E402
from rotbeam.paper.studies import fig7_beams  # noqa: E402
from rotbeam.report import nonlinear_figures  # noqa: E402
from rotbeam.report.style import legend_in_headroom, panel_label  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
THRESHOLD = 0.1


# --- the checks ---------------------------------------------------------------------------


def curve_points(ax) -> np.ndarray:
    """The display points of every line of `ax`, 20 to a segment (a legend over a segment
    between two vertices covers the curve as much as one over a vertex)."""
    out = []
    for line in ax.get_lines():
        xy = line.get_transform().transform(np.asarray(line.get_xydata(), float))
        xy = xy[np.isfinite(xy).all(axis=1)]
        if len(xy) == 1:
            out.append(xy)
        for p, q in itertools.pairwise(xy):
            out.append(p + np.linspace(0.0, 1.0, 20)[:, None] * (q - p))
    return np.concatenate(out) if out else np.empty((0, 2))


def covered_points(ax) -> int:
    """How many points of the curves of `ax` lie inside its legend's box."""
    box = ax.get_legend().get_window_extent()
    return int(sum(box.contains(*p) for p in curve_points(ax)))


def style_key(artist) -> tuple:
    """What tells an artist apart on the page: a line's marker, colour and dash; a patch's or a
    filled area's face colour."""
    if isinstance(artist, matplotlib.lines.Line2D):
        color = np.round(to_rgba(artist.get_color()), 3)
        return ("line", artist.get_marker(), tuple(color), artist.get_linestyle())
    face = np.atleast_2d(artist.get_facecolor())[0]
    return ("area", tuple(np.round(to_rgba(face), 3)))


def unexplained_styles(fig) -> set:
    """The styles drawn in some panel of `fig` that no legend of the figure shows."""
    drawn, shown = set(), set()
    for ax in fig.axes:
        lines = [ln for ln in ax.get_lines() if len(ln.get_xdata())]
        for artist in lines + list(ax.patches) + list(ax.collections):
            drawn.add(style_key(artist))
        if ax.get_legend() is not None:
            shown |= {style_key(h) for h in ax.get_legend().legend_handles}
    return drawn - shown


def markers_outside(fig) -> list[str]:
    """The markers of `fig` that reach past their axes (their full size, at their position)."""
    out = []
    for ax in fig.axes:
        box = ax.get_window_extent()
        for line in ax.get_lines():
            if line.get_marker() in ("None", "", None, " ") or not len(line.get_xdata()):
                continue
            r = (line.get_markersize() / 2 + line.get_markeredgewidth()) * fig.dpi / 72.0
            xy = line.get_transform().transform(np.asarray(line.get_xydata(), float))
            for x, y in xy[np.isfinite(xy).all(axis=1)]:
                inside = box.x0 <= x - r and x + r <= box.x1 and box.y0 <= y - r and y + r <= box.y1
                if not inside:
                    out.append(f"{line.get_label()} at ({x:.0f}, {y:.0f}) px")
    return out


def page_texts(fig) -> list[Text]:
    """The texts a reader reads beside the ticks: panel labels and other texts, titles, axis
    labels, legend titles and entries."""
    texts = []
    for ax in fig.axes:
        texts += [*ax.texts, ax.title, ax.xaxis.label, ax.yaxis.label]
        if ax.get_legend() is not None:
            texts += [ax.get_legend().get_title(), *ax.get_legend().get_texts()]
    return [t for t in texts if t.get_visible() and t.get_text().strip()]


def overlapping_texts(fig) -> list[tuple[str, str]]:
    """The pairs of texts of `fig` whose boxes overlap."""
    boxes = [(t.get_text(), t.get_window_extent()) for t in page_texts(fig)]
    return [
        (s, t)
        for (s, p), (t, q) in itertools.combinations(boxes, 2)
        if min(p.x1, q.x1) > max(p.x0, q.x0) and min(p.y1, q.y1) > max(p.y0, q.y0)
    ]


def relative_luminance(color) -> float:
    """WCAG 2 relative luminance of an sRGB colour."""
    lin = [c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4 for c in to_rgba(color)[:3]]
    return 0.2126 * lin[0] + 0.7152 * lin[1] + 0.0722 * lin[2]


def contrast_on_white(color) -> float:
    """WCAG 2 contrast ratio of a colour against white (3 is the floor for graphics)."""
    return 1.05 / (relative_luminance(color) + 0.05)


# --- small inputs -------------------------------------------------------------------------


def resonance_line(omega0: float, f0: float, points: int = 30, zeta: float = 0.02):
    """A Fig. 4 sweep line of a one-mode oscillator: quasi-static RMS grows with f_d (the Euler
    load), the dynamic one is it over |1 - r^2 + 2 i zeta r|, r = f_d / f_0."""
    f_d = f0 * np.linspace(0.05, 1.5, points)
    r = f_d / f0
    qs = 0.03 * r
    dyn = qs / np.abs(1.0 - r**2 + 2j * zeta * r)
    return pd.DataFrame({
        "f_d": f_d, "rms_dynamic": dyn, "rms_quasistatic": qs,
        "delta_rms": np.abs(dyn - qs) / dyn, "omega0": omega0, "f_n_hz": 6.52, "f0_hz": f0,
    })  # fmt: skip


def critical_rows(lines) -> pd.DataFrame:
    """f_d* of each line: the first crossing of the threshold, interpolated, and the first
    scanned point at or above it."""
    rows = []
    for line in lines:
        d, f = line["delta_rms"].to_numpy(), line["f_d"].to_numpy()
        k = int(np.argmax(d >= THRESHOLD))
        root = f[k - 1] + (THRESHOLD - d[k - 1]) * (f[k] - f[k - 1]) / (d[k] - d[k - 1])
        rows.append({"omega0": line["omega0"].iloc[0], "f_d_root": root, "f_d_grid": f[k]})
    return pd.DataFrame(rows)


def time_series(e_max: float, dyn: float, qs: float) -> pd.DataFrame:
    """A kept time series of three periods (the full config's) whose dynamic curve fills its
    panel."""
    tau = np.linspace(0.0, 2.0 * math.pi, 600)
    wave = np.cos(3.0 * tau)
    return pd.DataFrame({
        "tau": tau, "y_m_dynamic": dyn * wave, "y_m_quasistatic": qs * wave,
        "C_max": 50.0, "E_max": e_max, "delta_rms": abs(dyn - qs) / dyn,
    })  # fmt: skip


def fig5_boundary() -> pd.DataFrame:
    """A reference-beam boundary E*(C_max) rising as sqrt(1 + C_max / 50)."""
    c = np.array([0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 50.0, 100.0, 300.0, 787.0])
    e = 0.4 * np.sqrt(1.0 + c / 50.0)
    return pd.DataFrame(
        {"threshold": THRESHOLD, "C_max": c, "E_star_root": e, "E_star_grid": 1.1 * e}
    )


def fig7_boundary() -> pd.DataFrame:
    """The config's Fig. 7 grid of beams (their real zeta: every h/L = 0.01 beam is overdamped),
    with E* on the collapse curve c sqrt(1 + x), 3 times it where zeta > 0.2, and a factor of its
    own per beam so that each curve is told from the others by its values."""
    config = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
    rows = []
    for k, (name, spec) in enumerate(fig7_beams(config).items()):
        b = Beam(**spec)
        e_n = b.G * 1.0 * 2.0 * math.pi * b.f_n
        for c_max in config["fig7"]["c_max"]:
            row = {"beam": name, "E": b.E, "L": b.L, "h_over_L": float(f"{b.h / b.L:.6g}"),
                   "zeta": b.zeta, "C_max": c_max, "E_n": e_n, "G": b.G, "hub_ratio": b.hub_ratio,
                   "threshold": THRESHOLD}  # fmt: skip
            x = figures._scaled_x(row)
            scale = (3.0 if b.zeta > figures.ZETA_UNDERDAMPED else 1.0) * (1.0 + 0.01 * k)
            rows.append({**row, "E_star_root": scale * 0.23 * e_n * math.sqrt(1.0 + x)})
    return pd.DataFrame(rows)


@pytest.fixture
def drawn(monkeypatch):
    """Draw a paper figure and hand back the figure, laid out, instead of writing it."""
    caught = []
    monkeypatch.setattr(figures, "save", lambda fig, pdf, png=None: caught.append(fig))

    def draw(name: str):
        if name == "fig4":
            lines = [resonance_line(10.0, 7.6), resonance_line(100.0, 34.6)]
            figures.fig4_compare(lines, critical_rows(lines), THRESHOLD, "f.pdf", "f.png")
        elif name == "fig5":
            series = [time_series(2.0, 0.033, 0.016), time_series(1.0, 0.0093, 0.008)]
            figures.fig5_phase(fig5_boundary(), THRESHOLD, series, "f.pdf", "f.png")
        elif name == "fig7":
            figures.fig7_collapse(fig7_boundary(), 0.23, "f.pdf", "f.png")
        fig = caught.pop()
        fig.canvas.draw()  # the constrained layout runs at the draw
        return fig

    yield draw
    plt.close("all")


# --- the controls: each check fails on a figure drawn to break it --------------------------


def control_figure():
    """Two sines filling a panel, an unlabelled shaded band, a marker on the upper edge, and an
    upper-left legend with a title under the panel's label."""
    fig, ax = plt.subplots(figsize=(3.6, 3.0))
    t = np.linspace(0.0, 26.0, 4000)
    ax.plot(t, 0.34 * np.cos(2.0 * np.pi * t / 1.7), label="dyn.")
    ax.plot(t, 0.05 * np.sin(2.0 * np.pi * t / 1.7), "--", label="QS")
    ax.axvspan(0.0, 3.0, color="g", alpha=0.1)
    ax.set_ylim(-0.4, 0.4)
    ax.plot([13.0], [0.4], "v", color="k", label="peak")
    ax.legend(loc="upper left", title="marker size: L")
    panel_label(ax, "(a)")
    fig.canvas.draw()
    return fig, ax


def test_the_checks_can_fail():
    fig, ax = control_figure()
    assert covered_points(ax) > 0
    assert ("area", tuple(np.round(to_rgba("g", 0.1), 3))) in unexplained_styles(fig)
    assert any(s.startswith("peak") for s in markers_outside(fig))
    assert ("(a)", "marker size: L") in overlapping_texts(fig)
    assert contrast_on_white("0.65") < 3.0 and contrast_on_white("#feba2c") < 3.0
    plt.close(fig)


def test_legend_in_headroom_covers_no_point():
    fig, ax = plt.subplots(figsize=(3.6, 3.0))
    t = np.linspace(0.0, 26.0, 4000)
    ax.plot(t, 0.34 * np.cos(2.0 * np.pi * t / 1.7), label="dyn.")
    ax.plot(t, 0.05 * np.sin(2.0 * np.pi * t / 1.7), "--", label="QS")
    legend_in_headroom(ax, 0.2, ncol=2)
    fig.canvas.draw()
    assert covered_points(ax) == 0
    plt.close(fig)


# --- the figures --------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["fig4", "fig5", "fig7"])
def test_legends_cover_no_curve(drawn, name):
    fig = drawn(name)
    for ax in fig.axes:
        if ax.get_legend() is not None:
            assert covered_points(ax) == 0, f"{name}: a legend covers a curve"


@pytest.mark.parametrize("name", ["fig4", "fig5"])
def test_every_drawn_style_has_a_legend_entry(drawn, name):
    assert unexplained_styles(drawn(name)) == set()


@pytest.mark.parametrize("name", ["fig4", "fig5", "fig7"])
def test_markers_stay_inside_their_axes(drawn, name):
    assert markers_outside(drawn(name)) == []


def test_fig4_peak_marker_points_at_the_peak_without_hiding_it(drawn):
    fig = drawn("fig4")
    rms_panels = [ax for ax in fig.axes if ax.get_ylabel().startswith("RMS")]
    assert len(rms_panels) == 2
    for ax in rms_panels:
        (peak,) = [ln for ln in ax.get_lines() if ln.get_label() == "peak of scan"]
        (dyn,) = [ln for ln in ax.get_lines() if ln.get_label() == "dynamical"]
        k = int(np.nanargmax(dyn.get_ydata()))
        top = dyn.get_transform().transform(dyn.get_xydata()[k])
        half = lambda ln: (ln.get_markersize() / 2 + ln.get_markeredgewidth()) * fig.dpi / 72.0  # noqa: E731
        (x, y) = peak.get_transform().transform(peak.get_xydata()[0])
        assert abs(x - top[0]) < 0.5  # over the peak
        assert y - half(peak) > top[1] + half(dyn)  # above the peak's own marker, not on it


@pytest.mark.parametrize("name", ["fig4", "fig5", "fig7"])
def test_no_two_texts_overlap(drawn, name):
    assert overlapping_texts(drawn(name)) == []


def test_fig7_every_h_over_l_has_a_distinct_readable_colour(drawn):
    boundary = fig7_boundary()
    fig = drawn("fig7")
    a = fig.axes[0]
    entries = zip(a.get_legend().get_texts(), a.get_legend().legend_handles, strict=True)
    legend = {text.get_text(): handle for text, handle in entries}
    colour = {
        hl: to_rgba(legend[f"h/L = {hl:g}"].get_color()) for hl in boundary["h_over_L"].unique()
    }
    # each curve is drawn in its own h/L's colour, the one its legend entry shows
    for line in a.get_lines():
        if not len(line.get_xdata()):
            continue
        (hl,) = boundary.loc[
            np.isin(boundary["E_star_root"], line.get_ydata()), "h_over_L"
        ].unique()
        assert to_rgba(line.get_color()) == colour[hl], f"h/L = {hl:g}"
    # distinct, not grey, and readable on white
    for c in colour.values():
        assert contrast_on_white(c) >= 3.0, c
        assert max(c[:3]) - min(c[:3]) >= 0.2, f"{c} is nearly grey"
    for p, q in itertools.combinations(colour.values(), 2):
        assert np.linalg.norm(np.subtract(p[:3], q[:3])) >= 0.25, (p, q)


@pytest.mark.parametrize("name", ["fig4", "fig5"])
def test_every_y_m_axis_says_its_unit(drawn, name):
    labels = [ax.get_ylabel() for ax in drawn(name).axes if "y_m" in ax.get_ylabel()]
    assert labels
    assert all(label.rstrip().endswith("/ L") for label in labels), labels


def branch_rows(unsteady: bool) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Branch and sweep rows of one amplitude: a stable arm from below ending at a fold and an
    up-sweep on it, steady; with `unsteady`, an arm from above turning unstable at a period
    doubling and a torus, and a down-sweep with a point that reached no steady state."""
    f = np.linspace(6.0, 6.9, 4)
    rows = [{"kind": "branch", "arm": "from_below", "index": k, "f_d": x, "rms_ym": 0.2 + 0.1 * k,
             "stable": True, "bifurcation": "fold" if k == 3 else None, "status": np.nan}
            for k, x in enumerate(f)]  # fmt: skip
    rows += [{"kind": "sweep", "arm": "up", "index": k, "f_d": x, "rms_ym": 0.2 + 0.1 * k,
              "stable": True, "bifurcation": None, "status": 0}
             for k, x in enumerate(f[:2])]  # fmt: skip
    if unsteady:
        rows += [{"kind": "branch", "arm": "from_above", "index": k, "f_d": 8.0 - 0.3 * k,
                  "rms_ym": 0.1 + 0.05 * k, "stable": k < 2, "status": np.nan,
                  "bifurcation": "period doubling+torus" if k == 2 else None}
                 for k in range(4)]  # fmt: skip
        rows += [{"kind": "sweep", "arm": "down", "index": k, "f_d": 8.0 - 0.3 * k,
                  "rms_ym": 0.1 + 0.05 * k, "stable": True, "bifurcation": None,
                  "status": 1 if k == 1 else 0} for k in range(2)]  # fmt: skip
    frame = pd.DataFrame(rows).assign(amplitude=1.0)
    return frame, pd.DataFrame({"amplitude": [1.0], "f_loss": [6.9]})


@pytest.mark.parametrize(
    "unsteady, labels",
    [
        (False, ["branch from below (stable)", "fold (mu through +1)", "sweep up"]),
        (True, ["branch from below (stable)", "branch from above (stable)", "unstable",
                "fold (mu through +1)", "period doubling (mu through -1)",
                "torus (complex pair through |mu| = 1)", "sweep up", "sweep down",
                "sweep point not steady"]),
    ],
)  # fmt: skip
def test_the_branches_legend_lists_only_what_is_drawn(monkeypatch, unsteady, labels):
    """The nonlinear study's figure names each kind of mark its rows draw and none they do not:
    with every sweep point steady there is no "not steady" entry."""
    caught = []
    monkeypatch.setattr(nonlinear_figures, "save", lambda fig, pdf, png=None: caught.append(fig))
    rows, folds = branch_rows(unsteady)
    nonlinear_figures.branches_figure(rows, folds, 5.0, "b.pdf", "b.png")
    (legend,) = caught[0].legends
    assert [t.get_text() for t in legend.get_texts()] == labels
    plt.close("all")
