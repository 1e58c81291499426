"""Fuzzing the console's database paths (issue 34): files given to ``orccad tui --db`` — bytes
of any kind, SQLite files of other programs, campaign and study databases damaged at random
bytes or cut short, in WAL mode or not — read as the campaign screen reads them.

Promises checked: each read gives a snapshot or one located
:class:`~orccad_app.diagnostics.OrccadError` naming the file, never another exception; the
file is not changed and nothing is left beside it. The default run has a small budget;
``-m fuzz_long`` runs hundreds of examples."""

from __future__ import annotations

import contextlib
import os
import sqlite3
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from orccad_app.campaign.store import CampaignStore
from orccad_app.diagnostics import OrccadError
from orccad_app.tui.campaigns import CampaignSnapshot, FalsifySnapshot, read_campaign, read_study
from tests.fuzz.harness import scratch_folder

SPEC = "missions/arm_pid.campaign.toml"
_TABLES = st.sampled_from(["campaign", "runs", "params", "metrics", "properties", "studies",
                           "trials", "t", "version_info", "alembic_version"])
_COLUMNS = st.lists(st.sampled_from(["key", "value", "run", "seed", "status", "x", "name"]),
                    min_size=1, max_size=4, unique=True)


def _campaign_bytes(wal: bool) -> bytes:
    """A campaign's database as the command leaves it (its meta written), as bytes."""
    folder = scratch_folder("orccad-fuzz-db-")
    path = folder / "c.db"
    store = CampaignStore(str(path))
    store.db.execute("INSERT INTO campaign VALUES ('file', 'missions/arm_pid.orc'), "
                     "('spec', 'runs = 3'), ('mission', 'ArmPid')")
    store.db.commit()
    if not wal:
        store.db.execute("PRAGMA journal_mode=DELETE")
    store.close()
    return path.read_bytes()


_CAMPAIGN = {True: _campaign_bytes(True), False: _campaign_bytes(False)}


@st.composite
def _database(draw) -> tuple[str, bytes | list[tuple[str, list[str]]]]:
    """What to write: raw bytes, or an SQLite file with the given tables and columns."""
    kind = draw(st.sampled_from(["bytes", "damaged", "cut", "tables"]))
    if kind == "bytes":
        head = draw(st.sampled_from([b"", b"SQLite format 3\x00"]))
        return "bytes", head + draw(st.binary(max_size=300))
    if kind == "tables":
        return "tables", draw(st.lists(st.tuples(_TABLES, _COLUMNS), max_size=4,
                                       unique_by=lambda t: t[0]))
    data = bytearray(_CAMPAIGN[draw(st.booleans())])
    if kind == "cut":
        return "bytes", bytes(data[:draw(st.integers(0, len(data)))])
    for _ in range(draw(st.integers(1, 8))):
        at = draw(st.integers(0, len(data) - 1))
        data[at] = draw(st.integers(0, 255))
    return "bytes", bytes(data)


def _write(path: Path, kind: str, what) -> None:
    if kind == "bytes":
        path.write_bytes(what)
        return
    with contextlib.closing(sqlite3.connect(path)) as db:
        for table, columns in what:
            db.execute(f"CREATE TABLE {table} ({', '.join(columns)})")
        db.commit()


def _settings(examples: int):
    return settings(max_examples=examples, deadline=None, database=None,
                    suppress_health_check=list(HealthCheck))


def _reads(examples: int):
    @_settings(examples)
    @given(_database())
    def run(database):
        folder = scratch_folder("orccad-fuzz-db-")
        path = folder / "x.db"
        _write(path, *database)
        before = path.read_bytes()
        for read in (lambda: read_campaign(str(path)),
                     lambda: read_study(str(path), SPEC, "bounded", 0.5, budget=2)):
            try:
                snapshot = read()
            except OrccadError as error:
                assert str(path) in error.message, error.message
                assert "\n" not in error.message
            else:
                assert isinstance(snapshot, (CampaignSnapshot, FalsifySnapshot))
        assert path.read_bytes() == before
        assert os.listdir(folder) == ["x.db"]
    return run


def test_any_database_file_is_read_or_refused_in_one_located_message():
    pytest.importorskip("optuna")
    _reads(40)()


@pytest.mark.fuzz_long
def test_long_database_files():
    pytest.importorskip("optuna")
    _reads(500)()
