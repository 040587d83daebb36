"""Ctrl-C during long work: KeyboardInterrupt arrives at once and the worker
thread stops (the library polls the interrupt flag), instead of running on in
the background (issue 29, "Inputs"; issue 27: "Ctrl-C interrupts a long run").

SIGINT is sent by `_thread.interrupt_main()` from a timer, as Ctrl-C would.
The worker is the Rust thread named `sticky-work`; it is seen in
/proc/self/task (Linux only: the test skips elsewhere).
"""

import _thread
import os
import threading
import time

import pytest

import sticky

TASKS = "/proc/self/task"

pytestmark = pytest.mark.skipif(
    not os.path.isdir(TASKS), reason="needs /proc/self/task (Linux)"
)


def workers():
    """The number of live `sticky-work` threads of this process."""
    count = 0
    for task in os.listdir(TASKS):
        try:
            with open(f"{TASKS}/{task}/comm") as f:
                count += f.read().strip() == "sticky-work"
        except OSError:
            pass  # the thread ended while we looked
    return count


def hostile(n):
    """The hostile scene of issue 29: small denominators 1 … n, a huge
    common one; its event history takes minutes at n = 20,000."""
    return sticky.Scene(
        [3 * i for i in range(n)],
        [f"{(-1) ** i}/{i + 1}" for i in range(n)],
        "1/2",
    )


def interrupt_during(call, after=0.3):
    """Runs `call` and sends SIGINT after `after` seconds; returns the
    seconds from the signal to KeyboardInterrupt and the number of workers
    alive when the signal was sent."""
    seen = {}

    def fire():
        seen["workers"] = workers()
        seen["at"] = time.monotonic()
        _thread.interrupt_main()

    timer = threading.Timer(after, fire)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            call()
            # Finished before the signal: wait for it (the test then fails
            # on `workers` below, not here).
            time.sleep(10)
    finally:
        timer.cancel()
    return time.monotonic() - seen["at"], seen["workers"]


def wait_until_no_worker(limit):
    """Seconds until no `sticky-work` thread is left (at most `limit`)."""
    start = time.monotonic()
    while workers() and time.monotonic() - start < limit:
        time.sleep(0.02)
    return time.monotonic() - start


def test_events_stop_on_ctrl_c():
    scene = hostile(20_000)
    delay, busy = interrupt_during(scene.events)
    assert busy == 1, "events() had ended before the signal: the test proves nothing"
    assert delay < 1.0, f"KeyboardInterrupt came {delay:.2f} s after SIGINT"
    # The merge polls the flag at every collision instant: the worker ends
    # within a few instants, not after the minutes the whole history takes.
    left = wait_until_no_worker(5.0)
    assert workers() == 0, f"the worker still runs {left:.1f} s after Ctrl-C"
    # A second call right after is not slowed by a worker left behind.
    start = time.monotonic()
    assert len(hostile(50).events()) > 0
    assert time.monotonic() - start < 2.0


def test_claims_stop_on_ctrl_c():
    delay, busy = interrupt_during(sticky.claims)
    assert busy == 1, "claims() had ended before the signal: the test proves nothing"
    assert delay < 1.0, f"KeyboardInterrupt came {delay:.2f} s after SIGINT"
    # The ledger stops between two claims (the whole run takes a minute).
    left = wait_until_no_worker(20.0)
    assert workers() == 0, f"the ledger still runs {left:.1f} s after Ctrl-C"


def test_state_on_the_general_path_stops_on_ctrl_c():
    # The hostile scene takes neither the dyadic nor the streaming path:
    # `blockwise::state_at`, a few seconds at this size. The signal comes
    # early, where the work guard's lcm and the free flight's shift once ran
    # unpolled. "Stopped, not finished" is judged against the whole call
    # timed on this machine just before (a load-independent bound: a fixed
    # wall-time limit fails on a busy machine).
    timed, scene = hostile(300_000), hostile(300_000)
    start = time.monotonic()
    timed.state(1)
    whole = time.monotonic() - start
    delay, busy = interrupt_during(lambda: scene.state(1), after=0.1)
    assert busy == 1, "state() had ended before the signal: the test proves nothing"
    left = wait_until_no_worker(whole)
    assert workers() == 0, f"the worker still runs {left:.2f} s after Ctrl-C"
    stopped = 0.1 + delay + left
    assert stopped < whole / 2, (
        f"the worker ended {stopped:.2f} s after the call began, "
        f"against {whole:.2f} s for the whole call: it ran on instead of stopping"
    )
