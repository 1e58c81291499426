"""Shared fixtures of the SIL tests: one build cache per test session (each controller is
compiled once), skipped with the reason where no C compiler exists."""

from __future__ import annotations

import os
import shutil

import pytest


@pytest.fixture(scope="session", autouse=True)
def build_cache(tmp_path_factory: pytest.TempPathFactory):
    if not any(shutil.which(name) for name in (os.environ.get("CC") or "cc", "gcc")):
        pytest.skip("no C compiler (cc or gcc): .ci/run installs gcc")
    previous = os.environ.get("ORCCAD_CACHE_DIR")
    os.environ["ORCCAD_CACHE_DIR"] = str(tmp_path_factory.mktemp("orccad-cache"))
    yield
    if previous is None:
        os.environ.pop("ORCCAD_CACHE_DIR", None)
    else:
        os.environ["ORCCAD_CACHE_DIR"] = previous
