#!/usr/bin/env python3
"""One QP / isotonic-regression peer: x(t) = P_K(y), y = x0 + t u0, as

    min 1/2 |x - y|^2  s.t.  x_{i+1} - x_i >= 2r          (df:KN, prop:proj-micro)

solved by --solver osqp | osqp-tight | clarabel | proxsuite | quadprog | cvxopt,
or, for --solver scipy-isotonic, by scipy.optimize.isotonic_regression in the
shifted coordinates x~_i = x_i - 2r i (df:translat-x).

Every QP is solved in the displacement d = x - y (x = y + d: min 1/2 |d|^2
s.t. D d >= 2r - D y), the form whose objective has the scale of the answer's
displacement: with the constant 1/2 |y|^2 dropped (min 1/2 |x|^2 - y.x), the
objective is of order N |y|^2 and the interior-point solvers' relative
duality-gap tolerance (Clarabel, CVXOPT: 1e-8) left positions a whole
diameter off on random-1000 (every contact missed).

Contacts: the pairs with gap <= 1e-6 * 2r (common.contacts), written as the
solution's `clusters`. Velocities ("velocity_method": "active-set
projection, same solver"): u(t) is the same solver's answer to
min 1/2 |v - u0|^2 s.t. v_{i+1} = v_i on those pairs (eq:proj-u-micro:
u(t) = P_H(u0)); for scipy-isotonic the cluster means of u0 are taken
directly. No multipliers: the QP duals are Appendix A's KKT multipliers (the
time integral of lambda), not lambda. A solve whose status is not "solved"
(OSQP at its iteration cap, Clarabel declaring the projection infeasible,
CVXOPT "unknown") gives no answer: the driver exits with an error
(quadprog raises its own).
"""
import sys

import common


def extra(p):
    p.add_argument("--solver", required=True,
                   choices=["osqp", "osqp-tight", "clarabel", "proxsuite", "quadprog", "cvxopt",
                            "scipy-isotonic"])


def diff_matrix(np, n, rows):
    """Rows (x_{j+1} - x_j) for j in rows, dense (len(rows), n)."""
    D = np.zeros((len(rows), n))
    for k, j in enumerate(rows):
        D[k, j] = -1.0
        D[k, j + 1] = 1.0
    return D


def check(name, status, ok):
    """A solver that reports failure gives no answer: the driver exits with
    an error naming the solver's status (the projection is always feasible,
    so any status but "solved" is the solver's failure)."""
    if not ok:
        raise SystemExit("%s: the solver failed (status %s)" % (name, status))


def solve(name, np, y, D, lo, E):
    """argmin 1/2|x - y|^2 s.t. D x >= lo, E x = 0 (D, E dense; may be
    empty), solved in the displacement: y + argmin 1/2|d|^2 s.t.
    D d >= lo - D y, E d = -E y."""
    if D.shape[0] == 0 and E.shape[0] == 0:
        return y.copy()
    return y + solve0(name, np, len(y), D, lo - D @ y, E, -(E @ y))


def solve0(name, np, n, D, lo, E, be):
    """argmin 1/2|d|^2 s.t. D d >= lo, E d = be."""
    mi, me = D.shape[0], E.shape[0]
    if name.startswith("osqp"):
        import osqp
        import scipy.sparse as sp
        A = sp.csc_matrix(np.vstack([D, E]))
        l = np.concatenate([lo, be])
        u = np.concatenate([np.full(mi, np.inf), be])
        prob = osqp.OSQP()
        settings = dict(verbose=False)
        if name == "osqp-tight":
            settings.update(eps_abs=1e-12, eps_rel=1e-12, max_iter=1000000, polishing=True)
        prob.setup(sp.identity(n, format="csc"), np.zeros(n), A, l, u, **settings)
        res = prob.solve()
        check(name, res.info.status, res.info.status == "solved")
        return np.array(res.x)
    if name == "clarabel":
        import clarabel
        import scipy.sparse as sp
        A = sp.csc_matrix(np.vstack([E, -D]))
        b = np.concatenate([be, -lo])
        cones = []
        if me:
            cones.append(clarabel.ZeroConeT(me))
        if mi:
            cones.append(clarabel.NonnegativeConeT(mi))
        s = clarabel.DefaultSettings()
        s.verbose = False
        sol = clarabel.DefaultSolver(sp.identity(n, format="csc"), np.zeros(n), A, b, cones,
                                     s).solve()
        check(name, sol.status, str(sol.status) == "Solved")
        return np.array(sol.x)
    if name == "proxsuite":
        import proxsuite
        qp = proxsuite.proxqp.dense.QP(n, me, mi)
        qp.settings.verbose = False
        qp.init(np.identity(n), np.zeros(n), E if me else None, be if me else None,
                D if mi else None, lo if mi else None, np.full(mi, 1e30) if mi else None)
        qp.solve()
        status = qp.results.info.status
        check(name, status, status == proxsuite.proxqp.QPSolverOutput.PROXQP_SOLVED)
        return np.array(qp.results.x)
    if name == "quadprog":
        import quadprog
        C = np.vstack([E, D]).T
        b = np.concatenate([be, lo])
        return np.array(quadprog.solve_qp(np.identity(n), np.zeros(n), C, b, me)[0])
    if name == "cvxopt":
        import cvxopt
        cvxopt.solvers.options["show_progress"] = False
        kw = {}
        if mi:
            kw["G"] = cvxopt.matrix(-D)
            kw["h"] = cvxopt.matrix(-lo)
        if me:
            kw["A"] = cvxopt.matrix(E)
            kw["b"] = cvxopt.matrix(be)
        sol = cvxopt.solvers.qp(cvxopt.spdiag([1.0] * n), cvxopt.matrix(np.zeros(n)), **kw)
        check(name, sol["status"], sol["status"] == "optimal")
        return np.array(sol["x"]).ravel()
    raise ValueError(name)


MODULES = {"osqp": "osqp", "osqp-tight": "osqp", "clarabel": "clarabel", "proxsuite": "proxsuite",
           "quadprog": "quadprog", "cvxopt": "cvxopt", "scipy-isotonic": "scipy.optimize"}


def main():
    a = common.args(__doc__.splitlines()[0], extra)
    peer = a.solver
    try:
        import numpy as np
        __import__(MODULES[peer])
        if peer in ("osqp", "osqp-tight", "clarabel"):
            import scipy.sparse  # noqa: F401
    except ImportError as e:
        common.skip(peer, "not installed (%s); run scripts/peers/install.sh" % e)
    n, r, x0, u0 = common.load(a.export)
    x0, u0 = np.array(x0), np.array(u0)
    two_r = 2.0 * r

    def solve_all():
        frames = []
        for ts in a.at:
            t = common.time_of(ts)
            y = x0 + t * u0
            if peer == "scipy-isotonic":
                from scipy.optimize import isotonic_regression
                shift = two_r * np.arange(n)
                x = isotonic_regression(y - shift).x + shift
            else:
                x = solve(peer, np, y, diff_matrix(np, n, list(range(n - 1))),
                          np.full(n - 1, two_r), np.zeros((0, n)))
            contacts = common.contacts(x, two_r)
            clusters = common.clusters_from(contacts)
            if peer == "scipy-isotonic":
                v = np.empty(n)
                for first, size in clusters:
                    v[first:first + size] = u0[first:first + size].mean()
            else:
                rows = [j for j in range(n - 1) if contacts[j]]
                v = solve(peer, np, u0, np.zeros((0, n)), np.zeros(0), diff_matrix(np, n, rows))
            frames.append({"t": ts, "positions": x, "velocities": v, "clusters": clusters})
        return frames

    frames, timing = common.timed(solve_all)
    setting = {"osqp": "default tolerances", "osqp-tight": "eps_abs=eps_rel=1e-12, polishing"}.get(
        peer, "default")
    common.write(a.out, frames, peer, setting, "active-set projection, same solver", timing)


if __name__ == "__main__":
    main()
