#!/usr/bin/python3
"""Siconos Moreau-Jean time-stepping (MoreauJeanOSI, theta = 1/2), Newton
impact law with restitution 0, LCP one-step problem: N unit-mass
LagrangianLinearTIDS on a line, one LagrangianLinearTIR per neighbour pair
(y = x_{i+1} - x_i - 2r >= 0). Siconos is Debian's python3-siconos: run with
the system /usr/bin/python3.

Each requested time t runs its own simulation from 0 with the step
h' = t / ceil(t / h), so that t is reached exactly in steps of h'.
Velocities ("velocity_method": "solver's own dynamics"): Siconos's
velocities after the last step. Multipliers: lambda_i = P_i / N, P_i the
sum over the steps of the impulse of contact i (eq:dyn-micro with unit
masses: u_i - u0_i = -(P_i - P_{i-1})). The solver's contacts: the pairs
with gap <= 1e-6 * 2r (common.contacts; a resting contact has no impulse).
"""
import math

import common


def extra(p):
    p.add_argument("--h", type=float, default=1e-3, help="time step")


def main():
    a = common.args(__doc__.splitlines()[0], extra)
    peer = "siconos-mj"
    try:
        import numpy as np
        import siconos.kernel as sk
    except ImportError as e:
        common.skip(peer, "not installed (%s); apt-get install python3-siconos, "
                          "run with /usr/bin/python3" % e)
    n, r, x0, u0 = common.load(a.export)
    def build():
        """The set-up: one Siconos model and simulation per requested time
        (built apart from the stepping, which is the solve)."""
        models = []
        for ts in a.at:
            t = common.time_of(ts)
            if t == 0.0:
                models.append((ts, None))
                continue
            steps = max(1, math.ceil(t / a.h))
            h = t / steps
            nsds = sk.NonSmoothDynamicalSystem(0.0, t)
            ds = []
            for i in range(n):
                d = sk.LagrangianLinearTIDS([x0[i]], [u0[i]], [[1.0]])
                nsds.insertDynamicalSystem(d)
                ds.append(d)
            law = sk.NewtonImpactNSL(0.0)
            inters = []
            for i in range(n - 1):
                rel = sk.LagrangianLinearTIR(np.array([[-1.0, 1.0]]), np.array([-2.0 * r]))
                it = sk.Interaction(law, rel)
                nsds.link(it, ds[i], ds[i + 1])
                inters.append(it)
            sim = sk.TimeStepping(nsds, sk.TimeDiscretisation(0.0, h), sk.MoreauJeanOSI(0.5),
                                  sk.LCP())
            models.append((ts, (steps, ds, inters, sim)))
        return models

    def step_all(models):
        frames = []
        for ts, model in models:
            if model is None:
                frames.append({"t": ts, "positions": x0, "velocities": u0,
                               "multipliers": [0.0] * (n - 1)})
                continue
            steps, ds, inters, sim = model
            P = [0.0] * (n - 1)
            k = 0
            while sim.hasNextEvent() and k < steps:
                sim.computeOneStep()
                for i, it in enumerate(inters):
                    P[i] += float(it.lambda_(1)[0])
                sim.nextStep()
                k += 1
            frames.append({
                "t": ts,
                "positions": [float(d.q()[0]) for d in ds],
                "velocities": [float(d.velocity()[0]) for d in ds],
                "multipliers": [p / n for p in P],
                "clusters": common.clusters_from(common.contacts([float(d.q()[0]) for d in ds],
                                                                 2.0 * r)),
            })
        return frames

    frames, timing = common.timed(step_all, setup=build)
    common.write(a.out, frames, peer, "h=%g" % a.h, "solver's own dynamics", timing)


if __name__ == "__main__":
    main()
