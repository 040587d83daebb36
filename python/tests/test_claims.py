"""sticky.claims(): the ledger from Python, and Ctrl-C during a long run.

The ledger has a fixed cost (about 40 s of one core at the smallest
budget), so it runs once here.
"""

import os
import signal
import threading
import time

import pytest

import sticky


def test_ctrl_c_interrupts_a_long_run():
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        sticky.claims(cases=1, max_n=1, scaling_max_n=8)
    # Returned at the next poll after the signal, not at the end of the run.
    assert time.monotonic() - start < 5


def test_the_ledger_as_dicts():
    ledger = sticky.claims(cases=1, max_n=1, scaling_max_n=8)
    ids = [c["id"] for c in ledger]
    assert "prop:proj-micro" in ids
    assert all(c["status"] in {"holds", "counterexample", "not checkable", "identity"} for c in ledger), {c["status"] for c in ledger}
