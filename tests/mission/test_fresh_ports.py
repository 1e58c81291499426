"""Issue 15, defect 1: every run of a Robot-Task starts with fresh ports as well as fresh
modules — a re-run never reads what its killed instance wrote (docs/executive.md, *What
runs*)."""

from __future__ import annotations

import numpy as np

from orccad_app.executive import Observer, Simulation
from orccad_app.mission.injection import parse_injection
from orccad_app.mission.run import MissionRun
from orccad_app.tcs import TCS, ModuleTask, Port, ms

RECOVERY = "missions/arm_recovery.orc"
KP, KV = 600.0, 40.0  # TrackPID(kp = 600.0) in ArmRecovery, kv = 40.0


class _Writes(Observer):
    """Every write (raw values) and the mission's Robot-Task starts."""

    def __init__(self) -> None:
        self.writes: list[tuple[int, str, str, object]] = []
        self.starts: list[tuple[int, str]] = []

    def on_write(self, t_ns: int, module: str, port: str, value: object) -> None:
        self.writes.append((t_ns, module, port, value))

    def on_task_start(self, t_ns: int, task: str, site: int, args: dict) -> None:
        self.starts.append((t_ns, task))


def _first_writes(log: _Writes, module: str, port: str) -> list[tuple[int, np.ndarray]]:
    """Per run of the module's Robot-Task: the first value it wrote on ``port``."""
    task = module.split(".")[0]
    writes = [(t, np.asarray(v, float)) for t, m, p, v in log.writes
              if m == module and p == port]
    firsts = []
    for start, name in log.starts:
        if name == task:
            firsts.append(next(w for w in writes if w[0] >= start))
    return firsts


def test_a_rerun_of_trackpid_commands_no_torque_spike(plan_file):
    plan = plan_file(RECOVERY)
    log = _Writes()
    result = MissionRun(plan, observers=[log], until_ns=12_000_000_000,
                        injections=[parse_injection("TrackPID.TrackingLost@2.5")]).run()
    runs = [r for r in result.robot_tasks if r.name == "TrackPID"]
    assert len(runs) == 2 and runs[0].outcome == "TrackingLost"
    errors = _first_writes(log, "TrackPID.ctrl", "e")
    torques = _first_writes(log, "TrackPID.ctrl", "tau")
    assert len(errors) == len(torques) == 2
    for (_, e), (_, tau) in zip(errors, torques):
        # Home leaves the arm at rest on q_d(0) = [1, 1, 1]: the true error is a few 1e-2 rad
        assert np.max(np.abs(e)) < 0.05
        # the PID law's bound for that error, the arm at rest (|ė| < 0.1 rad/s)
        assert np.all(np.abs(tau) <= KP * np.abs(e) + KV * 0.1 + 1e-9), (e, tau)


def test_a_retried_task_does_not_raise_from_the_killed_instances_error(plan_file):
    # the first TrackPID is lost for real (gains too low for a fast cosine): its last
    # error is above 0.2 rad; the retry must not read it.
    plan = plan_file(RECOVERY, {"omega = pi": "omega = 4 * pi"})
    log = _Writes()
    result = MissionRun(plan, observers=[log], until_ns=20_000_000_000).run()
    starts = [t for t, name in log.starts if name == "TrackPID"]
    lost = [x.time_ns for x in result.exceptions if x.name == "TrackingLost"]
    assert len(starts) >= 2 and lost
    for start in starts:
        assert not [t for t in lost if start <= t < start + 10_000_000], (starts, lost)


class _Counter:
    def __init__(self) -> None:
        self.count = 0

    def compute(self, t_s: float, inputs: dict) -> dict:
        self.count += 1
        return {"y": float(self.count)}


class _Recorder:
    def __init__(self) -> None:
        self.seen: list = []

    def compute(self, t_s: float, inputs: dict) -> dict:
        self.seen.append(inputs.get("x"))
        return {}


def test_reset_ports_brings_every_protocol_back_to_its_initial_value():
    for protocol in ("asyn/asyn", "syn/asyn", "synF/asyn", "asyn/synD"):
        tcs = TCS("t")
        tcs.add(ModuleTask("P", ms(1), ms(0.1), _Counter(), (Port("y", "out", "vector"),),
                           priority=1))
        recorder = _Recorder()
        tcs.add(ModuleTask("C", ms(1), ms(0.1), recorder, (Port("x", "in", "vector"),),
                           offset_ns=ms(0.5), priority=2))
        tcs.connect("P.y", "C.x", protocol)
        sim = Simulation(tcs)
        sim.activate()
        sim.run(ms(3))
        assert recorder.seen[-1] is not None, protocol
        sim.kill(["P", "C"])
        sim.run(ms(4))
        sim.reset_ports(["C"])
        sim.activate(["C"])
        sim.run(ms(5))
        # C alone, restarted: its producer has not written since, it reads "none yet"
        assert recorder.seen[-1] is None, protocol
