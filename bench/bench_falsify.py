"""Falsification against a plain random campaign: runs until the first violation.

On ``missions/auv_survey.orc`` with ``missions/auv_survey.campaign.toml``, the signal property
``safe_depth`` (``always (auv.depth < 30.0)``) is violated only when the depth sensor's
offset fault (probability 0.1) reads some 15-20 m or more too shallow early enough in the survey:
about 1 run in 100 of the spec's distribution. This prints, for the same budget:

- the **random campaign** (``orccad campaign``: settings drawn from the spec's distributions):
  for each of ``--chunks`` independent stretches of ``--budget`` runs, the index of the first
  violating run (``-`` if none) and the smallest robustness;
- **falsification** (``orccad falsify``, optuna TPE) for each ``--seeds``: the trial of the
  first violation and the smallest robustness.

A campaign database made beforehand can stand for the random side (``--campaign-db``: its runs
``0 … chunks·budget−1`` are used), which saves running it again.

    python bench/bench_falsify.py [--budget 60] [--seeds 0 1] [--chunks 3] [--workers 2]
                                  [--campaign-db auv200.db]

Needs: no extra: ORCCAD's own dependencies (optuna is one).
"""

from __future__ import annotations

import argparse
import sqlite3
import tempfile
import time
from pathlib import Path

from orccad_app.campaign.falsify import Falsifier
from orccad_app.campaign.runner import Campaign, CampaignOptions
from orccad_app.campaign.spec import load_spec

ROOT = Path(__file__).resolve().parents[1]
AUV = str(ROOT / "missions" / "auv_survey.orc")
SPEC = str(ROOT / "missions" / "auv_survey.campaign.toml")
PROPERTY = "safe_depth"


def random_side(db: str | None, runs: int, workers: int) -> list[tuple[int, float | None]]:
    """Per run index: (index, robustness) of the random campaign."""
    if db is None:
        db = tempfile.mktemp(suffix=".db")
        Campaign(AUV, load_spec(SPEC), CampaignOptions(runs=runs, db=db, workers=workers)).run()
    with sqlite3.connect(db) as connection:
        rows = connection.execute(
            "SELECT run, robustness FROM properties WHERE name = ? AND run < ? ORDER BY run",
            (PROPERTY, runs)).fetchall()
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--budget", type=int, default=60)
    parser.add_argument("--seeds", type=int, nargs="+", default=[0, 1])
    parser.add_argument("--chunks", type=int, default=3)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--campaign-db")
    args = parser.parse_args()
    rows = random_side(args.campaign_db, args.budget * args.chunks, args.workers)
    print(f"random campaign ({args.budget} runs per stretch, settings from the spec):")
    for chunk in range(args.chunks):
        part = [(i, r) for i, r in rows if chunk * args.budget <= i < (chunk + 1) * args.budget]
        first = next((i - chunk * args.budget for i, r in part if r is not None and r < 0), None)
        low = min(r for _, r in part if r is not None)
        print(f"  stretch {chunk}: first violation at run {first if first is not None else '-'}"
              f", smallest robustness {low:.3f} m")
    print(f"falsification (optuna TPE, budget {args.budget}):")
    for seed in args.seeds:
        start = time.perf_counter()
        result = Falsifier(AUV, load_spec(SPEC), PROPERTY, seed=seed).run(
            args.budget, args.workers)
        wall = time.perf_counter() - start
        first = result.first_violation
        print(f"  seed {seed}: first violation at trial {first if first is not None else '-'}"
              f", smallest robustness {result.best_robustness:.3f} m ({wall:.0f} s)")
        print(f"    {result.replay}")


if __name__ == "__main__":
    main()
