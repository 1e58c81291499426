"""The executive's plant-extension hook, independently of the AUV: a toy extension on a
sliding block (per-step forces, extra sensor ports with noise, named faults, partial steps)."""

from __future__ import annotations

import numpy as np
import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.executive.kernel import Kernel
from orccad_app.control.plant_extension import PlantExtension
from orccad_app.executive.plant import MujocoPlant

BLOCK = """
<mujoco>
  <option timestep="0.01" gravity="0 0 0"/>
  <worldbody>
    <body name="block">
      <joint name="x" type="slide" axis="1 0 0"/>
      <inertial pos="0 0 0" mass="2" diaginertia="1 1 1"/>
    </body>
  </worldbody>
  <actuator><motor joint="x" ctrlrange="-1 1"/></actuator>
</mujoco>
"""


class Push(PlantExtension):
    """A constant push [N] on the block, the time it was applied [s], a 'brake' fault."""

    sensors = {"pushed_s": 1}
    faults = {"push": "the push [N]"}

    def __init__(self, push_n: float) -> None:
        self.push_n = push_n
        self.pushed_s = 0.0
        self.steps = 0

    def bind(self, model, data) -> None:
        self.data = data

    def step(self, dt_s: float) -> None:
        self.data.qfrc_applied[0] = self.push_n
        self.pushed_s += dt_s
        self.steps += 1

    def read(self, port: str) -> np.ndarray:
        return np.array([self.pushed_s])

    def inject(self, fault: str, value) -> None:
        self.push_n = float(value)


def _plant(**kwargs) -> tuple[MujocoPlant, Kernel]:
    plant = MujocoPlant("block", xml=BLOCK, extension=Push(4.0), **kwargs)
    kernel = Kernel(seed=1)
    plant.attach(kernel)
    return plant, kernel


def test_the_extension_acts_before_every_step_whole_or_partial():
    plant, kernel = _plant()
    plant.advance_to(1_005_000_000)  # 100 whole steps and a partial one
    assert plant.extension.steps == 101
    assert plant.extension.pushed_s == pytest.approx(1.005)
    assert plant.qvel[0] == pytest.approx(4.0 / 2.0 * 1.005)  # a = F / m


def test_extension_sensors_are_ports_with_noise_and_faults_apply_now():
    plant, kernel = _plant(noise_std={"pushed_s": 0.5})
    assert "pushed_s" in [port.name for port in plant.resource.ports]
    kernel.now = 500_000_000
    assert plant.sample("pushed_s")[0] != pytest.approx(0.5)  # noisy
    plant.inject("push", 0.0)
    speed = plant.qvel[0]
    plant.advance_to(2_000_000_000)
    assert plant.qvel[0] == pytest.approx(speed)
    with pytest.raises(OrccadError, match="no fault 'brake'"):
        plant.inject("brake", 1.0)


def test_a_plant_without_extension_has_no_faults():
    plant = MujocoPlant("block", xml=BLOCK)
    with pytest.raises(OrccadError, match=r"no fault 'push' \(faults: none\)"):
        plant.inject("push", 1.0)
    with pytest.raises(OrccadError, match="already has an extension"):
        extended, _ = _plant()
        extended.extend(Push(1.0))
