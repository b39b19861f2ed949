"""Ctrl-C during a render raises KeyboardInterrupt soon, and leaves no thread behind."""

import os
import signal
import threading
import time

import pytest

import lightlab


def os_threads():
    return len(os.listdir("/proc/self/task"))


@pytest.mark.skipif(not os.path.isdir("/proc/self/task"), reason="counts threads in /proc")
def test_ctrl_c_stops_a_render_with_keyboard_interrupt():
    before = os_threads()
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        # Some ten seconds of work in rounds of about one: only the interrupt ends it early.
        lightlab.render("builtin:assignment", spp=1 << 16, width=16, height=12, threads=2)
    assert time.monotonic() - start < 20
    timer.join()
    deadline = time.monotonic() + 5  # rayon's workers exit just after the pool is dropped
    while os_threads() > before and time.monotonic() < deadline:
        time.sleep(0.05)
    assert os_threads() <= before
    # The module still works afterwards.
    assert lightlab.render("builtin:assignment", spp=1, width=8, height=6).spp == 1
