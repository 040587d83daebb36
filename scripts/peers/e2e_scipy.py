#!/usr/bin/env python3
"""scipy's own file -> answer -> file pipeline, the peer of `sticky run` end to end
(issue 13): read the columns `position,velocity` of a particle file, project
x0 + t u0 onto K = {x_{i+1} - x_i >= 2r} with scipy.optimize.isotonic_regression
(on the translated positions x - 2r i), write the positions.

    e2e_scipy.py csv IN.csv OUT.csv --t 1 --two-r 0.002   # numpy.loadtxt ... numpy.savetxt
    e2e_scipy.py npy IN.npy OUT.npy --t 1 --two-r 1/32    # numpy.load ... numpy.save

Everything in f64 (the peer's arithmetic); the timing is the whole process
(`sticky bench --e2e`). When STICKY_PEAK_RSS_FILE is set, the script writes
its own peak resident memory (kB, VmHWM of /proc/self/status, else
ru_maxrss) into that file at the end, as the `sticky` binary does.
"""
import argparse
import os
import resource
from fractions import Fraction

import numpy as np
from scipy.optimize import isotonic_regression


def main():
    p = argparse.ArgumentParser()
    p.add_argument("format", choices=["csv", "npy"])
    p.add_argument("input")
    p.add_argument("output")
    p.add_argument("--t", default="1")
    p.add_argument("--two-r", required=True)
    a = p.parse_args()
    t = float(Fraction(a.t))
    two_r = float(Fraction(a.two_r))
    if a.format == "csv":
        data = np.loadtxt(a.input, delimiter=",", skiprows=1)
    else:
        data = np.load(a.input)
    shift = two_r * np.arange(data.shape[0])
    y = data[:, 0] + t * data[:, 1] - shift
    x = isotonic_regression(y).x + shift
    if a.format == "csv":
        np.savetxt(a.output, x, header="position", comments="")
    else:
        np.save(a.output, x)
    peak_to = os.environ.get("STICKY_PEAK_RSS_FILE")
    if peak_to:
        with open(peak_to, "w") as f:
            f.write(f"{peak_kib()}\n")


def peak_kib():
    """This process's peak resident memory in kB."""
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1])
    except OSError:
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss


if __name__ == "__main__":
    main()
