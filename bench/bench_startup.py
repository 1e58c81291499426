"""Benchmark: start-up of the ``orccad`` command against a bare Python interpreter.

    .venv/bin/python bench/bench_startup.py              # from the repository root
    .venv/bin/python bench/bench_startup.py --repeat 20

Each command is run as a new process, as a user runs it, ``--repeat`` times; the figure is the
median wall time. The baseline, measured in the same command, is the same interpreter doing
nothing (``python -c pass``): the ratio says what ORCCAD adds to a bare start. Targets (issue
14, on an idle machine): ``orccad --version`` and ``--help`` ≤ 0.2 s, ``orccad compile
missions/abro.orc`` ≤ 0.4 s. Byte-code caches are written before timing (a first run), as an
installed package has them; the parser's tables come from the user's cache (see
``orccad_app.lang.parser``).

Also prints which of the heavy libraries (numpy, mujoco, pinocchio, textual) each command
imported: ``--version``, ``--help`` and ``compile`` of a mission without Robot-Tasks import
none of them.

Exit status 0 when every target is met, 1 when one is MISSED (2 is bad input, as for
orccad).

Needs: no extra: ORCCAD's own dependencies.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
HEAVY = ("numpy", "mujoco", "pinocchio", "textual")

COMMANDS: dict[str, list[str]] = {
    "python -c pass (baseline)": ["-c", "pass"],
    "orccad --version": ["-m", "orccad_app", "--version"],
    "orccad --help": ["-m", "orccad_app", "--help"],
    "orccad compile missions/abro.orc": ["-m", "orccad_app", "compile", "missions/abro.orc"],
}
TARGETS_S = {"orccad --version": 0.2, "orccad --help": 0.2,
             "orccad compile missions/abro.orc": 0.4}


def _environment() -> dict[str, str]:
    env = dict(os.environ)
    env.pop("PYTHONDONTWRITEBYTECODE", None)  # an installed package has its .pyc files
    return env


def _time(argv: list[str], repeat: int) -> float:
    env = _environment()
    subprocess.run([sys.executable, *argv], cwd=ROOT, env=env, capture_output=True, check=True)
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        subprocess.run([sys.executable, *argv], cwd=ROOT, env=env, capture_output=True,
                       check=True)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def heavy_imports(argv: list[str]) -> list[str]:
    """The heavy libraries a command imports (from ``python -X importtime``)."""
    result = subprocess.run([sys.executable, "-X", "importtime", *argv], cwd=ROOT,
                            env=_environment(), capture_output=True, text=True)
    imported = {line.rsplit("|", 1)[-1].strip() for line in result.stderr.splitlines()
                if line.startswith("import time:")}
    return [name for name in HEAVY if name in imported]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=10)
    args = parser.parse_args()
    baseline = None
    met = True
    print(f"{'command':<36} {'median':>9} {'× bare python':>14} {'target':>8}  heavy imports")
    for name, argv in COMMANDS.items():
        seconds = _time(argv, args.repeat)
        baseline = baseline or seconds
        target = TARGETS_S.get(name)
        heavy = ", ".join(heavy_imports(argv)) or "none"
        verdict = "" if target is None else " met" if seconds <= target else " MISSED"
        met = met and (target is None or seconds <= target)
        print(f"{name:<36} {seconds * 1e3:7.0f} ms {seconds / baseline:13.1f}× "
              f"{f'{target:.1f} s' if target else '':>8}{verdict}  {heavy}")
    print(f"load average: {', '.join(f'{x:.1f}' for x in os.getloadavg())} "
          f"({os.cpu_count()} CPUs): figures scale with it")
    return 0 if met else 1


if __name__ == "__main__":
    sys.exit(main())
