"""The typed automaton/executive seam: labels, signal roles, run sites, one instance per site."""

from __future__ import annotations

from pathlib import Path

import pytest

from orccad_app.lang.ast_robottask import ExceptionType
from orccad_app.mission.plan import plan_mission
from orccad_app.mission.run import MissionRun
from orccad_app.pipeline import compose_mission, load, select_mission
from orccad_app.robottask.labels import Phase, PhaseLabel, RtLabel
from orccad_app.robottask.signals import RaisedBy, RoleKind, SignalRole
from tests.robottask.conftest import arm_task

ROOT = Path(__file__).resolve().parents[2]

TASKS = arm_task("Track", params="kp: float = 400.0", clauses="""
    precondition measure at_rest(tol = 0.05) within 2 s;
    exception Saturated from torque_saturation : adjust ctrl.kp = 200.0;
    exception Lost from tracking_error(max = 0.2) : abort;""")


@pytest.fixture
def source(tmp_path):
    path = tmp_path / "m.orc"
    path.write_text(TASKS + "mission M { run Track(); run Track(kp = 600.0) within 5 s; }\n",
                    encoding="utf-8")
    return load(path)


def test_the_lowering_gives_the_role_of_every_signal_it_adds(source):
    composition = compose_mission(source, select_mission(source, None))
    roles = composition.roles
    assert roles.get("Track.Saturated.adjust") == SignalRole(RoleKind.ADJUST, "Track",
                                                             "Saturated")
    assert roles.get("Lost.raised") == SignalRole(RoleKind.RAISED, None, "Lost")
    assert roles.get("at_rest_timeout.raised") == SignalRole(RoleKind.RAISED, None,
                                                             "at_rest_timeout")
    assert roles.get("Timeout.raised") == SignalRole(RoleKind.RAISED, None, "Timeout")
    assert roles.get("Track.start") == SignalRole(RoleKind.START, "Track")
    assert roles.get("Track.Lost") == SignalRole(RoleKind.EVENT, "Track", "Lost")
    assert roles.raisers["Lost"] == [RaisedBy("Track", ExceptionType.ABORT)]
    assert roles.raisers["at_rest_timeout"] == [RaisedBy("Track", ExceptionType.ABORT)]
    assert "Timeout" not in roles.raisers  # the mission's own (run … within)
    # every generated output has a role; only the mission's own are left without one
    generated = {s.name for s in composition.automaton.outputs if roles.get(s.name) is None}
    assert generated <= {"_failed", "_aborted"}


def test_states_are_labelled_with_typed_run_site_and_phase_labels(source):
    composition = compose_mission(source, select_mission(source, None))
    labels = set().union(*composition.automaton.labels)
    assert {RtLabel("Track", 0), RtLabel("Track", 1)} <= labels
    phases = {label.phase for label in labels if isinstance(label, PhaseLabel)}
    assert phases == {Phase.MEASURING, Phase.ACTIVE}  # no synchronization pre-condition
    assert all(isinstance(label, (RtLabel, PhaseLabel)) for label in labels)


def test_each_run_site_runs_the_instance_checked_at_load(source):
    plan = plan_mission(source, select_mission(source, None))
    assert [site.number for site in plan.sites] == [0, 1]
    for site in plan.sites:
        assert site.instance is source.instance(site.site.stmt)
    assert [site.instance.params["kp"] for site in plan.sites] == [400.0, 600.0]
    assert plan.sites[0].adjustments["Saturated"].param == "kp"


def test_a_run_reports_phases_as_the_phase_enum():
    source = load(ROOT / "missions" / "arm_pid.orc")
    run = MissionRun(plan_mission(source, select_mission(source, None)), until_ns=50_000_000)
    seen: set = set()

    class Watch:
        def on_reaction(self, t_ns, inputs, outputs, status):
            seen.update(run.phases.values())

    run.add_observer(Watch())
    run.run()
    assert seen and all(isinstance(phase, Phase) for phase in seen)
    assert Phase.ACTIVE in seen
