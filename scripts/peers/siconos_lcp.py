#!/usr/bin/python3
"""Siconos LCP solvers (siconos.numerics: Lemke, PGS, ENUM) on the KKT system
of x(t) = P_K(y), y = x0 + t u0 (Appendix A): x = y + D^T mu, and with
w = D x - 2r: w = M mu + q >= 0, mu >= 0, w.mu = 0, M = D D^T,
q = D y - 2r (D the (N-1) x N difference matrix). Run with /usr/bin/python3.

Contacts: the pairs with gap <= 1e-6 * 2r (common.contacts), not {mu_i > 0}:
a resting contact (gap 0, mu_i = 0, e.g. particles touching with equal
velocities) is a contact (df:Omega-micro). Velocities ("velocity_method":
"active-set projection"): u(t) = cluster means of u0 over those contacts
(eq:proj-u-micro); the contacts are written as `clusters`. No multipliers:
mu is Appendix A's KKT multiplier (the time integral of lambda), not lambda.
A solver that reports failure (info != 0; ENUM gives up beyond a few dozen
pairs) gives no answer: the driver exits with an error.
"""
import common


def extra(p):
    p.add_argument("--solver", default="lemke", choices=["lemke", "pgs", "enum"])


def main():
    a = common.args(__doc__.splitlines()[0], extra)
    peer = "siconos-lcp-" + a.solver
    try:
        import numpy as np
        import siconos.numerics as sn
    except ImportError as e:
        common.skip(peer, "not installed (%s); apt-get install python3-siconos, "
                          "run with /usr/bin/python3" % e)
    n, r, x0, u0 = common.load(a.export)
    x0, u0 = np.array(x0), np.array(u0)
    D = np.zeros((n - 1, n))
    for j in range(n - 1):
        D[j, j], D[j, j + 1] = -1.0, 1.0
    M = D @ D.T
    sid = {"lemke": sn.SICONOS_LCP_LEMKE, "pgs": sn.SICONOS_LCP_PGS,
           "enum": sn.SICONOS_LCP_ENUM}[a.solver]
    def solve_all():
        frames = []
        for ts in a.at:
            t = common.time_of(ts)
            y = x0 + t * u0
            if n == 1:
                frames.append({"t": ts, "positions": y, "velocities": u0})
                continue
            q = D @ y - 2.0 * r
            lcp = sn.LCP(M, q)
            z = np.zeros(n - 1)
            w = np.zeros(n - 1)
            info = sn.linearComplementarity_driver(lcp, z, w, sn.SolverOptions(sid))
            if info != 0:
                raise SystemExit("%s: the solver failed (info = %d) at t = %s" % (peer, info, ts))
            x = y + D.T @ z
            clusters = common.clusters_from(common.contacts(x, 2.0 * r))
            v = np.empty(n)
            for first, size in clusters:
                v[first:first + size] = u0[first:first + size].mean()
            frames.append({"t": ts, "positions": x, "velocities": v, "clusters": clusters})
        return frames

    frames, timing = common.timed(solve_all)
    common.write(a.out, frames, peer, "default options", "active-set projection", timing)


if __name__ == "__main__":
    main()
