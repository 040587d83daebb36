#!/usr/bin/env python3
"""cromosim 2.1's velocity projection (cromosim.micro.projection, Maury's
crowd-motion scheme) as a catching-up time-stepper in 1D: at every step the
velocity is the projection of the desired velocity u0 onto the feasible
velocities { u : u_i - u_{i+1} <= (x_{i+1} - x_i - 2r)/dt } (disks of radius
r on the line y = 0, every neighbour pair in the contact list), then
x <- x + dt u. This is the first-order inclusion x' in u0 - dI_K(x) of the
paper, whose solution is x(t) = P_K(x0 + t u0). --method cvxopt (default;
tolerances from cvxopt.solvers.options, --tight sets abstol = reltol =
feastol = 1e-12) or uzawa.

Each requested time runs from 0 with dt = t / ceil(t / h).
Velocities ("velocity_method": "solver's own dynamics"): the last projected
velocity. Contacts: pairs with gap <= 1e-6 * 2r (common.contacts).
"""
import math

import common


def extra(p):
    p.add_argument("--h", type=float, default=1e-2, help="time step")
    p.add_argument("--method", default="cvxopt", choices=["cvxopt", "uzawa"])
    p.add_argument("--tight", action="store_true")


def main():
    a = common.args(__doc__.splitlines()[0], extra)
    peer = "cromosim"
    try:
        import numpy as np
        import cvxopt
        from cromosim.micro import projection
    except ImportError as e:
        common.skip(peer, "not installed (%s); run scripts/peers/install.sh" % e)
    if a.tight:
        for k in ("abstol", "reltol", "feastol"):
            cvxopt.solvers.options[k] = 1e-12
    n, r, x0, u0 = common.load(a.export)
    def solve_all():
        frames = []
        for ts in a.at:
            t = common.time_of(ts)
            x = np.array(x0, dtype=float)
            u = np.array(u0, dtype=float)
            Vd = np.zeros((n, 2))
            Vd[:, 0] = u0
            steps = max(1, math.ceil(t / a.h)) if t > 0 else 0
            dt = t / steps if steps else a.h
            for _ in range(steps):
                xyrv = np.zeros((n, 4))
                xyrv[:, 0] = x
                xyrv[:, 2] = r
                xyrv[:, 3] = 1.0
                contacts = np.zeros((n - 1, 5))
                contacts[:, 0] = np.arange(n - 1)
                contacts[:, 1] = np.arange(1, n)
                contacts[:, 2] = x[1:] - x[:-1] - 2.0 * r
                contacts[:, 3] = 1.0  # e_ij = (x_j - x_i)/|x_j - x_i|
                out = projection(dt, xyrv, contacts, Vd, method=a.method)
                U = np.asarray(out[2], dtype=float).ravel()
                u = U[0::2] if U.size == 2 * n else U.reshape(n, 2)[:, 0]
                x = x + dt * u
            frames.append({"t": ts, "positions": x, "velocities": u,
                           "clusters": common.clusters_from(common.contacts(x, 2.0 * r))})
        return frames

    frames, timing = common.timed(solve_all)
    setting = "method=%s h=%g%s" % (a.method, a.h, " tight" if a.tight else "")
    common.write(a.out, frames, peer, setting, "solver's own dynamics", timing)


if __name__ == "__main__":
    main()
