"""The long fuzz runs (marker ``fuzz_long``) run only when asked: ``-m fuzz_long``."""

from __future__ import annotations

import pytest


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    if "fuzz_long" in (config.getoption("markexpr") or ""):
        return
    skip = pytest.mark.skip(reason="long fuzz run: select it with -m fuzz_long")
    for item in items:
        if item.get_closest_marker("fuzz_long"):
            item.add_marker(skip)


def pytest_configure(config: pytest.Config) -> None:
    # parsing raises Python's recursion limit once (orccad_app.lang.limits); doing it before
    # the tests run keeps hypothesis from warning that it changed during a test
    from orccad_app.lang.limits import ensure_recursion_headroom
    ensure_recursion_headroom()
