"""Replaying one setting of a campaign in this process, with a trace (falsify, tests)."""

from __future__ import annotations

from orccad_app.campaign.adapter import CompiledMission, RunRecord, execute
from orccad_app.campaign.setting import RunSetting
from orccad_app.campaign.spec import CampaignSpec

__all__ = ["replay_with_trace"]


def replay_with_trace(compiled: CompiledMission, setting: RunSetting, spec: CampaignSpec,
                      path: str) -> RunRecord:
    """Run ``setting`` again, writing its trace to ``path`` (``.csv`` or ``.mcap``), the
    same trace ``orccad run … --trace path`` writes."""
    return execute(compiled, setting, spec.signals, spec.checks, trace=path)
