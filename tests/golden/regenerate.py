"""Regenerate the golden references: ``python -m tests.golden.regenerate``.

Run it only when a change of behaviour is intended, and say in the commit message which
references changed and why (``git diff --stat tests/golden/data`` lists them). Each case runs
the ``orccad`` command in a fresh interpreter, exactly as a user would.
"""

from __future__ import annotations

import gzip
import json
import re
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

from tests.golden.cases import CASES, DATA, ROOT, Case

INDEX = DATA / "index.json"
_WALL_TIME = re.compile(rb'"wall_time_s": [-+0-9.eE]+')


@dataclass(frozen=True)
class Output:
    """What one golden command produced.

    :param status: its exit status.
    :param stdout: its standard output, ``wall_time_s`` zeroed.
    :param trace: the CSV trace it wrote (``None`` when the case writes none).
    """

    status: int
    stdout: bytes
    trace: bytes | None


def _zero_wall_time(stdout: bytes) -> bytes:
    """The report with its one machine-dependent field (``wall_time_s``) set to 0.0."""
    return _WALL_TIME.sub(rb'"wall_time_s": 0.0', stdout)


def produce(case: Case) -> Output:
    """Run ``case``'s command in a fresh interpreter and collect its outputs."""
    with tempfile.TemporaryDirectory() as tmp:
        trace_path = Path(tmp) / "trace.csv"
        argv = list(case.argv) + (["--trace", str(trace_path)] if case.trace else [])
        proc = subprocess.run(
            [sys.executable, "-c", "import sys; from orccad_app.cli import main; sys.exit(main())",
             *argv], cwd=ROOT, capture_output=True, timeout=300, check=False)
        trace = trace_path.read_bytes() if case.trace else None
    return Output(proc.returncode, _zero_wall_time(proc.stdout), trace)


def reference(case: Case) -> Output:
    """The stored references of ``case``."""
    index = json.loads(INDEX.read_text())
    trace = None
    if case.trace:
        trace = gzip.decompress((DATA / f"{case.name}.csv.gz").read_bytes())
    return Output(index[case.name], (DATA / f"{case.name}.out").read_bytes(), trace)


def main() -> int:
    DATA.mkdir(exist_ok=True)
    statuses: dict[str, int] = {}
    for case in CASES:
        output = produce(case)
        statuses[case.name] = output.status
        (DATA / f"{case.name}.out").write_bytes(output.stdout)
        if output.trace is not None:
            (DATA / f"{case.name}.csv.gz").write_bytes(gzip.compress(output.trace, mtime=0))
        print(f"{case.name}: status {output.status}", file=sys.stderr)
    INDEX.write_text(json.dumps(statuses, indent=2, sort_keys=True) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
