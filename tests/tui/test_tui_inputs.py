"""Inputs raised in the console are ``orccad run --inject`` (issue 28.2): a sequence of pulses,
a hold and a valued input replayed through the live session and through ``orccad run`` with
the instants the console reports gives the same trace and the same outputs; a hold is one
line of the report, not one per instant."""

from __future__ import annotations

import pytest

from orccad_app.cli import main
from orccad_app.trace import CsvTraceWriter, TraceRecorder
from orccad_app.tui.session import LiveSession
from orccad_app.tui.user_inputs import due_ns

RECOVERY = "missions/arm_recovery.orc"
UNTIL_S = 6.0


class _Keys:
    """Presses the console's keys at simulated instants: each ``(t [ns], action)`` runs once,
    at the first reaction at or after ``t`` (as a user's key reaches a running run)."""

    def __init__(self, steps):
        self.steps = sorted(steps, key=lambda step: step[0])

    def on_reaction(self, t_ns, inputs, outputs, status):
        while self.steps and t_ns >= self.steps[0][0]:
            self.steps.pop(0)[1]()


def _inject_args(records, tick_ns: int) -> list[str]:
    """``--inject`` arguments giving the console's records (a hold: one per tick)."""
    args = []
    for record in records:
        shown = record.name if record.value is None else f"{record.name}({record.value})"
        last = record.time_ns if record.until_ns is None else record.until_ns
        for time_ns in range(record.time_ns, last + 1, tick_ns):
            args += ["--inject", f"{shown}@{time_ns / 1e9!r}"]
    return args


def _section(report: str, title: str) -> list[str]:
    lines = report.splitlines()
    start = lines.index(title) + 1
    end = next((i for i in range(start, len(lines)) if not lines[i].startswith("  ")),
               len(lines))
    return lines[start:end]


@pytest.fixture(scope="module")
def console_run(tmp_path_factory):
    """Gripper(0.8) pulsed at 1.606 s, Hold held 1.871–2.143 s (the tracking suspended),
    Gripper(0.3) at 2.5 s, then Stop at 3.2 s (the arm parks): the live session's trace,
    report and records."""
    session = LiveSession(RECOVERY, None, lambda update: None, speed=None, until_s=UNTIL_S)
    observer = session.observer
    session.run.add_observer(_Keys([
        (1_606_000_000, lambda: observer.raise_input("Gripper", 0.8)),
        (1_871_000_000, lambda: observer.hold("Hold")),
        (2_143_000_000, lambda: observer.release("Hold")),
        (2_500_000_000, lambda: observer.raise_input("Gripper", 0.3)),
        (3_200_000_000, lambda: observer.raise_input("Stop")),
    ]))
    folder = tmp_path_factory.mktemp("console")
    live = folder / "live.csv"  # the live run itself, recorded by the test
    writer = CsvTraceWriter(live)
    session.run.add_observer(TraceRecorder(writer))
    session.execute()
    writer.close()
    exported = folder / "console.csv"  # the console's export: the run replayed with a trace
    session.export(str(exported))
    return session, (live, exported), session.report()


def test_console_inputs_give_the_run_of_inject_at_the_reported_instants(console_run, tmp_path,
                                                                        capsys):
    session, (live_trace, exported_trace), console_report = console_run
    records = session.observer.injected
    tick = session.run.tick_ns
    pressed = [1_606_000_000, 1_871_000_000, 2_500_000_000, 3_200_000_000]
    assert [r.name for r in records] == ["Gripper", "Hold", "Gripper", "Stop"]
    # queued at the reaction after the key (the probe runs after the console's observer),
    # taking effect at the due instant: the second tick after that reaction
    assert [r.time_ns for r in records] == [due_ns(t + tick, tick) for t in pressed]
    hold = records[1]
    assert hold.until_ns == due_ns(2_143_000_000 + tick, tick) - tick
    assert hold.instants == (hold.until_ns - hold.time_ns) // tick + 1
    cli_trace = tmp_path / "cli.csv"
    status = main(["run", RECOVERY, "--until", str(UNTIL_S), "--trace", str(cli_trace),
                   *_inject_args(records, tick)])
    cli_report = capsys.readouterr().out
    assert status == 0
    assert live_trace.read_text() == cli_trace.read_text()  # row for row, bit for bit
    assert exported_trace.read_text() == cli_trace.read_text()  # the export is that run
    assert _section(console_report, "Outputs:") == _section(cli_report, "Outputs:")
    assert "Stopping" in "\n".join(_section(cli_report, "Outputs:"))


def test_a_hold_is_one_line_of_the_report_and_of_the_log(console_run):
    session, _, report = console_run
    injections = _section(report, "Injections:")
    held = [line for line in injections if "Hold" in line]
    hold = session.observer.injected[1]
    assert held == [f"  {hold.time_ns / 1e9:.3f}–{hold.until_ns / 1e9:.3f} s  Hold (input, "
                    f"user (held), at {hold.instants} instants)"]
    assert len(injections) == 4  # two Gripper pulses, the hold, Stop


def test_the_log_says_when_a_hold_starts_and_ends(tmp_path):
    updates = []
    session = LiveSession(RECOVERY, None, updates.append, speed=None, until_s=0.5)
    observer = session.observer
    session.run.add_observer(_Keys([(100_000_000, lambda: observer.hold("Hold")),
                                    (300_000_000, lambda: observer.release("Hold"))]))
    session.execute()
    log = [entry.text for update in updates for entry in update.log if entry.kind == "input"]
    assert log == ["Hold held by the user",
                   "Hold released by the user (held 0.103–0.302 s, 200 instants)"]



#: The topics of ``orccad run --trace X.mcap`` beyond the events (issue 26.1).
FOXGLOVE_TOPICS = ("/tf", "/scene", "/params/", "/mission/phase/", "/mission/state",
                   "/properties/")


def _messages(path) -> list[tuple[str, int, bytes]]:
    from mcap.reader import make_reader

    with open(path, "rb") as stream:
        return [(channel.topic, message.log_time, message.data)
                for _, channel, message in make_reader(stream).iter_messages()]


def test_a_run_in_its_own_process_exports_the_mcap_of_orccad_run_with_every_topic(
        tmp_path, capsys, monkeypatch):
    """The console's run (in its own process, keys pressed as its frames arrive) exported
    as MCAP is ``orccad run --trace X.mcap --inject …`` at the reported instants, message for
    message, the Foxglove topics (frames, scene, gains, phases, state, verdicts) included."""
    # frames every 20 ms of the run's CPU time, not 250: the 2 s run now takes about 0.4 s
    # of CPU, one frame at the default rate, and no key would be pressed (the fork inherits it)
    monkeypatch.setattr("orccad_app.tui.live.BUSY_FRAME_S", 0.02)
    pressed = []

    def post(update):  # the UI's side: a key when a frame shows the run past 0.5 s, then 1 s
        for at, name, value in ((0.5e9, "Gripper", 0.8), (1e9, "Stop", None)):
            if update.time_ns > at and name not in pressed:
                pressed.append(name)
                session.observer.raise_input(name, value)

    session = LiveSession(RECOVERY, None, post, speed=None, until_s=2.0, own_process=True)
    assert session.own_process
    session.execute()
    records = session.observer.injected
    assert [r.name for r in records] == pressed[:len(records)] and records
    exported = tmp_path / "console.mcap"
    session.export(str(exported))
    cli = tmp_path / "cli.mcap"
    main(["run", RECOVERY, "--until", "2", "--trace", str(cli),
          *_inject_args(records, session.run.tick_ns)])
    capsys.readouterr()
    console, reference = _messages(exported), _messages(cli)
    topics = {topic for topic, _, _ in reference}
    for prefix in FOXGLOVE_TOPICS:
        assert any(topic.startswith(prefix) for topic in topics), prefix
    assert console == reference
