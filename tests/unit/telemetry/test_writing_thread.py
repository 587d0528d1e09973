"""The writing thread: calls run in the order handed over, and a call's error reaches
the caller (next call and stop) with nothing after it run."""

import threading
import time

import pytest

from rocketsim.telemetry.writing_thread import WritingThread


def test_calls_run_in_order_on_one_other_thread_through_a_bounded_queue():
    ran, threads = [], set()

    def note(k):
        ran.append(k)
        threads.add(threading.get_ident())

    writing = WritingThread("test", depth=3)      # a queue shorter than the calls: submit waits
    for k in range(200):
        writing.submit(note, k)
    assert writing.stop() is None
    assert ran == list(range(200))
    assert threads and threading.get_ident() not in threads
    assert writing.stop() is None                  # again: nothing


def test_an_error_is_raised_at_a_next_call_and_returned_by_stop():
    ran = []

    def fail():
        raise OSError(28, "No space left on device")

    writing = WritingThread("test")
    writing.submit(ran.append, 1)
    writing.submit(fail)
    deadline = time.monotonic() + 10
    with pytest.raises(OSError, match="No space left"):
        while time.monotonic() < deadline:         # until the thread has met the error
            writing.submit(ran.append, 2)
            time.sleep(0.001)
    error = writing.stop()
    assert isinstance(error, OSError) and error.errno == 28
    assert ran == [1]                               # nothing handed over after the error ran
