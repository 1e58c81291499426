"""How the suite is shared between pytest-xdist's workers (a pytest plugin, loaded by
pyproject's ``addopts``, which also asks for ``-n auto --dist loadgroup``).

Each test is put in an ``xdist_group``: a worker runs a whole group, in collection order. By
default the group is the test's file, so module-scoped fixtures are built once and tests that
follow each other in a file keep their order. The few files that hold most of the suite's time
are split finer, along their real dependencies:

- ``tests/docs/test_doc_commands.py``: one group per documentation page (a page's commands may
  read what an earlier command of the same page wrote);
- ``tests/golden/test_golden.py``: one group per golden case (the determinism test of a case
  reuses that case's output, so both sit in the case's group);
- every other parametrized test listed in :data:`SPLIT`: one group per parameter.

With ``-n 0`` (one process, e.g. to debug) the groups mean nothing and the suite runs in order.
"""

from __future__ import annotations

import re

import pytest

#: ``file::function`` of parametrized tests whose parameters are independent and long enough to
#: be worth sharing out one by one
SPLIT = frozenset({
    "tests/verify/test_spin.py::test_spin_agrees",
    "tests/verify/test_check_cli.py::test_check_proves_the_missions",
    "tests/sil/test_lockstep.py::test_lockstep_ends_as_the_executive",
    "tests/sil/test_automaton.py::"
    "test_the_c_automaton_reacts_as_the_python_reactor_reaction_by_reaction",
})

_DOC_PAGE = re.compile(r"\[([^:\]]+\.md):")


def _group(item: pytest.Item) -> str:
    path, _, rest = item.nodeid.partition("::")
    function, _, parameter = rest.partition("[")
    if path == "tests/docs/test_doc_commands.py":
        page = _DOC_PAGE.search(item.nodeid)
        return f"{path}:{page.group(1) if page else 'README'}"
    if path == "tests/golden/test_golden.py" and parameter:
        return f"{path}:{parameter.rstrip(']')}"
    if parameter and f"{path}::{function}" in SPLIT:
        return f"{path}::{rest}"
    return path


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Mark every test with its group, before xdist reads the marks."""
    for item in items:
        item.add_marker(pytest.mark.xdist_group(_group(item)))
