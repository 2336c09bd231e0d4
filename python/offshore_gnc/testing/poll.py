"""Waiting for a condition in a test: the one poll-until loop the Python tests and the rostest checkers share."""
import contextlib
import time


def wait_until(pred, timeout, step=0.1, lock=None):
    """True as soon as pred() holds (checked every `step` seconds, under `lock` when one is given: the condition
    reads what subscriber callbacks write); else pred() once more at the deadline."""
    guard = lock if lock is not None else contextlib.nullcontext()
    deadline = time.time() + timeout
    while time.time() < deadline:
        with guard:
            if pred():
                return True
        time.sleep(step)
    with guard:
        return bool(pred())
