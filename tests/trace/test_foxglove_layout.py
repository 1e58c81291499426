"""docs/foxglove-layout.json: written by docs/make_foxglove_layout.py with the Foxglove SDK's
layout types, and every topic it shows is one a trace of missions/arm_recovery.orc holds."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest
from mcap.reader import make_reader

LAYOUT = Path("docs/foxglove-layout.json")


def _panels(node):
    if node.get("type") == "panel":
        yield node
    for item in node.get("items", []):
        yield from _panels(item["content"])


def test_the_shipped_layout_is_the_generator_s():
    pytest.importorskip("foxglove", reason="the foxglove extra is not installed")
    result = subprocess.run([sys.executable, "docs/make_foxglove_layout.py", "--check"],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, "docs/foxglove-layout.json is stale: run the script"


def test_the_layout_shows_3d_set_points_gains_verdicts_state_and_the_log(recovery_run):
    layout = json.loads(LAYOUT.read_text(encoding="utf-8"))
    panels = {panel["title"]: panel for panel in _panels(layout["content"])}
    kinds = sorted(panel["panelType"] for panel in panels.values())
    assert kinds == ["Log", "Plot", "Plot", "Plot", "Plot", "StateTransitions", "ThreeDee"]
    shown = {panels["arm"]["config"]["followTf"], "/log"} - {"world"}
    shown |= set(panels["arm"]["config"]["topics"])
    for panel in panels.values():
        for series in panel["config"].get("paths", []):
            shown.add(re.match(r"(/[^.]+)\.", series["value"]).group(1))
    with open(recovery_run.path, "rb") as stream:
        traced = {c.topic for c in make_reader(stream).get_summary().channels.values()}
    assert shown <= traced, shown - traced
    assert {"/scene", "/plant/arm/q", "/ports/TrackPID/traj/qd", "/params/TrackPID/ctrl/kp",
            "/mission/state", "/mission/phase/TrackPID", "/properties/park_completes"} <= shown
