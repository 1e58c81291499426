"""Regenerate the golden references: ``python -m tests.golden.regenerate``.

Run it only when a change of behaviour is intended, and say in the commit message which
references changed and why (``git diff --stat tests/golden/data`` lists them). Each case runs
the ``orccad`` command in a fresh interpreter, exactly as a user would.
"""

from __future__ import annotations

import hashlib
import json
import lzma
import re
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

from tests.golden.cases import CASES, DATA, ROOT, Case

INDEX = DATA / "index.json"
TRACE_SUFFIX = ".csv.xz"
"""A reference trace is stored xz-compressed (a third smaller than gzip)."""
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


def summary(case: Case, stdout: bytes) -> bytes:
    """What is kept of ``case``'s standard output: all of it, except for a compile case whose
    automaton's ``states`` (the bulk: 95 % of ArmRecovery's output) are kept as their
    SHA-256 digest ``states_sha256`` (over their canonical JSON) beside the summary fields
    (interface, counts, initial state). A changed state still changes the digest."""
    if case.argv[0] != "compile" or not stdout.startswith(b"{"):
        return stdout
    from orccad_app.jsonout import dumps

    document = json.loads(stdout)
    states = document.pop("states", None)
    if states is not None:
        canonical = json.dumps(states, sort_keys=True, separators=(",", ":"),
                               allow_nan=False).encode()
        document["states_sha256"] = hashlib.sha256(canonical).hexdigest()
    return (dumps(document, indent=2) + "\n").encode()


def trace_bytes(name: str) -> bytes:
    """The stored reference trace of case ``name`` (CSV text)."""
    return lzma.decompress((DATA / f"{name}{TRACE_SUFFIX}").read_bytes())


def produce(case: Case) -> Output:
    """Run ``case``'s command in a fresh interpreter and collect its outputs."""
    with tempfile.TemporaryDirectory() as tmp:
        trace_path = Path(tmp) / "trace.csv"
        argv = list(case.argv) + (["--trace", str(trace_path)] if case.trace else [])
        proc = subprocess.run(
            [sys.executable, "-c", "import sys; from orccad_app.cli import main; sys.exit(main())",
             *argv], cwd=ROOT, capture_output=True, timeout=300, check=False)
        trace = trace_path.read_bytes() if case.trace else None
    return Output(proc.returncode, summary(case, _zero_wall_time(proc.stdout)), trace)


def reference(case: Case) -> Output:
    """The stored references of ``case``."""
    index = json.loads(INDEX.read_text())
    trace = None
    if case.trace:
        trace = trace_bytes(case.name)
    return Output(index[case.name], (DATA / f"{case.name}.out").read_bytes(), trace)


def main() -> int:
    DATA.mkdir(exist_ok=True)
    statuses: dict[str, int] = {}
    for case in CASES:
        output = produce(case)
        statuses[case.name] = output.status
        (DATA / f"{case.name}.out").write_bytes(output.stdout)
        if output.trace is not None:
            (DATA / f"{case.name}{TRACE_SUFFIX}").write_bytes(
                lzma.compress(output.trace, preset=9 | lzma.PRESET_EXTREME))
        print(f"{case.name}: status {output.status}", file=sys.stderr)
    INDEX.write_text(json.dumps(statuses, indent=2, sort_keys=True) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
