"""Interrupt a call as the task budget's alarm does (SIGALRM raising mid-call), for the
tests of what a half-started worker or program leaves behind."""

import signal

import pytest


class Alarm(Exception):
    """What the alarm raises inside the interrupted call."""


def interrupted(call, seconds: float) -> None:
    """Run ``call()`` with an alarm ``seconds`` in, and assert the alarm cut it short."""
    def ring(signum, frame):
        raise Alarm

    previous = signal.signal(signal.SIGALRM, ring)
    try:
        signal.setitimer(signal.ITIMER_REAL, seconds)
        with pytest.raises(Alarm):
            call()
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
