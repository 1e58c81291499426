"""A plugin kind's C (ModuleKind.c_implementation, docs/deploy.md): the test plugin's
``low_pass`` filter (docs/plugins.md's) between the arm's encoders and the PID law runs in
the controller from the plugin's own C file, and the lockstep run ends as the executive's;
without C the same kind is refused with its name and the reason."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from orccad_app.pipeline import load, select_mission
from orccad_app.plugin_api import (REQUIRED, CField, CFieldType, CImplementation,
                                   ModuleInstance, ModuleKind, OrccadError, ParamSpec, PortSpec,
                                   PluginHost, Timing, hookimpl, kind_header)
from orccad_app.session import ControllerOptions, Execution, RunOptions, RunSession
from orccad_app.sil.generate.layout import NoCImplementation

from tests.sil.helpers import MISSIONS, report

LOW_PASS_C = Path(__file__).parent / "c" / "low_pass.c"


class _LowPassInstance(ModuleInstance):
    def init(self) -> None:
        super().init()
        self._y: np.ndarray | None = None
        self._t = 0.0

    def compute(self, t_s: float, inputs: dict) -> dict:
        u = inputs.get("u")
        if u is None:
            return {}
        u = np.asarray(u, dtype=float)
        if self._y is None:
            self._y = u
        else:
            alpha = 1.0 - math.exp(-2.0 * math.pi * self.params["cutoff"] * (t_s - self._t))
            self._y = self._y + alpha * (u - self._y)
        self._t = t_s
        return {"y": self._y.copy()}


class LowPass(ModuleKind):
    """First-order low-pass filter of a vector (docs/plugins.md's), with its C."""

    name = "low_pass"
    summary = "first-order low-pass filter of a vector"
    ports = (PortSpec("u", "in", "vector", None, True, "signal"),
             PortSpec("y", "out", "vector", None, True, "filtered signal"))
    params = (ParamSpec("cutoff", "float", REQUIRED, "cut-off frequency [Hz]", 0.0, True),)
    default_timing = Timing.from_ms(1.0, 0.05)
    c_implementation = CImplementation(LOW_PASS_C, "low_pass",
                                       lambda instance: [instance.params["cutoff"]])

    def _instantiate(self, values, context):
        dim = context.robot.dof if context.robot is not None else None
        return _LowPassInstance(self, values, tuple(p.with_dim(dim) for p in self.ports))


class PythonOnlyLowPass(LowPass):
    c_implementation = None


class _Plugin:
    def __init__(self, kind: ModuleKind) -> None:
        self.kind = kind

    @hookimpl
    def orccad_register_module_kinds(self, register) -> None:
        register(self.kind)


def _mission(tmp_path) -> Path:
    """arm_pid for 1 s, the law reading the encoders through the plugin's filter."""
    text = (MISSIONS / "arm_pid.orc").read_text().replace("duration 4 s", "duration 1 s")
    text = text.replace("    connect arm.q       -> ctrl.q      : asyn/asyn;\n",
                        "    module filt : low_pass(cutoff = 150.0) period 1 ms wcet 0.05 ms "
                        "on cpu0 priority 1;\n"
                        "    connect arm.q -> filt.u : asyn/asyn;\n"
                        "    connect filt.y -> ctrl.q : asyn/asyn;\n")
    assert "filt.y -> ctrl.q" in text
    path = tmp_path / "arm_filtered.orc"
    path.write_text(text)
    return path


def _session(path: Path, kind: ModuleKind,
             execution: Execution = Execution.SIMULATED) -> RunSession:
    source = load(str(path), PluginHost.load([("sil_test_low_pass", _Plugin(kind))]))
    return RunSession(source, select_mission(source, None),
                      RunOptions(execution=execution, controller=ControllerOptions(str(path))))


def test_a_plugin_kinds_c_runs_in_the_controller_as_its_python_does(tmp_path):
    path = _mission(tmp_path)
    expected = report(_session(path, LowPass()).execute())
    got = report(_session(path, LowPass(), Execution.LOCKSTEP).execute())
    assert expected["status"] == "done"
    assert got == expected


def test_a_plugin_kind_without_c_is_refused_with_its_name_and_the_reason(tmp_path):
    path = _mission(tmp_path)
    with pytest.raises(NoCImplementation, match="low_pass") as refused:
        _session(path, PythonOnlyLowPass(), Execution.LOCKSTEP)
    assert "exists only in Python" in refused.value.message
    assert "c_implementation" in refused.value.message


def test_check_kinds_reports_the_first_difference_of_a_wrong_c(tmp_path):
    """``orccad sil --check-kinds``: the plugin's C agrees with its Python bit for bit; a C
    whose filter forgets the first sample (y starts at 0) is reported at its first job, with
    the Module-Task, the port and both values."""
    from orccad_app.mission.plan import plan_mission
    from orccad_app.sil.lockstep import check_kinds

    path = _mission(tmp_path)
    wrong = tmp_path / "low_pass_wrong.c"
    wrong.write_text(LOW_PASS_C.read_text().replace("y[i] = u[i];", "y[i] = 0.0;"))

    class WrongLowPass(LowPass):
        c_implementation = CImplementation(wrong, "low_pass",
                                           lambda instance: [instance.params["cutoff"]])

    for kind, agrees in ((LowPass(), True), (WrongLowPass(), False)):
        source = load(str(path), PluginHost.load([("sil_test_low_pass", _Plugin(kind))]))
        plan = plan_mission(source, select_mission(source, None))
        compared, difference = check_kinds(plan, str(path), jobs=20, seed=1)
        if agrees:
            assert difference is None, difference.text()
            assert compared == len(plan.tcs.module_tasks)
            continue
        assert difference is not None and difference.module == "TrackPID.filt"
        assert (difference.kind, difference.port) == ("low_pass", "y")
        assert difference.job == 0 and difference.c == pytest.approx([0.0] * 3)
        assert "module-task 'TrackPID.filt' (kind low_pass), job 0" in difference.text()


LOW_PASS_DECLARED_C = Path(__file__).parent / "c" / "low_pass_declared.c"


class DeclaredLowPass(LowPass):
    """The same filter, its parameters and state declared once: the words sent and the C
    structs (low_pass_d_kind.h) both come from the declaration."""

    c_implementation = CImplementation(
        LOW_PASS_DECLARED_C, "low_pass_d",
        lambda instance: {"cutoff_hz": instance.params["cutoff"]},
        param_fields=(CField("cutoff_hz", doc="cut-off frequency [Hz]"),),
        state_fields=(CField("primed", CFieldType.INT64, doc="1 once y holds a value"),
                      CField("last_t_s", doc="the previous job's time [s]"),
                      CField("y", size=16, doc="the filtered signal")))


def test_a_kind_declared_once_runs_in_the_controller_as_its_python_does(tmp_path):
    """A third-party-style kind whose parameters and state are declared once
    (CImplementation.param_fields, state_fields): its C reads typed structs from the generated
    header, no offset written by hand, and the lockstep run ends as the executive's."""
    from orccad_app.sil.lockstep import check_kinds
    from orccad_app.mission.plan import plan_mission

    path = _mission(tmp_path)
    expected = report(_session(path, DeclaredLowPass()).execute())
    got = report(_session(path, DeclaredLowPass(), Execution.LOCKSTEP).execute())
    assert expected["status"] == "done" and got == expected
    source = load(str(path), PluginHost.load([("declared", _Plugin(DeclaredLowPass()))]))
    plan = plan_mission(source, select_mission(source, None))
    assert check_kinds(plan, str(path), jobs=50, seed=2)[1] is None


def test_the_declaration_gives_the_words_and_the_header():
    c = DeclaredLowPass.c_implementation
    assert c.words(type("I", (), {"params": {"cutoff": 150.0}})()) == (150.0,)
    header = kind_header(c)
    assert "typedef struct {\n    double cutoff_hz; /* cut-off frequency [Hz] */\n} " \
           "low_pass_d_params;" in header
    assert "    int64_t primed; /* 1 once y holds a value */" in header
    assert "    double y[16]; /* the filtered signal */" in header
    assert "v.cutoff_hz = m->p[0];" in header


@pytest.mark.parametrize("given,words", [
    ({"cutoff_hz": 1.0, "gain": 2.0}, r"undeclared field\(s\) gain"),
    ({}, "no value for field 'cutoff_hz'"),
    ([1.0], "must give a mapping"),
])
def test_a_declared_kinds_params_must_match_its_declaration(given, words):
    c = CImplementation(LOW_PASS_DECLARED_C, "low_pass_d", lambda instance: given,
                        param_fields=(CField("cutoff_hz"),))
    with pytest.raises(OrccadError, match=words):
        c.words(None)


def test_a_declaration_is_checked_when_it_is_made():
    with pytest.raises(OrccadError, match="declared twice"):
        CImplementation(LOW_PASS_DECLARED_C, "x", dict, param_fields=(CField("a"), CField("a")))
    with pytest.raises(OrccadError, match="161 state words declared, the C runtime holds 160"):
        CImplementation(LOW_PASS_DECLARED_C, "x", dict, state_fields=(CField("s", size=161),))
    with pytest.raises(OrccadError, match="int64"):
        CImplementation(LOW_PASS_DECLARED_C, "x", lambda i: {"n": 2.5},
                        param_fields=(CField("n", CFieldType.INT64),)).words(None)


def test_the_built_in_plugins_carry_their_own_c_and_the_core_names_none_of_their_kinds():
    """The observers' and the AUV's kinds run from their plugins' own C files, through
    CImplementation as a third party's do (issue 36); no string in the core's Python names one
    of them."""
    import ast

    from orccad_app.sil.generate.layout import kind_c

    root = Path(__file__).resolve().parents[2]
    host = PluginHost.load()
    names = set()
    for registry in (host.registries.module_kinds, host.registries.observers):
        for entry in registry.entries():
            if entry.plugin not in ("orccad_observers", "orccad_auv"):
                continue
            names.add(entry.name)
            c = entry.item.c_implementation
            if c is not None:
                assert (root / "plugins" / entry.plugin) in c.source.parents, entry.name
                assert "runtime library" not in kind_c(entry.item)
    assert {"joint_limits", "at_rest", "auv_autopilot", "gps_fix"} <= names
    literals = set()
    for path in (root / "orccad_app").rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Constant) and isinstance(node.value, str):
                literals.add(node.value)
    literals.discard("tracking_error")  # the report's field of a run's error samples, not the kind
    assert not names & literals, sorted(names & literals)
