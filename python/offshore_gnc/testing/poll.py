"""Waiting for a condition in a test: the one poll-until loop the Python tests and the rostest checkers share."""
import contextlib
import time


def wait_until(pred, timeout, step=0.1, lock=None):
    """pred()'s value as soon as it is truthy (checked every `step` seconds of wall time, under `lock` when one is
    given: the condition reads what subscriber callbacks write); else pred() once more at the deadline. A pred that
    returns what it found (the first matching message) makes this a wait-for-it."""
    guard = lock if lock is not None else contextlib.nullcontext()
    deadline = time.time() + timeout
    while time.time() < deadline:
        with guard:
            found = pred()
        if found:
            return found
        time.sleep(step)
    with guard:
        return pred()
