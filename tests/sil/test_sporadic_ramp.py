"""A type-1 ramp on a sporadic Module-Task, applied by the real-time controller itself (issue
35 item 1): stepped, as the executive steps it, every minimum inter-arrival from the update —
each job sees the grid's last step before its release; the supervisor writes nothing."""

from __future__ import annotations

import pytest

from orccad_app.mission.injection import parse_injection
from orccad_app.mission.plan import plan_mission
from orccad_app.pipeline import load, select_mission
from orccad_app.session import ControllerOptions, Execution, RunOptions, RunSession
from orccad_app.sil.controller.process import Op
from orccad_app.sil.generate.adjust import AdjustForm, c_adjustments
from orccad_app.sil.generate.automaton import managed_sites, mission_automaton, supervisor_needs
from orccad_app.sil.generate.tree import controller_table
from tests.sil.helpers import MISSIONS

RAMP = "adjust watch.max = ramp(0.2, 0.5, 1 s)"


@pytest.fixture
def ramped(tmp_path):
    text = (MISSIONS / "arm_interrupts.orc").read_text().replace(
        "    exception TrackingLost from watch : abort;\n}",
        f"    exception TrackingLost from watch : abort;\n"
        f"    exception Saturated from torque_saturation : {RAMP};\n}}", 1)
    path = tmp_path / "ramped.orc"
    path.write_text(text)
    return str(path)


def test_the_ramp_on_the_sporadic_observer_is_the_controller_s(ramped):
    source = load(ramped)
    plan = plan_mission(source, select_mission(source, "ArmInterrupts"))
    table = controller_table(plan, mission_automaton(plan).program)
    (ramp,) = c_adjustments(plan, table, managed_sites(plan))
    assert (ramp.form, ramp.offsets, ramp.duration_ns) == (AdjustForm.RAMP, (1,), 10**9)
    assert supervisor_needs(plan, (ramp,)) == ()


def test_the_controller_steps_it_on_the_minimum_inter_arrival_grid(ramped):
    source = load(ramped)
    session = RunSession(source, select_mission(source, "ArmInterrupts"), RunOptions(
        execution=Execution.REALTIME, controller=ControllerOptions(ramped),
        injections=(parse_injection("TrackWatched.Saturated@0.5"),), until_s=1.8))
    controller = session.backend.controller
    request, request_words = controller.request, controller.request_words
    watch = session.backend.table.index("TrackWatched.watch")
    ops: list[Op] = []
    samples: list[float] = []

    def spy(op, *args, **kwargs):
        ops.append(op)
        return request(op, *args, **kwargs)

    def spy_words(op, *args, **kwargs):  # PING, ACTIVATE, INPUT: integer or packed words
        ops.append(op)
        if op is Op.PING:
            samples.append(request(Op.PARAMS, watch)[1])
        return request_words(op, *args, **kwargs)

    controller.request, controller.request_words = spy, spy_words
    result = session.execute().result
    assert Op.PARAM not in ops and controller.supervisor_writes == 0
    (update,) = [e.update for e in result.exceptions if e.name == "Saturated"]
    assert update.ramp is not None and (update.ramp.start, update.ramp.end) == (0.2, 0.5)
    assert samples[0] == 0.2 and samples[-1] == 0.5
    assert samples == sorted(samples)
    between = [v for v in samples if 0.2 < v < 0.5]
    assert between  # stepped, not jumped
    for value in between:  # 0.2 + 0.3 * (k * 2 ms) / 1 s: on the 2 ms grid from the update
        steps = (value - 0.2) / 0.3 * 500
        assert abs(steps - round(steps)) < 1e-6, value
