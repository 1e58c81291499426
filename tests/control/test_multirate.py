"""Computed torque split into Module-Tasks at two rates (``dynamic_model`` + ``ct_feedback``):
the split law computes the same torque as the one-piece law, and in the executive the
tracking error grows with the model's update period (RR-1801 §6.2)."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from orccad_app.control.errors import InvalidParameter
from orccad_app.control.multirate import ComputedTorqueFeedbackModule, DynamicModelModule
from orccad_app.control.trajectories import Sample
from orccad_app.executive import Bus
from orccad_app.mission.plan import plan_mission
from orccad_app.mission.run import MissionRun
from orccad_app.pipeline import load, select_mission

ROOT = Path(__file__).resolve().parents[2]
MISSION = ROOT / "missions" / "arm_computed_torque_multirate.orc"


def test_split_law_gives_the_computed_torque_of_the_one_piece_law(cosine_context):
    context = cosine_context(law=("computed_torque", {"kp": 400.0, "kv": 40.0}))
    model = DynamicModelModule().create({}, context)
    feedback = ComputedTorqueFeedbackModule().create({"kp": 400.0, "kv": 40.0}, context)
    assert {p.name: p.dim for p in model.ports} == {"q": 3, "qdot": 3, "M": 9, "N": 3}
    q, qdot = np.array([0.9, 1.1, 0.7]), np.array([0.3, -0.2, 0.5])
    ref = Sample(pos=np.array([1.0, 1.0, 0.8]), vel=np.array([0.1, 0.0, 0.4]),
                 acc=np.array([-1.0, 2.0, 0.5]))
    m_n = model.compute(0.0, {"q": q, "qdot": qdot})
    out = feedback.compute(0.0, {"qd": ref.pos, "qd_dot": ref.vel, "qd_ddot": ref.acc,
                                 "q": q, "qdot": qdot, **m_n})
    law = context.law.build(context.robot, context.task_function.build(context.robot))
    expected = law.command(0.0, q, qdot, ref)
    np.testing.assert_allclose(out["tau"], expected.tau, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(out["e"], q - ref.pos)
    assert out["saturated"] is False


def test_feedback_writes_nothing_before_the_first_model(cosine_context):
    feedback = ComputedTorqueFeedbackModule().create({}, cosine_context())
    inputs = {"qd": np.ones(3), "qd_dot": np.zeros(3), "qd_ddot": np.zeros(3),
              "q": np.ones(3), "qdot": np.zeros(3), "M": None, "N": None}
    assert feedback.compute(0.0, inputs) == {}


def test_feedback_gains_are_checked_and_retunable(cosine_context):
    with pytest.raises(InvalidParameter, match="kp must be > 0"):
        ComputedTorqueFeedbackModule().create({"kp": -1.0}, cosine_context())
    feedback = ComputedTorqueFeedbackModule().create({}, cosine_context())
    feedback.set_param("kp", 100.0)
    assert feedback.kp[0, 0] == 100.0


def _run(period_ms: float, wcet_ms: float, processor: str = "cpu1", tmp_path=None):
    text = MISSION.read_text(encoding="utf-8")
    text, found = re.subn(r"module model : dynamic_model\s+period 10 ms wcet 2 ms\s+on cpu1",
                          f"module model : dynamic_model period {period_ms:g} ms "
                          f"wcet {wcet_ms:g} ms on {processor}", text)
    assert found == 1
    path = tmp_path / f"multirate_{period_ms:g}.orc"
    path.write_text(text, encoding="utf-8")
    source = load(path)
    return MissionRun(plan_mission(source, select_mission(source, None)),
                      bus=Bus(transfer_ns=50_000)).run()


def test_the_shipped_mission_tracks_with_a_10_ms_model_across_the_bus():
    source = load(MISSION)
    result = MissionRun(plan_mission(source, select_mission(source, None)),
                        bus=Bus(transfer_ns=50_000)).run()
    assert result.status == "done"
    tasks = result.stats.tasks
    assert tasks["TrackCTMultirate.model"].completed == 400      # 4 s at 10 ms
    assert tasks["TrackCTMultirate.ctrl"].completed == 4000      # 4 s at 1 ms
    assert all(s.deadline_misses == 0 for s in tasks.values())
    assert result.stats.bus.messages == 800                      # M and N, per model job
    errors = result.robot_tasks[0].errors.summary()
    assert errors["max"] < 0.005 and errors["rms"] < 0.002


def test_tracking_error_grows_with_the_model_update_period(tmp_path):
    errors = [_run(period, min(2.0, period / 2), tmp_path=tmp_path).robot_tasks[0]
              .errors.summary() for period in (1, 5, 20)]
    rms = [e["rms"] for e in errors]
    peak = [e["max"] for e in errors]
    assert rms[0] < rms[1] < rms[2] and peak[0] < peak[1] < peak[2]
    assert rms[2] > 5 * rms[0]
