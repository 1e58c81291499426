"""A campaign or a falsification watched from the console (no Textual).

**Outside the console's process.** The search runs as its own command — ``orccad campaign
FILE --spec SPEC --db DB`` or ``orccad falsify FILE --spec SPEC --property P --study STUDY`` —
in a child process (:class:`SearchProcess`) with its own worker pool, so neither the pool nor
the runs ever share Textual's event loop or process. The console reads what the command
commits as each run ends (the campaign's SQLite database through
:class:`~orccad_app.campaign.store.CampaignStore`, the falsification's optuna study) at a fixed
rate, and stops it as Ctrl-C does (SIGINT): every finished run stays recorded and ``--resume``
continues. Opening an existing database reads it the same way, with no process.

**What is shown** is computed by the campaign package's own functions on the runs recorded so
far: :func:`~orccad_app.campaign.stats.estimates` (every outcome's and property's probability
with its Clopper–Pearson interval), each property's robustness as a :func:`histogram`, and the
:class:`Candidate` runs closest to violation (the smallest robustness per property, then the
runs that did not end ``done``), each with the :class:`~orccad_app.campaign.setting.RunSetting`
that replays it.
"""

from __future__ import annotations

import contextlib
import math
import os
import signal
import sqlite3
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from orccad_app.diagnostics import OrccadError

__all__ = ["SearchProcess", "Bin", "histogram", "Candidate", "CampaignSnapshot",
           "read_campaign", "FalsifySnapshot", "read_study", "default_spec", "default_db",
           "check_database", "HISTOGRAM_BINS", "CLOSEST", "LOCK_WAIT_S"]

HISTOGRAM_BINS = 12
"""Bins of each robustness histogram."""
CLOSEST = 5
"""Runs listed per property as the closest to violation."""
STOP_WAIT_S = 20.0
"""How long :meth:`SearchProcess.stop` waits for the command to record its finished runs and
exit after SIGINT before it terminates it."""


def default_spec(mission_file: str) -> str | None:
    """The campaign spec shipped beside ``mission_file`` (``arm_pid.orc`` →
    ``arm_pid.campaign.toml``), if there is one."""
    path = Path(mission_file)
    spec = path.with_name(f"{path.stem}.campaign.toml")
    return str(spec) if spec.is_file() else None


def default_db(spec: str) -> str:
    """``orccad campaign``'s default database for ``spec``: its name with ``.db`` instead of
    ``.campaign.toml``'s ``.toml``, in the current folder."""
    name = Path(spec).name
    return (name[:-5] if name.endswith(".toml") else name) + ".db"


class SearchProcess:
    """``orccad ARGS…`` in a child process of its own session (a Ctrl-C in the terminal does
    not reach it), its standard error kept in a temporary file for the message of a failure.

    :param args: the command's arguments after ``orccad`` (``["campaign", FILE, …]``).
    """

    def __init__(self, args: list[str]) -> None:
        self.args = list(args)
        self._stderr = tempfile.TemporaryFile(prefix="orccad-tui-search-")
        self.process = subprocess.Popen(
            [sys.executable, "-m", "orccad_app", *self.args], stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL, stderr=self._stderr, start_new_session=True)

    @classmethod
    def campaign(cls, file: str, spec: str, db: str, *, runs: int | None = None,
                 workers: int | None = None, resume: bool = False) -> SearchProcess:
        """``orccad campaign FILE --spec SPEC --db DB [--runs N] [--workers N] [--resume]``."""
        args = ["campaign", file, "--spec", spec, "--db", db]
        args += ["--runs", str(runs)] if runs is not None else []
        args += ["--workers", str(workers)] if workers is not None else []
        return cls(args + (["--resume"] if resume else []))

    @classmethod
    def falsify(cls, file: str, spec: str, prop: str, study: str, *, budget: int,
                workers: int | None = None, resume: bool = False,
                trace: str | None = None) -> SearchProcess:
        """``orccad falsify FILE --spec SPEC --property P --study STUDY --budget N …``."""
        trace = trace or str(Path(study).with_suffix(".csv"))
        args = ["falsify", file, "--spec", spec, "--property", prop, "--study", study,
                "--budget", str(budget), "--trace", trace]
        args += ["--workers", str(workers)] if workers is not None else []
        return cls(args + (["--resume"] if resume else []))

    @property
    def returncode(self) -> int | None:
        """The exit status once the command has ended, else ``None``."""
        return self.process.poll()

    @property
    def running(self) -> bool:
        return self.returncode is None

    def error_text(self) -> str:
        """What the command wrote on its standard error (its ``orccad: error`` message)."""
        self._stderr.seek(0)
        return self._stderr.read().decode("utf-8", "replace").strip()

    def stop(self, wait_s: float = STOP_WAIT_S) -> int:
        """Interrupt the command as Ctrl-C does (its finished runs stay recorded; ``--resume``
        continues) and wait for it; terminate, then kill it if it does not end in
        ``wait_s``. Its exit status."""
        if self.running:
            self.process.send_signal(signal.SIGINT)
            try:
                self.process.wait(wait_s)
            except subprocess.TimeoutExpired:
                self.process.terminate()
                try:
                    self.process.wait(5.0)
                except subprocess.TimeoutExpired:
                    os.killpg(self.process.pid, signal.SIGKILL)
                    self.process.wait()
        return self.process.returncode

    def close(self) -> None:
        """Stop the command if it runs, and drop its standard error."""
        self.stop()
        self._stderr.close()


@dataclass(frozen=True)
class Bin:
    """One bar of a histogram: the values in ``[low, high)`` (the last bin includes
    ``high``)."""

    low: float
    high: float
    count: int


def histogram(values: list[float], bins: int = HISTOGRAM_BINS) -> list[Bin]:
    """``values`` counted in ``bins`` equal bins over their range (one bin when they are all
    equal; none without values)."""
    finite = sorted(v for v in values if math.isfinite(v))
    if not finite:
        return []
    low, high = finite[0], finite[-1]
    if high == low:
        return [Bin(low, high, len(finite))]
    width = (high - low) / bins
    counts = [0] * bins
    for value in finite:
        counts[min(bins - 1, int((value - low) / width))] += 1
    return [Bin(low + i * width, low + (i + 1) * width, n) for i, n in enumerate(counts)]


@dataclass(frozen=True)
class Candidate:
    """A run worth replaying: the closest to violating ``what`` (a property, with its
    ``robustness``), or one that did not end ``done`` (``what`` its outcome)."""

    run: int
    what: str
    robustness: float | None
    outcome: str
    setting: Any
    """The :class:`~orccad_app.campaign.setting.RunSetting` that replays it."""


@dataclass
class CampaignSnapshot:
    """A campaign's database as read now (see the module docstring)."""

    db: str
    file: str
    mission: str
    spec_text: str
    runs: int
    """Runs recorded."""
    limit: int
    """Runs the campaign asks for (the spec's ``runs`` unless told otherwise)."""
    confidence: float
    estimates: dict[str, dict[str, Any]] = field(default_factory=dict)
    histograms: dict[str, list[Bin]] = field(default_factory=dict)
    candidates: list[Candidate] = field(default_factory=list)
    crashed: int = 0


SQLITE_HEADER = b"SQLite format 3\x00"
"""The first 16 bytes of every SQLite database file."""
LOCK_WAIT_S = 2.0
"""How long a read waits for another program's lock on the database [s]."""


def check_database(path: str, what: str) -> bool:
    """Refuse, with one located message, a file the console cannot read as ``what`` (``"a
    campaign database"``): missing, not a regular file (a FIFO would block the read), not
    SQLite (its header), locked by another program past :data:`LOCK_WAIT_S`, or unreadable
    as a database. Whether the file holds anything (``False``: an empty file). Nothing is
    written to the file or beside it (:func:`~orccad_app.campaign.store.connect_read_only`)."""
    from orccad_app.campaign.store import connect_read_only
    from orccad_app.pipeline import require_regular_file

    require_regular_file(path)
    try:
        with open(path, "rb") as handle:
            header = handle.read(len(SQLITE_HEADER))
    except OSError as error:
        raise OrccadError(f"{path}: cannot read: {error.strerror or error}") from None
    if not header:
        return False
    if header != SQLITE_HEADER:
        raise OrccadError(f"{path}: not an SQLite database (it does not begin with SQLite's "
                          f"header), so not {what}")
    try:
        with contextlib.closing(connect_read_only(path, LOCK_WAIT_S)) as db:
            db.execute("SELECT count(*) FROM sqlite_master").fetchone()
    except sqlite3.OperationalError as error:
        if "locked" in str(error) or "busy" in str(error):
            raise OrccadError(f"{path}: locked by another program ({error}): open it again "
                              "once that program has let it go") from None
        raise OrccadError(f"{path}: cannot be read as {what} ({error})") from None
    except (sqlite3.DatabaseError, UnicodeDecodeError) as error:  # SQLite's message quotes
        raise OrccadError(f"{path}: not {what}, or damaged ({_reason(error)})") from None
    return True


def _reason(error: BaseException) -> str:
    """An error's first line, short (a damaged file's bytes may be in it)."""
    text = (str(error).strip().splitlines() or [""])[0]
    return f"{type(error).__name__}: {text[:160]}"


def read_campaign(db: str, confidence: float = 0.95, limit: int | None = None
                  ) -> CampaignSnapshot:
    """What campaign database ``db`` holds now; refuses a file that is not one
    (:class:`OrccadError`, see :func:`check_database`; an empty file too)."""
    from orccad_app.campaign.adapter import CRASHED
    from orccad_app.mission.result import MissionStatus
    from orccad_app.campaign.spec import parse_spec
    from orccad_app.campaign.stats import estimates, summarize
    from orccad_app.campaign.store import CampaignStore

    if not check_database(db, "a campaign database"):
        raise OrccadError(f"{db}: an empty file, not a campaign database (no campaign has "
                          "written to it)")
    try:
        store = CampaignStore(db, read_only=True)
        try:
            meta = store.meta()
            if "spec" not in meta or "file" not in meta:
                raise OrccadError(f"{db}: not a campaign database (no campaign recorded in "
                                  "it)")
            records = store.records()
        finally:
            store.close()
    except (sqlite3.Error, ValueError, KeyError, TypeError) as error:  # the file's rows
        raise OrccadError(f"{db}: a damaged campaign database ({_reason(error)})") from None
    if limit is None:
        try:
            limit = parse_spec(meta["spec"]).runs
        except OrccadError:
            limit = len(records)
    summary = summarize(records, closest=CLOSEST)
    by_index = {r.index: r for r in records}
    histograms = {name: histogram([value for r in records if name in r.properties
                                   if (value := r.properties[name].robustness) is not None])
                  for name in summary["robustness"]}
    candidates = [Candidate(w["run"], name, w["robustness"], by_index[w["run"]].outcome,
                            by_index[w["run"]].setting)
                  for name, worst in summary["closest_to_violation"].items() for w in worst]
    candidates += [Candidate(r.index, r.outcome, None, r.outcome, r.setting)
                   for r in records if r.status not in (MissionStatus.DONE, CRASHED)][:2 * CLOSEST]
    return CampaignSnapshot(db, meta["file"], meta.get("mission", ""), meta["spec"],
                            len(records), max(limit, len(records)), confidence,
                            estimates(records, confidence) if records else {}, histograms,
                            candidates, sum(1 for r in records if r.status == CRASHED))


@dataclass
class FalsifySnapshot:
    """A falsification's optuna study as read now: per finished trial its score (the
    property's robustness; :data:`~orccad_app.campaign.falsify.UNDEFINED` when the run does
    not define it), the best score, the first violating trial and the trials closest to
    violation with the settings that replay them."""

    study: str
    prop: str
    trials: int
    budget: int
    best: float | None
    first_violation: int | None
    history: list[float] = field(default_factory=list)
    candidates: list[Candidate] = field(default_factory=list)
    histogram: list[Bin] = field(default_factory=list)


def _has_studies(path: str) -> bool:
    """Whether SQLite file ``path`` has optuna's tables yet (``False``: no table at all, a
    study being created); a file with other tables, or not SQLite, is refused."""
    from orccad_app.campaign.store import connect_read_only

    if not check_database(path, "an optuna study database"):
        return False
    try:
        with contextlib.closing(connect_read_only(path, LOCK_WAIT_S)) as db:
            tables = {row[0] for row in db.execute("SELECT name FROM sqlite_master")}
    except (sqlite3.DatabaseError, UnicodeDecodeError) as error:
        raise OrccadError(f"{path}: not an optuna study database, or damaged "
                          f"({_reason(error)})") from None
    if tables and "studies" not in tables:
        raise OrccadError(f"{path}: not an optuna study database (no table studies)")
    return bool(tables)


def _read_only_url(path: str) -> str:
    """SQLAlchemy's URL of SQLite file ``path`` opened read-only, any characters in it (the
    database part is percent-decoded once by SQLAlchemy, then read as a URI by SQLite)."""
    from urllib.parse import quote

    return f"sqlite:///{quote(Path(path).resolve().as_uri(), safe='/')}?mode=ro&uri=true"


def read_study(study: str, spec_path: str, prop: str, until_s: float, *, budget: int,
               run_seed: int = 0) -> FalsifySnapshot:
    """The trials of the falsification of ``prop`` kept in SQLite file ``study``
    (``orccad falsify --study``); each candidate's setting is rebuilt from the values the
    trial ran with (:func:`~orccad_app.campaign.setting.build_setting`), as the command
    replays its worst one."""
    from orccad_app.campaign.spec import load_spec

    try:
        import optuna
    except ImportError:
        raise OrccadError("falsification needs optuna: pip install 'orccad[falsify]'") from None
    spec = load_spec(spec_path)
    if not os.path.lexists(study) or not _has_studies(study):  # not created yet, or empty
        return FalsifySnapshot(study, prop, 0, budget, None, None)
    optuna.logging.set_verbosity(optuna.logging.WARNING)
    try:
        return _read_trials(optuna, study, spec, prop, until_s, budget, run_seed)
    except OrccadError:
        raise
    except Exception as error:  # noqa: BLE001 - optuna's or SQLAlchemy's, on a file not theirs
        raise OrccadError(f"{study}: not an optuna study database that can be read "
                          f"({_reason(error)})") from None


def _read_trials(optuna: Any, study: str, spec: Any, prop: str, until_s: float, budget: int,
                 run_seed: int) -> FalsifySnapshot:
    """:func:`read_study` once the file is known to hold optuna's tables."""
    from orccad_app.campaign.falsify import UNDEFINED
    from orccad_app.campaign.setting import build_setting

    # read-only, no table created: a reader that creates optuna's tables races the command
    # creating them in the same file, which then fails ("table studies already exists")
    storage = optuna.storages.RDBStorage(_read_only_url(study), skip_table_creation=True)
    names = [name for name in optuna.get_all_study_names(storage)
             if f"-{prop}-" in name]
    if not names:
        return FalsifySnapshot(study, prop, 0, budget, None, None)
    loaded = optuna.load_study(study_name=names[-1], storage=storage)
    done = [(t, float(t.value)) for t in loaded.get_trials(deepcopy=False)
            if t.value is not None and "values" in t.user_attrs]
    history = [value for _, value in done]
    defined = [(t, value) for t, value in done if value < UNDEFINED]
    ranked = sorted(defined, key=lambda scored: (scored[1], scored[0].number))[:CLOSEST]
    candidates = [Candidate(t.number, prop, value, "violated" if value < 0 else "holds",
                            build_setting(spec, t.number, run_seed, until_s,
                                          t.user_attrs["values"])) for t, value in ranked]
    first = next((t.number for t, value in done if value < 0), None)
    return FalsifySnapshot(study, prop, len(done), max(budget, len(done)),
                           min(value for _, value in defined) if defined else None, first,
                           history, candidates, histogram([value for _, value in defined]))
