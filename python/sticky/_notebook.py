"""Notebook views: HTML reprs of Scene, State and CompareReport (a short
table; the report's verdict coloured), and ``Scene.plot(t_end)``, the
worldlines x_i(t) coloured by cluster (matplotlib: ``pip install
./python[plot]``)."""

from fractions import Fraction
from html import escape

# Rows of data shown before "…".
_ROWS = 6

# The verdict's colour: the ladder from best to worst.
_COLOURS = {"exact": "#1a7f37", "rounding": "#2f81f7", "inexact": "#bf8700", "invalid": "#cf222e"}


def _number(q):
    """An exact value, with its decimal when the fraction is long."""
    text = str(q)
    if len(text) > 8 and "/" in text:
        return f"{text} (≈ {float(q):.6g})"
    return text


def _table(caption, rows):
    body = "".join(
        f"<tr><th style='text-align:left'>{escape(str(k))}</th><td style='text-align:left'>{v}</td></tr>"
        for k, v in rows
    )
    return f"<table><caption style='text-align:left'>{escape(caption)}</caption>{body}</table>"


def _head(values):
    shown = ", ".join(f"{v:.6g}" for v in values[:_ROWS])
    return escape(f"[{shown}{', …' if len(values) > _ROWS else ''}]")


def scene_html(self):
    """Scene._repr_html_: N, r, kind, name, the first values."""
    scene = self
    rows = [("N", scene.n), ("radius", escape(_number(scene.radius))), ("kind", scene.kind)]
    if scene.name is not None:
        rows.append(("name", escape(scene.name)))
    rows += [("x⁰", _head(scene.positions)), ("u⁰", _head(scene.velocities))]
    return _table("sticky.Scene", rows)


def state_html(self):
    """State._repr_html_: t, N, the clusters, the first values."""
    state = self
    clusters = state.clusters
    shown = ", ".join(f"({f}, {s})" for f, s in clusters[:_ROWS])
    rows = [
        ("t", escape(_number(state.t))),
        ("N", state.n),
        ("clusters", escape(f"{len(clusters)}: [{shown}{', …' if len(clusters) > _ROWS else ''}]")),
        ("x(t)", _head(state.positions)),
        ("u(t)", _head(state.velocities)),
    ]
    return _table("sticky.State", rows)


def report_html(self):
    """CompareReport._repr_html_: the verdict, coloured, and per time the
    main figures."""
    report = self
    verdict = report.verdict
    colour = _COLOURS.get(verdict, "inherit")
    rows = [("verdict", f"<b style='color:{colour}'>{escape(verdict)}</b>")]
    for k, f in enumerate(report.frames):
        rows += [
            (f"t (frame {k})", escape(_number(f.t))),
            ("max |x − x_exact|", escape(f"{f.position_max_float:.3g} at {f.position_max_index}")),
            ("overlaps", len(f.overlaps)),
            ("missed / spurious contacts", f"{f.missed_contacts} / {f.spurious_contacts}"),
        ]
    return _table("sticky.CompareReport", rows)


def plot(self, t_end, ax=None):
    """scene.plot(t_end, ax=None) -> matplotlib Figure

    The worldlines x_i(t) for 0 ≤ t ≤ t_end, exact: between collisions
    every particle moves on a straight line, so each worldline is drawn
    through its states at 0, at every collision instant before t_end and at
    t_end. Each particle is coloured by its cluster at t_end. Needs
    matplotlib (``pip install ./python[plot]``)."""
    scene = self
    try:
        import matplotlib.pyplot as plt
        from matplotlib.collections import LineCollection
    except ImportError as missing:
        raise ImportError("Scene.plot needs matplotlib: pip install ./python[plot]") from missing
    import numpy as np

    end = scene.state(t_end).t  # validates t_end (≥ 0, a number), exact
    times = sorted({Fraction(0), end} | {e.t for e in scene.events() if e.t < end})
    states = scene.states(times)
    x = np.stack([s.positions for s in states])
    t = np.array([float(q) for q in times])
    owner = np.empty(scene.n, dtype=int)
    for k, (first, size) in enumerate(states[-1].clusters):
        owner[first : first + size] = k
    colours = plt.get_cmap("tab10")(owner % 10)
    if ax is None:
        fig, ax = plt.subplots()
    else:
        fig = ax.figure
    lines = LineCollection([np.column_stack([x[:, i], t]) for i in range(scene.n)], colors=colours)
    ax.add_collection(lines)
    ax.autoscale()
    ax.set_xlabel("x")
    ax.set_ylabel("t")
    ax.set_title(f"worldlines, N = {scene.n}, coloured by cluster at t = {_number(end)}")
    return fig
