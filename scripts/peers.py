#!/usr/bin/env python3
"""Times the peers' isotonic regression on the inputs `sticky bench` wrote.

Each argument is a file of little-endian f64 values (one scene each, fresh
data per repetition). Prints `scipy NS_PER_PARTICLE` and `sklearn
NS_PER_PARTICLE` (median over the files), or `NAME skipped: REASON`.
Installs scipy and scikit-learn with pip when they are absent. Each peer
runs once untimed first (on a reversed copy of the first input), as
`sticky bench` warms its own methods up; the allocator setting comes from
the environment `sticky bench` runs this script in.
"""
import subprocess
import sys
import time


def ensure(module, package):
    try:
        __import__(module)
        return True
    except ImportError:
        r = subprocess.run([sys.executable, "-m", "pip", "install", "-q", package],
                           capture_output=True, text=True)
        if r.returncode != 0:
            return False
        try:
            __import__(module)
            return True
        except ImportError:
            return False


def main():
    files = sys.argv[1:]
    have_np = ensure("numpy", "numpy")
    if not have_np:
        print("scipy skipped: numpy unavailable")
        print("sklearn skipped: numpy unavailable")
        return
    import numpy as np
    data = [np.fromfile(f, dtype="<f8") for f in files]
    if ensure("scipy", "scipy"):
        try:
            from scipy.optimize import isotonic_regression
            isotonic_regression(data[0][::-1].copy())  # warm-up, untimed
            ts = []
            for y in data:
                t0 = time.perf_counter_ns()
                isotonic_regression(y)
                ts.append((time.perf_counter_ns() - t0) / len(y))
            print("scipy %.3f" % sorted(ts)[len(ts) // 2])
        except Exception as e:  # noqa: BLE001 - report, do not crash
            print("scipy skipped: %s" % e)
    else:
        print("scipy skipped: cannot install scipy")
    if ensure("sklearn", "scikit-learn"):
        from sklearn.isotonic import isotonic_regression as skl
        skl(data[0][::-1].copy())  # warm-up, untimed
        ts = []
        for y in data:
            t0 = time.perf_counter_ns()
            skl(y)
            ts.append((time.perf_counter_ns() - t0) / len(y))
        print("sklearn %.3f" % sorted(ts)[len(ts) // 2])
    else:
        print("sklearn skipped: cannot install scikit-learn")


if __name__ == "__main__":
    main()
