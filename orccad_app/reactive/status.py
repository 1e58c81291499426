"""The run status vocabulary, defined once where it is produced: the reactive layer.

:class:`Status` is the program's status after an instant, as a reaction tree's leaf gives it
and the runtime keeps it (sticky once ``failed`` or ``aborted``). :class:`MissionStatus` is how
a run of that program ended: the automaton's own word when it terminated, else what its
status means at the horizon (:func:`at_horizon`).

Both are :class:`enum.StrEnum`: a member *is* its word, so reports, traces, JSON and the
campaign database read ``"done"`` as before, and a word read back (a database row, a C
controller's reply) compares equal to its member. This module is the only one that writes
these words (``tests/test_seams.py`` counts them everywhere else).
"""

from __future__ import annotations

import enum

__all__ = ["Status", "MissionStatus", "at_horizon"]


class Status(enum.StrEnum):
    """The program's status after an instant."""

    RUNNING = "running"
    """The program goes on."""
    DONE = "done"
    """The program terminated normally."""
    FAILED = "failed"
    """An uncaught type-2 exception (sticky: the program may still run an ``on fatal``
    block)."""
    ABORTED = "aborted"
    """A type-3 exception (sticky: its ``on fatal`` recovery, if any, may still run)."""


class MissionStatus(enum.StrEnum):
    """How a mission run ended (its value is the word of reports and traces)."""

    DONE = Status.DONE.value
    """The mission ended normally."""
    FAILED = Status.FAILED.value
    """An uncaught type-2 exception, or a run-time failure (deadlock, diverging plant,
    failing module)."""
    ABORTED = Status.ABORTED.value
    """A type-3 exception, its ``on fatal`` recovery (if any) finished; or Ctrl-C, SIGTERM."""
    RECOVERING = "recovering"
    """A type-3 exception with the ``on fatal`` recovery still running at the horizon (the
    reason names the exception; where the recovery would end is unknown)."""
    TIMEOUT = "timeout"
    """Still running at the horizon."""


def at_horizon(status: Status, finished: bool) -> MissionStatus:
    """How a run ends when it stops with the program's status ``status``: the automaton's own
    word once it has ``finished`` (reached its terminal state); otherwise ``recovering`` for
    an ``aborted`` program (its ``on fatal`` recovery cut), ``failed`` for a failed one and
    ``timeout`` for one still running."""
    if finished:
        return MissionStatus(status)
    if status == Status.ABORTED:
        return MissionStatus.RECOVERING
    if status == Status.FAILED:
        return MissionStatus.FAILED
    return MissionStatus.TIMEOUT
