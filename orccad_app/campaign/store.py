"""The campaign database: one SQLite file, one row per run, written as runs finish.

Schema (docs/campaigns.md gives example queries)::

    campaign(key TEXT PRIMARY KEY, value TEXT)      -- file, mission, digest, spec, ...
    runs(run INTEGER PRIMARY KEY,                   -- the run's index (its setting's draw)
         seed INTEGER, status TEXT, outcome TEXT, reason TEXT,
         sim_time_s REAL, completion_time_s REAL, wall_time_s REAL,
         attempts INTEGER, error TEXT,              -- 2: retried once after a crash
         setting TEXT,                              -- JSON (RunSetting.as_dict)
         replay TEXT)                               -- the orccad run command
    params(run INTEGER, name TEXT, value REAL)      -- the drawn values (RunSetting.values)
    metrics(run INTEGER, name TEXT, value REAL)     -- max(auv.depth), sim_time_s, ...
    properties(run INTEGER, name TEXT, holds INTEGER, robustness REAL)

``status`` is ``done``, ``failed``, ``aborted``, ``timeout`` or ``crashed`` (an internal
error twice: ``error`` holds the traceback's last line). Runs are committed as they come back
to the campaign, those that come back together in one transaction (:meth:`CampaignStore.add_many`),
before anything else is done with them: an interrupted or killed campaign keeps every run it
had received and ``--resume`` runs the others. The database is in WAL mode with
``synchronous=NORMAL``: a commit is not flushed to the disk by itself (SQLite's WAL
guarantees a committed transaction survives the *process* being killed; only a power loss or
an operating-system crash may lose the last ones), which makes a commit cheap enough for
thousands of runs.
"""

from __future__ import annotations

import json
import sqlite3
from pathlib import Path
from typing import Any, Iterator

from orccad_app.campaign.adapter import RUN_STATUSES, PropertyResult, RunRecord
from orccad_app.campaign.setting import RunSetting
from orccad_app.diagnostics import OrccadError

__all__ = ["CampaignStore", "SCHEMA", "COLUMNS", "connect_read_only", "table_names"]

SCHEMA = """
CREATE TABLE IF NOT EXISTS campaign (key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS runs (
    run INTEGER PRIMARY KEY, seed INTEGER NOT NULL, status TEXT NOT NULL,
    outcome TEXT NOT NULL, reason TEXT, sim_time_s REAL, completion_time_s REAL,
    wall_time_s REAL, attempts INTEGER NOT NULL, error TEXT, setting TEXT NOT NULL,
    replay TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS params (run INTEGER NOT NULL, name TEXT NOT NULL, value REAL,
    PRIMARY KEY (run, name));
CREATE TABLE IF NOT EXISTS metrics (run INTEGER NOT NULL, name TEXT NOT NULL, value REAL,
    PRIMARY KEY (run, name));
CREATE TABLE IF NOT EXISTS properties (run INTEGER NOT NULL, name TEXT NOT NULL,
    holds INTEGER, robustness REAL, PRIMARY KEY (run, name));
"""


COLUMNS = {
    "campaign": ("key", "value"),
    "runs": ("run", "seed", "status", "outcome", "reason", "sim_time_s", "completion_time_s",
             "wall_time_s", "attempts", "error", "setting", "replay"),
    "params": ("run", "name", "value"),
    "metrics": ("run", "name", "value"),
    "properties": ("run", "name", "holds", "robustness"),
}
"""The columns of each table, in order (checked when a database is opened)."""

_STATUSES = RUN_STATUSES


def connect_read_only(path: str | Path, timeout_s: float = 5.0) -> sqlite3.Connection:
    """SQLite file ``path`` opened read-only (any characters in its name): nothing is ever
    written to it or beside it, and no write lock is taken that a writer would wait for; a
    lock held by another program is waited for ``timeout_s`` [s]. A WAL database that no
    writer has open (no ``-wal`` or ``-shm`` file beside it) is opened immutable: read-only,
    SQLite would still create both files beside it to read it."""
    uri = Path(path).resolve().as_uri() + "?mode=ro"
    if _wal_without_writer(Path(path)):
        uri += "&immutable=1"
    return sqlite3.connect(uri, uri=True, timeout=timeout_s)


def _wal_without_writer(path: Path) -> bool:
    """Whether regular file ``path`` is an SQLite database in WAL mode (its header's read and
    write versions are 2) with neither ``-wal`` nor ``-shm`` beside it."""
    import os
    import stat

    try:
        if not stat.S_ISREG(os.stat(path).st_mode):
            return False  # never opened here: a FIFO would block
        with open(path, "rb") as handle:
            header = handle.read(20)
    except OSError:
        return False
    return header[:16] == b"SQLite format 3\x00" and header[18:20] == b"\x02\x02" \
        and not any(os.path.lexists(f"{path}{suffix}") for suffix in ("-wal", "-shm"))


def table_names(db: sqlite3.Connection) -> set[str]:
    """The tables of the database ``db`` (SQLite's own ``sqlite_*`` tables left out)."""
    return {str(row[0]) for row in
            db.execute("SELECT name FROM sqlite_master WHERE type = 'table'")
            if not str(row[0]).startswith("sqlite_")}


class CampaignStore:
    """The database of one campaign (see the module docstring)."""

    def __init__(self, path: str | Path, *, read_only: bool = False) -> None:
        """Open (or create) the database at ``path``; ``read_only``: only read an existing
        one (a viewer: it never creates a table in a file, nor takes a write lock the
        campaign writing it would wait for)."""
        self.path = str(path)
        if Path(self.path).exists():
            from orccad_app.pipeline import require_regular_file

            require_regular_file(self.path)  # never a FIFO or a device opened as SQLite
        elif read_only:
            raise OrccadError(f"{self.path}: no such campaign database")
        try:
            if read_only:
                self.db = connect_read_only(self.path)
            else:
                self.db = sqlite3.connect(self.path)
            if not read_only:
                self._refuse_foreign_tables()
                self.db.execute("PRAGMA journal_mode=WAL")
                self.db.execute("PRAGMA synchronous=NORMAL")
                self.db.executescript(SCHEMA)
            self._check_schema()
        except sqlite3.DatabaseError as error:
            raise OrccadError(f"{self.path}: not a campaign database ({error})") from None

    def _refuse_foreign_tables(self) -> None:
        """A database holding tables a campaign does not write (an optuna study, another
        program's file) is refused before anything is written to it (a reader only checks
        the campaign's tables, :meth:`_check_schema`)."""
        foreign = sorted(table_names(self.db) - set(COLUMNS))
        if foreign:
            what = ("an optuna study: it is orccad falsify's --study" if "studies" in foreign
                    else "another program's file")
            shown = ", ".join(foreign[:6]) + (", ..." if len(foreign) > 6 else "")
            self.db.close()
            raise OrccadError(f"{self.path}: not a campaign database (it holds the tables "
                              f"{shown}: {what})")

    def _check_schema(self) -> None:
        """A database of another program (same table names, other columns) is refused."""
        for table, columns in COLUMNS.items():
            found = tuple(row[1] for row in self.db.execute(f"PRAGMA table_info({table})"))
            if not found:
                raise OrccadError(f"{self.path}: not a campaign database (no table {table})")
            if found != columns:
                raise OrccadError(f"{self.path}: not a campaign database (its table {table} "
                                  f"has the columns {', '.join(found)}; a campaign's has "
                                  f"{', '.join(columns)})")

    def close(self) -> None:
        self.db.close()

    # -- identity ------------------------------------------------------------------------

    def meta(self) -> dict[str, str]:
        return {str(k): str(v) for k, v in self.db.execute("SELECT key, value FROM campaign")}

    def start(self, meta: dict[str, str], resume: bool) -> None:
        """Bind the database to a campaign: a new one is stamped with ``meta``; an existing
        one must hold the same campaign (``--resume``), else it is refused."""
        old = self.meta()
        if not old or (not resume and self.count() == 0):  # new, or never got a run
            with self.db:
                self.db.execute("DELETE FROM campaign")
                self.db.executemany("INSERT INTO campaign VALUES (?, ?)", meta.items())
            return
        if not resume:
            raise OrccadError(f"{self.path} already holds a campaign ({self.count()} runs): "
                              f"--resume it, or choose another --db")
        for key in ("digest", "spec", "mission", "until_s"):
            if old.get(key) != meta.get(key):
                raise OrccadError(f"--resume: {self.path} holds another campaign (its {key} "
                                  f"differs); choose another --db")

    # -- runs ----------------------------------------------------------------------------

    def done(self) -> set[int]:
        """Indices of the runs already recorded."""
        return {row[0] for row in self.db.execute("SELECT run FROM runs")}

    def count(self) -> int:
        return self.db.execute("SELECT COUNT(*) FROM runs").fetchone()[0]

    def add(self, record: RunRecord, replay: str) -> None:
        """Record one run (committed at once)."""
        self.add_many([(record, replay)])

    def add_many(self, entries: list[tuple[RunRecord, str]]) -> None:
        """Record runs with their replay commands, in one transaction (committed at once)."""
        if not entries:
            return
        runs, params, metrics, properties = [], [], [], []
        for record, replay in entries:
            index = record.index
            runs.append((index, record.setting.seed, record.status, record.outcome,
                         record.reason, record.sim_time_s,
                         record.metrics.get("completion_time_s"), record.wall_time_s,
                         record.attempts, record.error, json.dumps(record.setting.as_dict()),
                         replay))
            params += [(index, k, v) for k, v in record.setting.values.items()]
            metrics += [(index, k, v) for k, v in record.metrics.items()]
            properties += [(index, k, None if p.holds is None else int(p.holds), p.robustness)
                           for k, p in record.properties.items()]
        with self.db:
            self.db.executemany("INSERT OR REPLACE INTO runs VALUES (?,?,?,?,?,?,?,?,?,?,?,?)",
                                runs)
            self.db.executemany("INSERT OR REPLACE INTO params VALUES (?,?,?)", params)
            self.db.executemany("INSERT OR REPLACE INTO metrics VALUES (?,?,?)", metrics)
            self.db.executemany("INSERT OR REPLACE INTO properties VALUES (?,?,?,?)",
                                properties)

    def records(self, limit: int | None = None) -> list[RunRecord]:
        """The recorded runs with index below ``limit`` (all by default), in index order; a
        row that is not what a campaign writes is refused (located by its run)."""
        try:
            return list(self._iter(limit))
        except sqlite3.DatabaseError as error:
            raise OrccadError(f"{self.path}: not a campaign database ({error})") from None

    def _iter(self, limit: int | None) -> Iterator[RunRecord]:
        bound = -1 if limit is None else limit
        metrics: dict[int, dict[str, Any]] = {}
        for run, name, value in self.db.execute("SELECT run, name, value FROM metrics"):
            metrics.setdefault(run, {})[name] = value
        props: dict[int, dict[str, PropertyResult]] = {}
        for run, name, holds, robust in self.db.execute("SELECT * FROM properties"):
            props.setdefault(run, {})[name] = PropertyResult(
                None if holds is None else bool(holds), robust)
        rows = self.db.execute(
            "SELECT run, status, outcome, reason, sim_time_s, wall_time_s, attempts, error, "
            "setting FROM runs WHERE ? < 0 OR run < ? ORDER BY run", (bound, bound))
        for run, status, outcome, reason, sim, wall, attempts, error, setting in rows:
            try:
                parsed = RunSetting.from_dict(json.loads(setting))
                if parsed.index != run or status not in _STATUSES or \
                        not isinstance(attempts, int):
                    raise ValueError("its index, status or attempts are not a campaign's")
                record = RunRecord(parsed, status, reason, outcome, float(sim or 0.0),
                                   float(wall or 0.0), metrics.get(run, {}),
                                   props.get(run, {}), attempts, error)
            except (ValueError, TypeError, KeyError, AttributeError) as failure:
                raise OrccadError(f"{self.path}: run {run}: not a row a campaign writes "
                                  f"({failure})") from None
            yield record

    def replay(self, index: int) -> str | None:
        row = self.db.execute("SELECT replay FROM runs WHERE run = ?", (index,)).fetchone()
        return None if row is None else row[0]
