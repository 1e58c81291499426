"""A real controller's delays (orccad_app/executive/delays.py): the robot's ports exchanged on a
period of their own, the releases' jitter; deterministic under the seed."""

from __future__ import annotations

import numpy as np
import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.executive import MujocoPlant, Observer, Simulation
from orccad_app.executive.delays import ControllerDelays
from orccad_app.executive.kernel import Kernel
from orccad_app.tcs import TCS, ModuleTask, Port, ms

PENDULUM = """
<mujoco model="pendulum">
  <option timestep="0.001" integrator="RK4" gravity="0 0 -9.81"/>
  <worldbody>
    <body name="link">
      <joint name="hinge" type="hinge" axis="0 1 0"/>
      <inertial pos="0 0 -1" mass="1" diaginertia="1e-4 1e-4 1e-4"/>
    </body>
  </worldbody>
  <actuator><motor joint="hinge"/></actuator>
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


class Scripted:
    """Writes ``tau`` at job ``k`` from ``{k: torque}``; records what it read of ``q``."""

    def __init__(self, torques=None):
        self.torques = torques or {}
        self.k = 0
        self.samples = []

    def compute(self, t_s, inputs):
        self.samples.append((round(t_s * 1e9), float(inputs["q"][0])))
        tau = self.torques.get(self.k)
        self.k += 1
        return {} if tau is None else {"tau": np.array([tau])}


class Releases(Observer):
    def __init__(self):
        self.at = []
        self.responses = []

    def on_release(self, t_ns, module, job):
        self.at.append(t_ns)

    def on_finish(self, t_ns, module, job, response_ns, missed):
        self.responses.append((t_ns, response_ns))


def _sim(plant, compute, delays, period=ms(1), wcet=ms(1) // 10, seed=0, observers=()):
    tcs = TCS("delays")
    tcs.add(plant.resource)
    tcs.add(ModuleTask("ctl", period, wcet, compute, (Port("q", "in"), Port("tau", "out"))))
    tcs.connect(f"{plant.name}.q", "ctl.q")
    tcs.connect("ctl.tau", f"{plant.name}.tau")
    return Simulation(tcs, plants=[plant], seed=seed, delays=delays, observers=observers)


def _phase(seed: int, period_ns: int) -> int:
    return int(Kernel(seed).stream("exchange/phase").integers(0, period_ns))


def test_a_torque_is_applied_at_the_next_exchange_not_when_written():
    period = ms(4)
    phase = _phase(0, period)
    plant = MujocoPlant("wheel", xml=WHEEL)
    sim = _sim(plant, Scripted({0: 1.0}), ControllerDelays(exchange_ns=period),
               period=ms(100), wcet=ms(1))
    sim.activate()
    sim.run(ms(500))
    applied = phase if phase > ms(1) else phase + period  # the first exchange after 1 ms
    # constant torque 1 on inertia 0.5 from the exchange: qdot = 2 (t - applied) rad/s.
    assert plant.qvel[0] == pytest.approx(2 * (0.5 - applied / 1e9), rel=1e-9)
    ideal = MujocoPlant("wheel", xml=WHEEL)
    sim = _sim(ideal, Scripted({0: 1.0}), ControllerDelays(), period=ms(100), wcet=ms(1))
    sim.activate()
    sim.run(ms(500))
    assert ideal.qvel[0] == pytest.approx(2 * 0.499, rel=1e-9)  # applied at the write, 1 ms


def test_a_sensor_read_sees_the_last_exchange():
    period = ms(5)
    phase = _phase(0, period)
    plant = MujocoPlant("arm", xml=PENDULUM, qpos0=[0.5])
    compute = Scripted()
    sim = _sim(plant, compute, ControllerDelays(exchange_ns=period))
    sim.activate()
    sim.run(ms(40))

    def last_exchange(t_ns):
        return 0 if t_ns < phase else phase + (t_ns - phase) // period * period

    by_exchange: dict[int, set[float]] = {}
    for t_ns, q in compute.samples:
        by_exchange.setdefault(last_exchange(t_ns), set()).add(q)
    # every read between two exchanges sees one value; the falling pendulum's value changes
    # from one exchange to the next
    assert all(len(values) == 1 for values in by_exchange.values())
    values = [next(iter(by_exchange[k])) for k in sorted(by_exchange)]
    assert len(values) >= 8 and all(a > b for a, b in zip(values, values[1:]))
    assert sim.exchange is not None and sim.exchange.exchanges >= len(by_exchange)


def test_a_torque_written_before_its_module_task_is_killed_is_dropped():
    plant = MujocoPlant("wheel", xml=WHEEL)
    sim = _sim(plant, Scripted({0: 1.0}), ControllerDelays(exchange_ns=ms(50)),
               period=ms(100), wcet=ms(1))
    sim.activate()
    sim.kill(at_ns=ms(2))
    sim.run(ms(200))
    assert plant.qvel[0] == 0.0 and plant.ctrl[0] == 0.0


def _jittered(seed, jitter_ns=ms(1) // 2):
    releases = Releases()
    plant = MujocoPlant("arm", xml=PENDULUM, qpos0=[0.5])
    sim = _sim(plant, Scripted(), ControllerDelays(jitter_ns=jitter_ns), period=ms(1),
               wcet=ms(1) // 10, seed=seed, observers=[releases])
    sim.activate()
    sim.run(ms(200))
    return releases


def test_releases_are_late_by_at_most_the_jitter_on_the_period_grid():
    jitter = ms(1) // 2
    releases = _jittered(0, jitter)
    late = [t - k * ms(1) for k, t in enumerate(releases.at)]
    assert len(late) == 200 and all(0 <= x <= jitter for x in late)  # no drift
    assert len(set(late)) > 100  # drawn, not constant
    # the response time counts from the grid instant: lateness included
    assert all(response >= ms(1) // 10 for _, response in releases.responses)
    assert max(response for _, response in releases.responses) > ms(1) // 10 + jitter // 2


def test_jitter_is_deterministic_under_the_seed():
    assert _jittered(3).at == _jittered(3).at
    assert _jittered(3).at != _jittered(4).at


def test_no_delays_is_the_ideal_exchange_bit_for_bit():
    def run(delays):
        plant = MujocoPlant("arm", xml=PENDULUM, qpos0=[0.5])
        compute = Scripted({k: 0.1 for k in range(50)})
        sim = _sim(plant, compute, delays, seed=2)
        sim.activate()
        sim.run(ms(50))
        return compute.samples, plant.qpos.tolist()

    assert run(ControllerDelays()) == run(ControllerDelays(0, 0))
    assert run(ControllerDelays()) != run(ControllerDelays(exchange_ns=ms(1)))


@pytest.mark.parametrize("bad", [-1, 2_000_000_000, 1.5, True])
def test_bad_delays_are_refused(bad):
    with pytest.raises(OrccadError, match="must be an integer in"):
        ControllerDelays(exchange_ns=bad)
