"""Validate a solver with sticky.compare: the Python twin of
examples/check_a_solver.rs.

A ten-line time-stepping solver (explicit Euler step, then the projection
onto the admissible set K, in floating point) runs the scene
scenes/random-1000.toml (N = 1000) to T = 1 at step sizes h = 1/10 …
1/1000; sticky.compare measures each answer
exactly against the exact solution and gives its verdict. The scheme is
exact in exact arithmetic (the semigroup property eq:semigroup: x(t + h) =
P_K(x(t) + h u(t))), so what the chart shows is floating-point rounding,
accumulated over T/h steps — including overlaps of a few ulps, which
sticky.compare calls "invalid" strictly and "rounding" with a tolerance. The chart of the
maximal position error against h is written to the path given.

    MPLBACKEND=Agg python examples/python/validate_a_solver.py errors.png
"""

import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from scipy.optimize import isotonic_regression

import sticky


def euler_projection(x0, u0, radius, T, h):
    """x_{k+1} = P_K(x_k + h u_k), u_{k+1} = (x_{k+1} - x_k) / h, in float64."""
    shift = 2 * radius * np.arange(len(x0))  # K is the monotone cone in x - shift
    x, u = np.array(x0, dtype=float), np.array(u0, dtype=float)
    for _ in range(round(T / h)):
        x_new = isotonic_regression(x + h * u - shift).x + shift
        x, u = x_new, (x_new - x) / h
    return x, u


def main():
    out = Path(sys.argv[1] if len(sys.argv) > 1 else "validate-a-solver.png")
    root = Path(__file__).resolve().parents[2]
    scene = sticky.Scene.load(root / "scenes" / "random-1000.toml")
    T = 1
    steps, errors = [], []
    print(f"scene: N = {scene.n}, r = {scene.radius}; answers at T = {T} (indices from 0)")
    for m in [10, 20, 50, 100, 200, 500, 1000]:
        h = 1 / m
        x, u = euler_projection(scene.positions, scene.velocities, float(scene.radius), T, h)
        # The solver's contacts: gaps within 1e-9 of 2r. Strictly, any
        # overlap is invalid; with a rounding tolerance of 1e-6 * 2r,
        # overlaps and errors that small are "rounding".
        strict = sticky.compare(scene, T, x, u, contact_tol="1e-9")
        report = sticky.compare(scene, T, x, u, contact_tol="1e-9", overlap_tol="1e-6")
        print(
            f"h = 1/{m:<4}: {strict.verdict} ({len(strict.overlaps)} overlaps), "
            f"{report.verdict} with tolerance; max position error "
            f"{report.position_max_float:.3e} at positions[{report.position_max_index}]"
        )
        steps.append(h)
        errors.append(report.position_max_float)
    fig, ax = plt.subplots(figsize=(5, 4))
    ax.loglog(steps, [max(e, 1e-17) for e in errors], "o-", label="Euler + projection")
    ax.set_xlabel("time step h")
    ax.set_ylabel(f"max |x_i(T) - exact|, T = {T}")
    ax.set_title("Error against the exact solution (sticky.compare)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
