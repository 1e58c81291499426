"""Issue 34, items 16 and 17: the benchmarks agree with docs/performance.md. A benchmark that
misses a target exits 1 (2 is bad input, as for orccad), prints MISSED as the docs say
"missed", names the extra it needs, and runs without an optional extra it can do without."""

from __future__ import annotations

import ast
import importlib.util
import re
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
BENCHES = sorted((ROOT / "bench").glob("bench_*.py"))


def _extras() -> set[str]:
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    return set(project["optional-dependencies"])


@pytest.mark.parametrize("path", BENCHES, ids=lambda p: p.name)
def test_each_benchmark_names_the_extra_it_needs(path):
    doc = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))) or ""
    found = re.search(r"^Needs: (.*?)(?:\n\n|\Z)", doc, re.S | re.M)
    assert found, f"{path.name}: no 'Needs:' paragraph in its docstring"
    named = set(re.findall(r"the ``(\w+)`` extra", found.group(1)))
    assert named or found.group(1).startswith("no extra"), found.group(1)
    assert named <= _extras(), (path.name, named - _extras())


def _returns_two_when_missed(tree: ast.AST) -> list[int]:
    """Lines of ``return 0 if OK else 2`` (the old convention for a missed target)."""
    return [node.lineno for node in ast.walk(tree)
            if isinstance(node, ast.Return) and isinstance(node.value, ast.IfExp)
            and isinstance(node.value.orelse, ast.Constant) and node.value.orelse.value == 2]


@pytest.mark.parametrize("path", BENCHES, ids=lambda p: p.name)
def test_a_benchmark_that_misses_a_target_exits_1_and_prints_missed(path):
    text = path.read_text(encoding="utf-8")
    tree = ast.parse(text)
    assert not _returns_two_when_missed(tree), f"{path.name} exits 2 on a missed target"
    verdicts = re.findall(r"'(met|MET)' if .+? else '(\w+)", text)
    for _, missed in verdicts:
        assert missed == "MISSED", f"{path.name} prints {missed!r} for a missed target"
    if "MISSED" in text:
        assert re.search(r"(sys\.exit|SystemExit)\(main\(\)\)", text), \
            f"{path.name}: its verdict never reaches the exit status"
        doc = ast.get_docstring(tree) or ""
        assert re.search(r"Exit status 0\s+when .+? met, 1\s", doc, re.S), \
            f"{path.name}: its docstring does not say it exits 1 when a target is missed"


def test_performance_md_gives_the_benchmarks_exit_status():
    text = (ROOT / "docs" / "performance.md").read_text(encoding="utf-8")
    assert not re.search(r"exits? 2 when missed|\(2 when missed\)|met, 2 otherwise", text)
    assert "`MISSED`" in text and "exits with status 0 when every target is met, 1" in text


def _load_bench(name: str):
    spec = importlib.util.spec_from_file_location(name, ROOT / "bench" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_bench_campaign_skips_dask_with_a_message_without_the_cluster_extra(monkeypatch,
                                                                              capsys):
    bench = _load_bench("bench_campaign")
    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: None if name == "distributed" else real(name, *a))
    asked: list[bool] = []
    monkeypatch.setattr(bench, "run_cost", lambda repeat: None)
    monkeypatch.setattr(bench, "throughput",
                        lambda runs, repeat, dask: asked.append(dask) or True)
    monkeypatch.setattr(sys, "argv", ["bench_campaign.py", "--runs", "1"])
    assert bench.main() == 0
    assert asked == [False]  # Dask never imported
    assert "3. Dask: skipped (Dask is not installed (pip install -e '.[cluster]'))" in \
        capsys.readouterr().out
    monkeypatch.setattr(bench, "throughput", lambda runs, repeat, dask: False)
    assert bench.main() == 1  # a missed target
