"""The run-time arguments the real-time controller binds itself (orccad_app/sil/generate/binds.py,
issue 35 item 1): where each component is copied, the checks found by bisection, and the
shipped missions that leave nothing to the supervisor."""

from __future__ import annotations

import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.sil.generate.adjust import c_adjustments
from orccad_app.sil.generate.automaton import managed_sites, mission_automaton, supervisor_needs
from orccad_app.sil.generate.binds import CBind, bindable, c_binds
from orccad_app.sil.generate.tree import controller_table
from tests.sil.helpers import MISSIONS, plan_of


def test_the_waypoint_s_components_are_copied_into_the_guidance_and_checked():
    plan = plan_of("auv_waypoints.orc")
    assert bindable(plan) == {0, 1} and managed_sites(plan) == {0, 1, 2, 3}
    binds, checks = c_binds(plan)
    goto = [b for b in binds if b.site == 0]
    assert CBind(0, "GoTo.arg.target", 2, "GoTo.guide", 1) in goto  # depth
    assert CBind(0, "GoTo.arg.target", 0, "GoTo.guide", 3) in goto  # x
    assert CBind(0, "GoTo.arg.target", 1, "GoTo.guide", 4) in goto  # y
    bounds = {(c.site, c.component): (c.low, c.high) for c in checks}
    assert bounds[(0, 0)] == (-1e6, 1e6)  # the guidance's position bound
    assert bounds[(0, 2)] == (0.0, 1e6)   # a depth >= 0, exactly
    site = plan.sites[0]
    site.bound({"GoTo.arg.target": [0.0, 0.0, 0.0]})
    with pytest.raises(OrccadError):
        site.bound({"GoTo.arg.target": [0.0, 0.0, -5e-324]})  # the next double below 0


@pytest.mark.parametrize("file, mission", [
    ("arm_pid.orc", None), ("arm_recovery.orc", None), ("arm_retune.orc", None),
    ("arm_interrupts.orc", "ArmInterrupts"), ("arm_interrupts.orc", "ArmInterruptsTight"),
    ("arm_computed_torque.orc", None), ("arm_computed_torque_multirate.orc", None),
    ("auv_survey.orc", None), ("auv_waypoints.orc", None), ("false_property.orc", None)])
def test_no_shipped_mission_needs_the_supervisor(file, mission):
    plan = plan_of(file, mission)
    table = controller_table(plan, mission_automaton(plan).program)
    assert supervisor_needs(plan, c_adjustments(plan, table, managed_sites(plan))) == ()


def test_a_value_the_kinds_transform_stays_with_the_supervisor(tmp_path):
    """An int argument (its words need not be doubles of it) is not bound in C."""
    from orccad_app.mission.plan import plan_mission
    from orccad_app.pipeline import load, select_mission

    text = (MISSIONS / "auv_waypoints.orc").read_text().replace(
        "robottask GoTo(target: vector = [10.0, 0.0, 10.0])",
        "robottask GoTo(target: vector = [10, 0, 10])")
    source_file = tmp_path / "ints.orc"
    source_file.write_text(text)
    source = load(str(source_file))
    plan = plan_mission(source, select_mission(source, None))
    assert 0 not in bindable(plan)
    needs = supervisor_needs(plan, ())
    assert needs and needs[0].startswith("the run-time arguments of GoTo at ")
