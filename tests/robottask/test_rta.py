"""Generated Robot-Task automata: phases, and each exception type (RR-1801 §3.4.3)."""

from __future__ import annotations

from tests.robottask.conftest import Trace, arm_task, rta

PAPER = """
    precondition measure at_rest(tol = 0.01);
    exception Saturated from torque_saturation : adjust ctrl.kp = 200.0;
    exception TrackingLost from tracking_error(max = 0.2) : abort;
    postcondition measure at_goal(tol = 0.005);
"""


def test_phases_wait_for_sync_then_measurement_preconditions(orc):
    source = orc("input Ready;\n" + arm_task(clauses="""
        precondition Ready;
        precondition measure at_rest(tol = 0.01);
        postcondition emit Done;"""))
    t = Trace(rta(source, "T"), ["", "Ready", "", "T.at_rest", "@1", "@3.5"])
    assert t.outputs[0] == {"T.start"}                       # phase 1: waits for Ready
    assert t.outputs[1] == {"T.measure"}                     # measuring modules activated
    assert t.outputs[2] == set()                             # phase 2: waits for at_rest
    assert t.outputs[3] == {"T.activate"}                    # all modules activated
    assert t.outputs[4] == set() and t.statuses[4] == "running"
    assert t.outputs[5] == {"T.good_end", "Done"}            # T = 2 s after activation
    assert t.statuses[5] == "done"


def test_sync_precondition_present_at_start_is_seen(orc):
    source = orc("input Ready;\n" + arm_task(clauses="precondition Ready;"))
    t = Trace(rta(source, "T"), ["Ready"])
    assert t.outputs[0] == {"T.start", "T.measure", "T.activate"}


def test_measurement_precondition_watchdog_raises_its_timeout(orc):
    source = orc(arm_task(clauses="precondition measure at_rest(tol = 0.01) within 2 s;"))
    t = Trace(rta(source, "T"), ["@0", "@1", "@2.5"])
    assert t.statuses == ["running", "running", "failed"]
    assert t.reason == "at_rest_timeout"


def test_type1_exception_adjusts_and_the_task_goes_on(orc):
    source = orc(arm_task(clauses=PAPER))
    t = Trace(rta(source, "T"), ["", "T.at_rest", "T.Saturated", "T.Saturated", "T.at_goal"])
    assert t.outputs[2] == {"T.Saturated.adjust"} and t.statuses[2] == "running"
    assert t.outputs[3] == {"T.Saturated.adjust"} and t.statuses[3] == "running"
    assert t.outputs[4] == {"T.good_end"} and t.statuses[4] == "done"


def test_type2_exception_kills_the_task_and_reaches_the_application(orc):
    source = orc(arm_task(clauses=PAPER))
    t = Trace(rta(source, "T"), ["", "T.at_rest", "T.TrackingLost", "T.at_goal"])
    assert t.statuses[2:] == ["failed", "failed"]
    assert t.reason == "TrackingLost"
    assert t.outputs[3] == set()  # killed: no good end afterwards


def test_type3_exception_aborts(orc):
    source = orc(arm_task(clauses="""
        module jl : joint_limits(margin = 0.05);
        connect arm.q -> jl.q;
        exception JointLimit from jl : fatal;
        exception TrackingLost from tracking_error(max = 0.2) : abort;"""))
    t = Trace(rta(source, "T"), ["", "T.JointLimit T.TrackingLost"])
    assert t.statuses[1] == "aborted" and t.reason == "JointLimit"  # type 3 wins


def test_exceptions_are_ignored_before_activation(orc):
    source = orc(arm_task(clauses=PAPER))
    t = Trace(rta(source, "T"), ["", "T.TrackingLost", "T.at_rest"])
    assert t.statuses == ["running", "running", "running"]


def test_paper_example_sizes():
    # RR-1801 §3.4.4: one measurement pre-condition, one type-1 and one type-2 exception,
    # one measurement post-condition: 3 states and 16 transitions in 1992. Ours: the same
    # three control states plus the terminated one, 10 transitions (see docs/robot-tasks.md).
    import tempfile
    from pathlib import Path

    from orccad_app.pipeline import load
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "paper.orc"
        clauses = PAPER.replace("at_goal(tol = 0.005)", "at_goal(tol = 0.005, goal = [1, 1, 1])")
        path.write_text(arm_task(clauses=clauses, duration=""))
        automaton = rta(load(path), "T")
    assert automaton.state_count == 4
    assert automaton.transition_count == 10
