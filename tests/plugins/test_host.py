"""The plugin host: entry points, failure isolation, blocking, check_pending."""

import pytest

from orccad_app.control.catalogue import COSINE
from orccad_app.control.trajectories import Cosine
from orccad_app.control.kinds import TrajectoryKind
from orccad_app.control.params import ParamSpec
from orccad_app.diagnostics import OrccadError
from orccad_app.plugin_host import (
    PluginHost,
    hookimpl,
)

from tests.plugins.conftest import install_dist_info, run_cli

BUILT_IN = {"robot_types": {"arm3dof": "orccad_arm3dof"},
            "control_laws": {"pid": "orccad_control", "generic": "orccad_control",
                             "computed_torque": "orccad_control"},
            "task_functions": {"joint_tracking": "orccad_control",
                               "cartesian_tracking": "orccad_control"},
            "trajectories": {"cosine": "orccad_control", "min_jerk": "orccad_control",
                             "constant": "orccad_control"},
            "observers": {name: "orccad_observers" for name in (
                "joint_limits", "tracking_error", "singularity", "torque_saturation",
                "at_rest", "at_goal", "sensor_threshold")},
            "module_kinds": {"trajectory": "orccad_control", "control_law": "orccad_control"}}

SINE = TrajectoryKind("sine", "test trajectory", (ParamSpec("q0", "vector", None),),
                      lambda p: Cosine(p["q0"]))


class GoodPlugin:
    @staticmethod
    @hookimpl
    def orccad_register_trajectories(register):
        register(SINE)


class RaisingPlugin:
    """Registers a trajectory, then fails in a later hook: everything is withdrawn."""

    @staticmethod
    @hookimpl
    def orccad_register_trajectories(register):
        register(TrajectoryKind("wave", "", (), lambda p: None))

    @staticmethod
    @hookimpl
    def orccad_register_observers(register):
        raise RuntimeError("sensor table missing")


def load(*plugins):
    return PluginHost.load(plugins=plugins, blocked=())


def test_built_in_plugins_come_through_the_entry_points(host):
    assert set(host.plugins) >= {"orccad_control", "orccad_arm3dof", "orccad_observers"}
    assert all(info.distribution == "orccad" for info in host.plugins.values())
    for category, expected in BUILT_IN.items():
        registry = getattr(host.registries, category)
        assert {name: registry.plugin_of(name) for name in expected} == expected
    assert host.failures == []


def test_a_plugin_that_raises_is_reported_and_the_others_keep_working():
    host = load(("good", GoodPlugin()), ("raising", RaisingPlugin()))
    [failure] = host.failures
    assert (failure.plugin, failure.stage) == ("raising", "orccad_register_observers")
    assert failure.message == "RuntimeError: sensor table missing"
    assert "plugin 'raising' disabled" in failure.format()
    assert "wave" not in host.trajectories and "raising" not in host.plugins
    assert host.trajectories.plugin_of("sine") == "good"
    assert "pid" in host.control_laws and "joint_limits" in host.observers


def test_invalid_items_disable_their_plugin():
    class WrongType:
        @staticmethod
        @hookimpl
        def orccad_register_control_laws(register):
            register(COSINE)  # a trajectory kind, not a law kind

    host = load(("wrong", WrongType()))
    [failure] = host.failures
    assert failure.plugin == "wrong"
    assert "control law 'cosine': must be a LawKind, got TrajectoryKind" in failure.message


def test_a_name_clash_refuses_only_the_clashing_contribution_naming_both_plugins():
    class Clash:
        @staticmethod
        @hookimpl
        def orccad_register_trajectories(register):
            register(COSINE)
            register(SINE)

    host = load(("clash", Clash()))
    [failure] = host.failures
    assert failure.plugin == "clash" and not failure.disabled
    assert failure.message == ("trajectory 'cosine' is already provided by plugin "
                               "'orccad_control'; plugin 'clash''s trajectory 'cosine' is ignored")
    assert host.trajectories.plugin_of("cosine") == "orccad_control"
    assert host.trajectories.plugin_of("sine") == "clash"  # its other contribution stays
    assert "clash" in host.plugins


def test_every_command_warns_once_on_stderr_when_a_plugin_clashes(tmp_path):
    package = tmp_path / "clash_plugin.py"
    package.write_text("from orccad_app.plugin_api import LAW_KINDS, hookimpl\n\n"
                       "@hookimpl\n"
                       "def orccad_register_control_laws(register):\n"
                       "    register(LAW_KINDS[0])  # a second 'pid'\n", encoding="utf-8")
    install_dist_info(tmp_path, "clash-plugin", "1.0", {"clash": "clash_plugin"})
    result = run_cli("compile", "missions/arm_pid.orc", "--format", "summary",
                     pythonpath=tmp_path)
    assert result.returncode == 0, result.stderr
    warning = ("orccad: warning: plugin 'clash': orccad_register_control_laws: control law "
               "'pid' is already provided by plugin 'orccad_control'; plugin 'clash''s control "
               "law 'pid' is ignored")
    assert result.stderr.count(warning) == 1, result.stderr


def test_a_misspelt_hook_is_caught_by_check_pending():
    class Typo:
        @staticmethod
        def orccad_register_trajectory(register):  # recognized by its prefix, no such hook
            register(SINE)

    host = load(("typo", Typo()))
    [failure] = host.failures
    assert failure.stage == "validation" and "orccad_register_trajectory" in failure.message
    assert "sine" not in host.trajectories


def test_a_hook_with_unknown_arguments_fails_validation():
    class BadArguments:
        @staticmethod
        @hookimpl
        def orccad_register_trajectories(register, robot):
            register(SINE)

    host = load(("bad", BadArguments()))
    assert [(f.plugin, f.stage) for f in host.failures] == [("bad", "validation")]


def test_a_failing_start_up_check_disables_the_plugin():
    class Picky(GoodPlugin):
        @staticmethod
        @hookimpl
        def orccad_plugins_loaded(host):
            raise OrccadError("needs the 'auv' robot type")

    host = load(("picky", Picky()))
    [failure] = host.failures
    assert failure.stage == "orccad_plugins_loaded" and failure.message == (
        "needs the 'auv' robot type")
    assert "sine" not in host.trajectories


def test_blocked_plugins_are_not_loaded():
    host = PluginHost.load(blocked=["orccad_observers"])
    assert "orccad_observers" not in host.plugins and len(host.observers) == 0
    assert "arm3dof" in host.robot_types


def test_module_kind_finds_module_kinds_and_observers(host):
    assert host.module_kind("control_law").name == "control_law"
    assert host.module_kind("joint_limits").is_observer
    with pytest.raises(OrccadError, match="unknown module kind 'joint_limit' "
                                          r"\(did you mean 'joint_limits'"):
        host.module_kind("joint_limit")
    assert host.provider("observers", "at_rest") == "orccad_observers"


def test_there_is_no_process_wide_host_each_load_is_independent():
    import orccad_app.plugin_host.host as module

    first, second = PluginHost.load(), PluginHost.load()
    assert first is not second and "arm3dof" in first.robot_types
    assert not hasattr(module, "default_host")


def test_the_environment_variable_blocks_named_plugins():
    import os

    env = dict(os.environ, ORCCAD_DISABLE_PLUGINS="orccad_observers, orccad_arm3dof")
    result = run_cli("plugins", env=env)
    assert result.returncode == 0
    assert "observers: none" in result.stdout and "robot types: none" in result.stdout
    assert "disabled by ORCCAD_DISABLE_PLUGINS: orccad_arm3dof, orccad_observers" in result.stdout
    assert "pid" in result.stdout


def test_a_plugin_that_fails_to_import_is_reported_by_name(tmp_path):
    install_dist_info(tmp_path, "broken-plugin", "1.0", {"broken": "no_such_module_xyz"})
    result = run_cli("plugins", pythonpath=tmp_path)
    assert result.returncode == 0
    assert "warning: plugin 'broken' disabled: import: ModuleNotFoundError" in result.stderr
    assert "Traceback" not in result.stderr
    assert "arm3dof" in result.stdout and "joint_limits" in result.stdout


class ExitingPlugin:
    """Calls sys.exit in a hook (issue 28: the command ended with exit 3 'this is a bug')."""

    @staticmethod
    @hookimpl
    def orccad_register_trajectories(register):
        import sys

        sys.exit(4)


def test_a_plugin_calling_sys_exit_in_a_hook_is_disabled_like_one_that_raises():
    host = load(("good", GoodPlugin()), ("exiting", ExitingPlugin()))
    [failure] = host.failures
    assert (failure.plugin, failure.stage) == ("exiting", "orccad_register_trajectories")
    assert failure.message == "called sys.exit(4)"
    assert "exiting" not in host.plugins and host.trajectories.plugin_of("sine") == "good"


def test_a_plugin_calling_sys_exit_at_import_is_reported_and_the_command_goes_on(tmp_path):
    (tmp_path / "exiting_at_import.py").write_text("import sys\nsys.exit('no licence')\n",
                                                   encoding="utf-8")
    install_dist_info(tmp_path, "exiting-plugin", "1.0", {"exiting": "exiting_at_import"})
    result = run_cli("plugins", pythonpath=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "warning: plugin 'exiting' disabled: import: called sys.exit('no licence')" \
        in result.stderr
    assert "arm3dof" in result.stdout
