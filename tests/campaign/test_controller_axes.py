"""The spec's ``[controller]`` axes: a real controller's exchange period and release jitter
drawn per run (``--exchange-us``, ``--jitter-us``), replayed by ``orccad run``."""

from __future__ import annotations

import re

import pytest

from orccad_app.campaign.adapter import CompiledMission, execute
from orccad_app.campaign.setting import RunSetting, draw_setting
from orccad_app.campaign.spec import parse_spec
from orccad_app.diagnostics import OrccadError

from .conftest import ROOT

PID = str(ROOT / "missions" / "arm_pid.orc")
SPEC = """\
mission = "ArmPID"
seed = 1
until_s = 0.3

[timing]
"TrackPID.ctrl.wcet_ms" = "U(0.1, 0.5)"

[controller]
exchange_us = "U(100, 1000)"
jitter_us = "U(0, 200)"
"""


def test_the_axes_are_drawn_whole_ns_and_given_to_the_run_and_its_replay():
    spec = parse_spec(SPEC, "d.toml")
    assert [(e.target, e.dist.bounds) for e in spec.controller] == [
        ("exchange_us", (100, 1000)), ("jitter_us", (0, 200))]
    setting = draw_setting(spec, 3, 0.3)
    assert 100 <= setting.exchange_us <= 1000 and 0 <= setting.jitter_us <= 200
    assert setting.exchange_us * 1000 == round(setting.exchange_us * 1000)
    args = setting.run_args()
    assert args[args.index("--exchange-us") + 1] == repr(setting.exchange_us)
    assert args[args.index("--jitter-us") + 1] == repr(setting.jitter_us)
    assert setting.values["controller.exchange_us"] == setting.exchange_us
    options = setting.options()
    assert options.delays.exchange_ns == round(setting.exchange_us * 1000)
    assert options.delays.jitter_ns == round(setting.jitter_us * 1000)
    assert RunSetting.from_dict(setting.as_dict()) == setting
    # the campaign's run is orccad run with the replay's options
    compiled = CompiledMission(PID)
    record = execute(compiled, setting)
    ideal = execute(compiled, RunSetting(3, setting.seed, 0.3, timings=setting.timings))
    assert record.metrics != ideal.metrics


def test_a_spec_without_controller_axes_draws_as_before():
    without = parse_spec(SPEC.split("[controller]")[0], "d.toml")
    setting = draw_setting(without, 3, 0.3)
    assert (setting.exchange_us, setting.jitter_us) == (0.0, 0.0)
    assert "--exchange-us" not in setting.run_args()
    assert setting.timings == draw_setting(parse_spec(SPEC, "d.toml"), 3, 0.3).timings


@pytest.mark.parametrize("text, message", [
    ("[controller]\nexchange = 1\n", "unknown key 'exchange' in [controller]"),
    ("[controller]\njitter_us = \"U(-1, 5)\"\n", "must draw microseconds in [0, 1e+06]"),
    ("[controller]\nexchange_us = 2e6\n", "must draw microseconds"),
])
def test_bad_controller_axes_are_located(text, message):
    with pytest.raises(OrccadError, match=re.escape(message)) as caught:
        parse_spec(text, "s.toml")
    assert caught.value.location.line == 2
