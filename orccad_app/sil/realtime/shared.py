"""The shared memory of the real-time controller: robot ports and Module-Task mirrors.

One file under ``/dev/shm`` (a temporary directory where there is none), mapped by the plant
server and by the controller (``orccad_app/sil/c/orccad_io_shm.c`` holds the same layout), as
8-byte words:

- a header of 8 words (word 1: the instant of the run's t = 0 on ``CLOCK_MONOTONIC`` [ns]);
- per robot port of the table, ``[seq, v0 … v7]``: a sensor written by the plant server, an
  actuator by the controller, each under a sequence lock (odd ``seq``: being written; 0:
  never written);
- per Module-Task, its mirror ``[seq, released, overruns, misses, events, lateness count,
  response max [ns] (double), unused]`` then its output slots ``[present, v0 … v7]``;
- per Module-Task, a ring of its last release latenesses [ns] (doubles);
- a ring of the automaton task's last :data:`REACTION_RING` reactions, each the words of its
  request then of its reply (``orccad_automaton.h``); header word 2 counts those published;
- a ring of the Module-Tasks' last :data:`JOB_RING` job records (:class:`JobRecord`, 8 words
  each), written only while header word 3 is 1 (:meth:`SharedMemory.want_jobs`: a trace
  observes the run); header word 4 counts those published.
"""

from __future__ import annotations

import mmap
import os
import tempfile
from dataclasses import dataclass

import numpy as np

from orccad_app.sil.generate.layout import MAX_DIM, MAX_PORTS

__all__ = ["SharedMemory", "Mirror", "JobRecord", "JobRecords", "LATENESS_RING", "REACTION_RING",
           "JOB_RING", "ReactionsLost"]

HEADER_WORDS = 8
ROBOT_WORDS = 1 + MAX_DIM
MODULE_HEAD = 8
MODULE_WORDS = MODULE_HEAD + MAX_PORTS * (1 + MAX_DIM)
LATENESS_RING = 16384
REACTION_RING = 4096
JOB_RING = 16384
"""Job records the ring holds: over 6 s of arm_pid's jobs (2600 a second), far beyond a
plant server's stall; 1 MiB of shared memory, touched only by a traced run."""
JOB_WORDS = 8
_OVERRUN, _MISSED = 1, 2


class ReactionsLost(Exception):
    """The automaton task published more reactions than the ring holds since the last read."""


@dataclass(frozen=True)
class JobRecord:
    """One job of a Module-Task as the controller measured it (``orc_io_job``), or one of its
    releases skipped (an overrun); instants [ns] from the run's t = 0, -1 where not reached.

    :param module: the Module-Task's index in the module table.
    :param job: the job's index (0-based, over the run); of an overrun, the unfinished job's.
    :param release_ns: its release (of an overrun: the release skipped).
    :param start_ns: its compute began.
    :param compute_end_ns: its compute ended.
    :param finish_ns: its outputs written (-1: aborted, its Module-Task killed).
    :param missed: it finished after its deadline (the period).
    :param overrun: this is a skipped release, not a job.
    """

    module: int
    job: int
    release_ns: int
    start_ns: int
    compute_end_ns: int
    finish_ns: int
    missed: bool
    overrun: bool


@dataclass(frozen=True)
class JobRecords:
    """The job records published since the last read, oldest first, and how many were
    overwritten in the ring before they could be read."""

    records: list[JobRecord]
    lost: int


@dataclass(frozen=True)
class Mirror:
    """One read of a Module-Task's mirror."""

    seq: int
    released: int
    overruns: int
    misses: int
    events: int
    lateness_count: int
    response_max_ns: float
    outputs: np.ndarray
    """Rows ``[present, v0 … v7]``, one per output slot."""


class SharedMemory:
    """The mapped file (see the module docstring) for ``robot_ports`` ports, ``modules``
    Module-Tasks and reactions of ``reaction_words`` words; removed by :meth:`close`."""

    def __init__(self, robot_ports: int, modules: int, reaction_words: int = 0) -> None:
        self.robot_ports, self.modules = robot_ports, modules
        self.reaction_words = reaction_words
        words = (HEADER_WORDS + robot_ports * ROBOT_WORDS + modules * MODULE_WORDS
                 + modules * LATENESS_RING + REACTION_RING * reaction_words
                 + JOB_RING * JOB_WORDS)
        where = "/dev/shm" if os.path.isdir("/dev/shm") else None
        fd, self.path = tempfile.mkstemp(prefix="orccad-sil-", dir=where)
        try:
            os.ftruncate(fd, words * 8)
            self._map = mmap.mmap(fd, words * 8)
        finally:
            os.close(fd)
        self.ints = np.frombuffer(self._map, dtype=np.int64)
        self.floats = np.frombuffer(self._map, dtype=np.float64)
        self._robot = HEADER_WORDS
        self._modules = self._robot + robot_ports * ROBOT_WORDS
        self._rings = self._modules + modules * MODULE_WORDS
        self._reactions = self._rings + modules * LATENESS_RING
        self._jobs = self._reactions + REACTION_RING * reaction_words
        self._read_reactions = 0
        self._read_jobs = 0

    def set_epoch(self, monotonic_ns: int) -> None:
        """The instant of t = 0 [ns, CLOCK_MONOTONIC]."""
        self.ints[1] = monotonic_ns

    def write_port(self, k: int, values: np.ndarray) -> None:
        """Write robot port ``k`` (a sensor) under its sequence lock."""
        at = self._robot + k * ROBOT_WORDS
        data = np.asarray(values, dtype=float).reshape(-1)
        self.ints[at] += 1
        self.floats[at + 1:at + 1 + data.size] = data
        self.ints[at] += 1

    def read_port(self, k: int, dim: int) -> tuple[int, np.ndarray | None]:
        """(its sequence, the values) of robot port ``k`` (an actuator); ``None`` before
        the first write."""
        at = self._robot + k * ROBOT_WORDS
        while True:
            before = int(self.ints[at])
            values = self.floats[at + 1:at + 1 + dim].copy()
            if before == int(self.ints[at]) and not before & 1:
                return before, (values if before else None)

    def mirror(self, m: int) -> Mirror:
        """A consistent read of Module-Task ``m``'s mirror."""
        at = self._modules + m * MODULE_WORDS
        while True:
            before = int(self.ints[at])
            head = self.ints[at:at + MODULE_HEAD].copy()
            response = float(self.floats[at + 6])
            outputs = self.floats[at + MODULE_HEAD:at + MODULE_WORDS].copy()
            if before == int(self.ints[at]) and not before & 1:
                return Mirror(before, int(head[1]), int(head[2]), int(head[3]), int(head[4]),
                              int(head[5]), response, outputs.reshape(MAX_PORTS, 1 + MAX_DIM))

    def seq(self, m: int) -> int:
        """The sequence of Module-Task ``m``'s mirror (it changes with every job)."""
        return int(self.ints[self._modules + m * MODULE_WORDS])

    def events(self, m: int) -> int:
        """The events Module-Task ``m`` has fired (one aligned word: read whole)."""
        return int(self.ints[self._modules + m * MODULE_WORDS + 4])

    def latenesses_ns(self, m: int) -> np.ndarray:
        """The release latenesses of Module-Task ``m`` still in its ring [ns]."""
        count = int(self.ints[self._modules + m * MODULE_WORDS + 5])
        at = self._rings + m * LATENESS_RING
        return self.floats[at:at + min(count, LATENESS_RING)].copy()

    def reactions(self) -> list[bytes]:
        """The reactions published since the last call, oldest first, each its words as
        bytes; raises :class:`ReactionsLost` when the ring was overrun."""
        count = int(self.ints[2])
        first = self._read_reactions
        if count - first > REACTION_RING:
            raise ReactionsLost(count - first - REACTION_RING)
        size = self.reaction_words
        found = []
        for number in range(first, count):
            at = self._reactions + (number % REACTION_RING) * size
            found.append(self.ints[at:at + size].tobytes())
        if int(self.ints[2]) - first > REACTION_RING:  # overwritten while read
            raise ReactionsLost(int(self.ints[2]) - first - REACTION_RING)
        self._read_reactions = count
        return found

    def want_jobs(self, wanted: bool) -> None:
        """Whether the controller records its jobs' life cycle (:meth:`jobs`) from its next
        release on."""
        self.ints[3] = int(wanted)

    def jobs(self) -> JobRecords:
        """The job records published since the last call, oldest first; those the
        controller overwrote before this read are counted as lost (never raises: a trace
        short of some jobs says so, the run goes on)."""
        count = int(self.ints[4])
        if count == self._read_jobs:
            return JobRecords([], 0)
        first = max(self._read_jobs, count - JOB_RING)
        rows = self.ints[self._jobs:self._jobs + JOB_RING * JOB_WORDS].reshape(JOB_RING,
                                                                                 JOB_WORDS)
        numbers = np.arange(first, count)
        copied = rows[numbers % JOB_RING].copy()
        # a record is intact when the writer had not begun to overwrite its slot by the end
        # of the copy: the writer of record `after` overwrites record `after - JOB_RING`
        after = int(self.ints[4])
        intact = min(count, max(first, after - JOB_RING + 1))
        copied = copied[intact - first:]
        lost = intact - self._read_jobs
        self._read_jobs = count
        records = [JobRecord(int(r[0]), int(r[2]), int(r[3]), int(r[4]), int(r[5]), int(r[6]),
                             bool(r[1] & _MISSED), bool(r[1] & _OVERRUN))
                   for r in copied.tolist()]
        return JobRecords(records, lost)

    def unlink(self) -> None:
        """Remove the file once both sides have mapped it: nothing is left in ``/dev/shm``
        even when a process is killed (the mappings live on until unmapped)."""
        try:
            os.unlink(self.path)
        except FileNotFoundError:
            pass

    def close(self) -> None:
        """Unmap and remove the file."""
        self.ints = np.empty(0, dtype=np.int64)
        self.floats = np.empty(0)
        try:
            self._map.close()
        except BufferError:  # a view still alive: the file goes anyway
            pass
        try:
            os.unlink(self.path)
        except FileNotFoundError:
            pass
