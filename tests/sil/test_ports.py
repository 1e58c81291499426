"""The real-time runtime's 8 port protocols (orccad_app/sil/c/orccad_port.c) do what the
executive's channels do (orccad_app/executive/channel.py, one processor): the same random
sequences of writes, reads and resets on each protocol give, in C and in Python, the same
results at each end — value, "none yet", blocked — and release the same waiting ends with the
same values. The C is compiled with AddressSanitizer and UndefinedBehaviorSanitizer (any
report fails the run) where the compiler has them."""

from __future__ import annotations

import random
import subprocess
from pathlib import Path

import pytest

from orccad_app.executive.block import BLOCK
from orccad_app.executive.channel import make_channel
from orccad_app.sil.build.compiler import CFLAGS, compiler
from orccad_app.sil.generate.library import C_DIR
from orccad_app.tcs.connection import Connection
from orccad_app.tcs.protocol import Protocol

#: the generated table's numbering (orccad_app/sil/generate/table.py, orccad_port.h)
PROTOCOLS = ["asyn/asyn", "syn/syn", "asyn/syn", "syn/asyn", "asyn/synF", "synF/asyn",
             "asyn/synD", "asyn/synDF"]
SANITIZE = ("-fsanitize=address,undefined", "-fno-sanitize-recover=all", "-g")


@pytest.fixture(scope="module")
def port_check(tmp_path_factory) -> Path:
    """The C driver of one port, with the sanitizers when the compiler links them."""
    target = tmp_path_factory.mktemp("ports") / "port_check"
    sources = [str(Path(__file__).parent / "c" / "port_check.c"), str(C_DIR / "orccad_port.c")]
    for extra in (SANITIZE, ()):
        done = subprocess.run([compiler(), *CFLAGS, *extra, "-I", str(C_DIR), *sources, "-o",
                               str(target)], capture_output=True, text=True, timeout=120)
        if done.returncode == 0:
            return target
    raise AssertionError(done.stderr)


def _operations(seed: int, count: int = 400) -> list[str]:
    """A random sequence a producer and a consumer could issue: an end that is blocked does
    nothing until released (tracked by the caller's model), resets now and then."""
    return [random.Random(seed * 1000 + k).choice("wwwrrrx" if k % 37 else "x")
            for k in range(count)]


class _End:
    """A Module-Task's job at one end of the channel (the channel wakes it)."""

    def __init__(self, log: list[str], name: str) -> None:
        self.runtime, self.log, self.name, self.waits_for = self, log, name, None

    def wake(self, job: _End, value: object = None) -> None:
        self.log.append(f"{self.name} woke {_text(value)}" if self.name == "R" else "W woke")

    def check_deadlock(self, job: _End) -> None:
        pass


def _text(value: object) -> str:
    return "none" if value is None else f"{value:g}"  # as the C driver prints it


def _python(protocol: str, operations: list[str]) -> tuple[list[str], list[str]]:
    """The executive's channel on ``operations``: its log, and the script for the C driver
    (a blocked end's operations dropped, as the C side must get the same commands)."""
    log: list[str] = []
    wakes: list[str] = []
    reader, writer = _End(wakes, "R"), _End(wakes, "W")
    channel = make_channel(Connection("p.out", "c.in", Protocol(protocol)), writer, reader,
                           None, None)
    script = [f"p {PROTOCOLS.index(protocol)}"]
    reading = writing = False
    value = 0
    for op in operations:
        if op == "x":
            channel.reset()
            reading = writing = False
            script.append("x")
            continue
        if (op == "w" and writing) or (op == "r" and reading):
            continue
        if op == "w":
            value += 1
            writing = not channel.write(writer, float(value))
            log.append("W blocked" if writing else "W done")
            script.append(f"w {value}")
        else:
            got = channel.read(reader)
            reading = got is BLOCK
            log.append("R blocked" if reading else f"R {_text(got)}")
            script.append("r")
        for line in sorted(wakes, key=lambda w: w[0] != "R"):  # the reader's first, as in C
            reading = reading and not line.startswith("R")
            writing = writing and not line.startswith("W")
            log.append(line)
        wakes.clear()
    return log, script


def _c(port_check: Path, script: list[str]) -> list[str]:
    done = subprocess.run([str(port_check)], input="\n".join(script) + "\n",
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert not done.stderr  # no sanitizer report
    return done.stdout.splitlines()


@pytest.mark.parametrize("protocol", PROTOCOLS)
def test_each_protocol_in_c_does_what_the_executive_does(port_check, protocol):
    for seed in range(3):
        expected, script = _python(protocol, _operations(seed))
        assert _c(port_check, script) == expected, (protocol, seed)
    if protocol in ("asyn/syn", "asyn/synF", "syn/syn", "asyn/synDF"):
        assert "R blocked" in expected  # these make a reader wait
    if protocol in ("syn/syn", "syn/asyn", "synF/asyn"):
        assert "W blocked" in expected  # these make a writer wait


def test_the_numbering_is_the_generated_tables():
    from orccad_app.sil.generate.table import PROTOCOL_NUMBERS

    assert list(PROTOCOL_NUMBERS) == PROTOCOLS
    assert {p.value for p in Protocol} == set(PROTOCOLS)
