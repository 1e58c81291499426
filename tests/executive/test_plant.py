"""The MuJoCo plant: sampling at read time, zero-order hold, torque limits, divergence."""

from __future__ import annotations

import numpy as np
import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.executive import MujocoPlant, PlantDivergenceError, Simulation
from orccad_app.tcs import TCS, ModuleTask, Port, ms, s

PENDULUM = """
<mujoco model="pendulum">
  <option timestep="0.001" integrator="RK4" gravity="0 0 -9.81"/>
  <worldbody>
    <body name="link">
      <joint name="hinge" type="hinge" axis="0 1 0"/>
      <geom type="sphere" pos="0 0 -1" size="0.05" mass="1"/>
      <inertial pos="0 0 -1" mass="1" diaginertia="1e-4 1e-4 1e-4"/>
    </body>
  </worldbody>
  <actuator><motor name="motor" joint="hinge" ctrlrange="-2 2" ctrllimited="true"/></actuator>
  <sensor><jointpos name="angle" joint="hinge"/></sensor>
</mujoco>
"""

WHEEL = """
<mujoco model="wheel">
  <option timestep="0.001" gravity="0 0 0"/>
  <worldbody>
    <body name="wheel">
      <joint name="axle" type="hinge" axis="0 0 1"/>
      <inertial pos="0 0 0" mass="1" diaginertia="0.5 0.5 0.5"/>
    </body>
  </worldbody>
  <actuator><motor joint="axle"/></actuator>
</mujoco>
"""


class Constant:
    """Writes ``tau`` once per job from a schedule ``{job index: torque}``; records ``q``."""

    def __init__(self, torques):
        self.torques = torques
        self.k = 0
        self.samples = []

    def compute(self, t_s, inputs):
        self.samples.append((t_s, inputs["q"].copy()))
        tau = self.torques.get(self.k)
        self.k += 1
        return {} if tau is None else {"tau": np.array([tau])}


def _sim(plant, compute, period=ms(10), wcet=ms(1)):
    tcs = TCS("plant")
    tcs.add(plant.resource)
    tcs.add(ModuleTask("ctl", period, wcet, compute, (Port("q", "in"), Port("tau", "out"))))
    tcs.connect(f"{plant.name}.q", "ctl.q")
    tcs.connect("ctl.tau", f"{plant.name}.tau")
    return Simulation(tcs, plants=[plant])


def test_plant_exposes_sensor_and_actuator_ports():
    plant = MujocoPlant("arm", xml=PENDULUM)
    ports = {(p.name, p.direction.value, p.dim) for p in plant.resource.ports}
    assert ports == {("q", "out", 1), ("qdot", "out", 1), ("angle", "out", 1), ("tau", "in", 1)}
    assert plant.timestep_ns == ms(1)


def test_pendulum_under_zero_torque_conserves_energy():
    plant = MujocoPlant("arm", xml=PENDULUM, qpos0=[1.0])
    start = plant.energy()
    sim = _sim(plant, Constant({0: 0.0}))
    sim.activate()
    sim.run(s(3))
    assert plant.time_ns == s(3)
    assert abs(plant.energy() - start) < 1e-6 * abs(start) + 1e-6
    assert np.max(np.abs(plant.qpos)) <= 1.0 + 1e-6  # it swings, it does not climb


def test_sensor_is_sampled_at_the_read_instant():
    plant = MujocoPlant("arm", xml=PENDULUM, qpos0=[0.5])
    compute = Constant({})
    sim = _sim(plant, compute)
    sim.activate()
    sim.run(ms(25))
    # the pendulum falls from rest: each release sees a smaller angle than the last.
    times = [t for t, _ in compute.samples]
    angles = [q[0] for _, q in compute.samples]
    assert times == [0.0, 0.01, 0.02]
    assert angles[0] == 0.5 and angles[0] > angles[1] > angles[2]


def test_torque_is_held_between_writes_zero_order_hold():
    plant = MujocoPlant("wheel", xml=WHEEL)
    # one write of 1 N·m at the end of the first job (1 ms), then nothing: the torque holds.
    sim = _sim(plant, Constant({0: 1.0}), period=ms(10), wcet=ms(1))
    sim.activate()
    sim.run(ms(500))
    assert plant.ctrl[0] == 1.0
    # constant torque 1 on inertia 0.5 from 1 ms: qdot = 2 * (t - 0.001) rad/s.
    assert plant.qvel[0] == pytest.approx(2 * 0.499, rel=1e-9)
    sim.kill()
    sim.run(ms(1000))
    assert plant.qvel[0] == pytest.approx(2 * 0.999, rel=1e-9)


def test_torques_are_clamped_to_the_limits():
    plant = MujocoPlant("arm", xml=PENDULUM)
    sim = _sim(plant, Constant({0: 50.0}))
    sim.activate()
    sim.run(ms(5))
    assert plant.ctrl[0] == 2.0 and plant.saturations == 1
    override = MujocoPlant("arm", xml=PENDULUM, torque_limits=0.5)
    sim = _sim(override, Constant({0: -50.0}))
    sim.activate()
    sim.run(ms(5))
    assert override.ctrl[0] == -0.5


def test_noise_and_quantization_are_seeded():
    def angles(seed):
        plant = MujocoPlant("arm", xml=PENDULUM, qpos0=[0.3], noise_std={"q": 1e-3},
                            quantization={"q": 1e-4})
        compute = Constant({})
        tcs = TCS("n")
        tcs.add(plant.resource)
        tcs.add(ModuleTask("ctl", ms(10), ms(1), compute, (Port("q", "in"),)))
        tcs.connect("arm.q", "ctl.q")
        sim = Simulation(tcs, plants=[plant], seed=seed)
        sim.activate()
        sim.run(ms(100))
        return np.array([q[0] for _, q in compute.samples])

    first = angles(5)
    assert np.array_equal(first, angles(5))
    assert not np.array_equal(first, angles(6))
    assert np.allclose(first / 1e-4, np.round(first / 1e-4), atol=1e-6)
    assert 0 < np.max(np.abs(first[:1] - 0.3)) < 5e-3


def test_divergence_raises_a_clear_error(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # without our handler MuJoCo logs to ./MUJOCO_LOG.TXT
    stiff = PENDULUM.replace('type="hinge"', 'type="hinge" stiffness="1e12"').replace(
        'integrator="RK4"', 'integrator="Euler"').replace('timestep="0.001"',
                                                          'timestep="0.01"')
    plant = MujocoPlant("arm", xml=stiff, qpos0=[0.5])
    sim = _sim(plant, Constant({}))
    sim.activate()
    with pytest.raises(PlantDivergenceError, match="plant 'arm' diverged") as raised:
        sim.run(s(2))
    assert "MuJoCo: " in raised.value.message  # its warning text, in the run's reason
    assert not (tmp_path / "MUJOCO_LOG.TXT").exists()


def test_bad_plant_configuration_is_reported():
    with pytest.raises(OrccadError, match="cannot load MJCF"):
        MujocoPlant("arm", xml="<mujoco><worldbody><body></mujoco>")
    with pytest.raises(OrccadError, match="unknown sensor port 'qq'"):
        MujocoPlant("arm", xml=PENDULUM, noise_std={"qq": 0.1})
    plant = MujocoPlant("arm", xml=PENDULUM)
    tcs = TCS("x", [ModuleTask("ctl", ms(10), ms(1))])
    with pytest.raises(OrccadError, match="not a physical resource"):
        Simulation(tcs, plants=[plant])
    tcs.add(plant.resource)
    with pytest.raises(OrccadError, match="has no plant"):
        Simulation(tcs)


def test_plant_ports_must_be_wired_asyn_asyn():
    plant = MujocoPlant("arm", xml=PENDULUM)
    tcs = TCS("w")
    tcs.add(plant.resource)
    tcs.add(ModuleTask("ctl", ms(10), ms(1), None, (Port("q", "in"),)))
    with pytest.raises(OrccadError, match="use asyn/asyn"):
        tcs.connect("arm.q", "ctl.q", "asyn/syn")


def test_a_write_between_grid_points_acts_from_its_exact_instant():
    plant = MujocoPlant("wheel", xml=WHEEL)
    # the job's 0.3 ms execution time delays the torque by exactly 0.3 ms (a partial step)
    sim = _sim(plant, Constant({0: 1.0}), period=ms(10), wcet=300_000)
    sim.activate()
    sim.run(ms(500))
    assert plant.time_ns == ms(500)
    assert plant.qvel[0] == pytest.approx(2 * (0.5 - 0.0003), rel=1e-9)
    # the grid is kept: a read at 500 ms needed no partial step after the one back onto it
    assert plant.steps == 500 + 1


def test_the_plant_reaches_an_instant_between_grid_points_exactly():
    plant = MujocoPlant("wheel", xml=WHEEL)
    sim = _sim(plant, Constant({0: 1.0}), period=ms(10), wcet=0)
    sim.activate()
    sim.run(ms(10) + 250_000)
    assert plant.time_ns == ms(10) + 250_000
    assert plant.qvel[0] == pytest.approx(2 * 0.01025, rel=1e-9)
