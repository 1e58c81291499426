"""The compiled automata agree with an independent reference interpreter.

The compiler and the runtime share one interpreter (the constructive engine of
:mod:`orccad_app.reactive.engine`), so their agreement proves little. These tests run a second
interpreter, :mod:`tests.reactive.reference` (term rewriting, statuses by logical coherence),
on the same programs and inputs and require the same outputs, values and status at every
instant. Three traces are compared for each random program (:mod:`tests.reactive.strategies`):

- the reference on the program with its derived forms (``abort``, ``every``, ``repeat`` …)
  interpreted directly by their Esterel v5 meaning — this checks
  :mod:`orccad_app.reactive.derived`;
- the reference on the kernel expansion of the program (what the compiler receives);
- the compiled, minimized automaton run by :class:`~orccad_app.reactive.runtime.Reactor`.

The same random programs and inputs also run on the automaton built on demand
(:class:`~orccad_app.reactive.lazy.LazyAutomaton`, what ``run`` and ``react`` use), which must
give the full automaton's outputs, values and status, and reach states with the same labels, at
every instant.

Programs the compiler rejects are skipped. That includes programs that are *logically*
correct but not *constructive* (``signal S { if S { emit S; } else { emit S; } }`` has the
single coherent solution "S present", but nothing forces S before it is tested): Esterel v5
and this compiler reject them, the logical reference accepts them — a documented, legitimate
difference (:func:`test_logically_correct_but_not_constructive_is_rejected_by_the_compiler`).
The converse cannot happen (constructive programs are logically correct), so when the
reference finds an instant with no or several coherent solutions, the compiler must have
rejected the program.
"""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, assume, event, given, note, settings

from orccad_app.diagnostics import OrccadError
from orccad_app.lang.parser import parse
from orccad_app.reactive import ir
from orccad_app.reactive.compiler import compile_program
from orccad_app.reactive.lazy import LazyAutomaton
from orccad_app.reactive.lower import lower_mission
from orccad_app.reactive.runtime import Reactor
from orccad_app.reactive.script import parse_script
from tests.reactive.conftest import mission
from tests.reactive.reference import terms as ref
from tests.reactive.reference.errors import NotCoherent, ReferenceError_
from tests.reactive.reference.reactor import ReferenceReactor
from tests.reactive.strategies import A, B, INPUTS, O1, O2, OUTPUTS, expand, input_sequences, \
    programs, show_program

#: Random programs checked per run (each on 10-20 instants); about 25 s on one core.
MAX_EXAMPLES = 1000
#: Random programs run on both the lazy and the full automaton.
LAZY_EXAMPLES = 300
#: Compilation budget for random programs (bigger ones are skipped, not failed).
MAX_STATES = 2000

CROSS_CHECK = settings(
    max_examples=MAX_EXAMPLES, deadline=None, derandomize=True, database=None,
    suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow,
                           HealthCheck.data_too_large],
)


# --------------------------------------------------------------------------- traces

def trace(reactor, script) -> list[tuple]:
    """``(outputs, values, status)`` per instant; a rejected instant ends the trace."""
    out: list[tuple] = []
    for inputs, clock_ns in script:
        try:
            reaction = reactor.react(inputs, clock_ns)
        except NotCoherent as error:  # which signals were guessed is no part of the result
            out.append(("not logically correct", len(error.solutions)))
            break
        except (OrccadError, ReferenceError_):
            out.append(("run-time error",))
            break
        out.append((reaction.outputs, reaction.values, reaction.status))
    return out


def labelled_trace(reactor, script) -> list[tuple]:
    """:func:`trace` with the labels of the state reached after each instant."""
    out: list[tuple] = []
    for inputs, clock_ns in script:
        try:
            reaction = reactor.react(inputs, clock_ns)
        except OrccadError:
            out.append(("run-time error",))
            break
        out.append((reaction.outputs, reaction.values, reaction.status, reactor.labels))
    return out


def _incoherent(steps: list[tuple]) -> bool:
    return any(step[0] == "not logically correct" for step in steps)


def _show(script, **traces) -> str:
    lines = []
    for i, (inputs, clock_ns) in enumerate(script):
        cells = [f"{name}={t[i] if i < len(t) else '·'}" for name, t in traces.items()]
        lines.append(f"  {i + 1:2} @{clock_ns} {sorted(inputs.items())}: " + "  ".join(cells))
    return "\n".join(lines)


# --------------------------------------------------------------------------- random programs

@CROSS_CHECK
@given(program=programs(), script=input_sequences())
def test_compiled_automaton_agrees_with_the_reference_interpreter(program, script):
    if program.relations:  # relation A # B: the environment never gives both
        script = [({k: v for k, v in inputs.items() if not (k == "B" and "A" in inputs)}, t)
                  for inputs, t in script]
    kernel = expand(program)
    shown = show_program(program)
    note(f"program:\n{shown}")
    for feature, mark in (("?L read", "?L"), ("pre", "pre("), ("counted abort", "abortcount("),
                          ("sub-mission", "mark("), ("combine", "signal=T"),
                          ("relation", None)):
        if (mark is None and program.relations) or (mark is not None and mark in shown):
            event(f"uses {feature}")
    native = trace(ReferenceReactor(program), script)
    expected = trace(ReferenceReactor(kernel), script)
    assert native == expected, "derived.py's expansion differs from the derived form:\n" + \
        _show(script, derived_form=native, expansion=expected)
    try:
        automaton = compile_program(kernel, max_states=MAX_STATES)
    except OrccadError:
        # non-causal (or too big): see the module docstring
        event("rejected; the reference found an incoherent instant" if _incoherent(expected)
              else "rejected; every instant the reference ran was coherent")
        assume(False)
    assert not _incoherent(expected), "the compiler accepted a program that is not logically " \
        "correct:\n" + _show(script, reference=expected)
    event(f"compiled: {min(automaton.state_count, 10)}{'+' if automaton.state_count >= 10 else ''}"
          " states")
    actual = trace(Reactor(automaton), script)
    assert actual == expected, "compiled automaton and reference disagree:\n" + \
        _show(script, compiled=actual, reference=expected)


@settings(CROSS_CHECK, max_examples=LAZY_EXAMPLES)
@given(program=programs(), script=input_sequences())
def test_lazy_automaton_agrees_with_the_full_one(program, script):
    """The automaton built on demand gives the full automaton's outputs, values and status
    and reaches states with the same labels, at every instant of random input sequences."""
    if program.relations:
        script = [({k: v for k, v in inputs.items() if not (k == "B" and "A" in inputs)}, t)
                  for inputs, t in script]
    kernel = expand(program)
    note(f"program:\n{show_program(program)}")
    try:
        automaton = compile_program(kernel, max_states=MAX_STATES)
    except OrccadError:
        assume(False)
    lazy_automaton = LazyAutomaton(kernel, max_states=MAX_STATES)
    full = labelled_trace(Reactor(automaton), script)
    lazy = labelled_trace(Reactor(lazy_automaton), script)
    assert lazy == full, "lazy and full automata disagree:\n" + _show(script, lazy=lazy,
                                                                      full=full)


# --------------------------------------------------------------------------- regressions

def _lowered(source: str) -> ir.Program:
    program = parse(source, "test.orc")
    return lower_mission(program, program.missions[0])


def _script(lines: list[str], inputs) -> list[tuple[dict, int | None]]:
    instants = parse_script("\n".join(lines) + "\n", "script.in", inputs)
    return [(instant.inputs, instant.time_ns) for instant in instants]


def _outputs(steps: list[tuple]) -> list[str]:
    return [" ".join(f"{o}({values[o]})" if o in values else o for o in outputs) or "-"
            for outputs, values, _ in steps]


def agree(program: ir.Program, lines: list[str], native: ir.Program | None = None) -> list[str]:
    """Run compiled automaton and reference (and the derived-form program if given) on the
    script; assert identical traces; return the outputs as text, ``-`` for none."""
    script = _script(lines, program.inputs)
    expected = trace(ReferenceReactor(program), script)
    actual = trace(Reactor(compile_program(program)), script)
    assert actual == expected, _show(script, compiled=actual, reference=expected)
    if native is not None:
        direct = trace(ReferenceReactor(native), script)
        assert direct == expected, _show(script, derived_form=direct, expansion=expected)
    return _outputs(expected)


def test_abro():
    with open("missions/abro.orc", encoding="utf-8") as handle:
        program = _lowered(handle.read())
    a, b, r = program.inputs
    o, = program.outputs
    body = ref.LoopEach(ir.Seq((ir.Par((ref.Await(ir.SigRef(a), False),
                                        ref.Await(ir.SigRef(b), False))),
                                ir.Emit(o), ref.Halt())), ir.SigRef(r))
    native = ir.Program("ABRO", program.inputs, program.outputs, body)
    script = ["", "A", "B", "A B", "R", "A B", "R A", "B", "A", "R A B", "A B"]
    assert agree(program, script, native) == ["-", "-", "O", "-", "-", "O", "-", "-", "O",
                                              "-", "O"]


@pytest.mark.parametrize("body, script, outputs", [
    pytest.param("loop { signal S { if S { emit O; } pause; emit S; } }",
                 ["", "", ""], ["-", "-", "-"], id="schizophrenia"),
    pytest.param("loop { signal S { par { if S { emit O; } else { emit N; } } || "
                 "{ pause; emit S; } } }", ["", "", ""], ["N", "N", "N"],
                 id="schizophrenia-in-par"),
    pytest.param("trap T { par { loop { emit O; pause; } } || { await A; exit T; } } emit N;",
                 ["", "A", ""], ["O", "O N", "-"], id="trap-in-par"),
    pytest.param("suspend { par { loop { emit O; pause; } } || { await A; emit N; } } when B;",
                 ["", "A B", "A", "", "B"], ["O", "-", "O N", "O", "-"],
                 id="suspend-of-par"),
    pytest.param("abort { abort { loop { emit O; pause; } } when A do { emit N; } } "
                 "when B do { emit P; }", ["", "A B", ""], ["O", "P", "-"],
                 id="nested-abort-outer-wins"),
    pytest.param("abort { abort { loop { emit O; pause; } } when A do { emit N; } } "
                 "when B do { emit P; }", ["", "A", "B"], ["O", "N", "-"],
                 id="nested-abort-inner"),
    pytest.param("race { await A; emit O; } || { await B; emit N; } emit P;",
                 ["", "A B", ""], ["-", "O N P", "-"], id="race-simultaneous-ends"),
    pytest.param("weak abort { await A; } when B do { emit N; } emit P;",
                 ["", "A B"], ["-", "P"], id="weak-abort-body-ends-first"),
    pytest.param("var n := 0; every A { n := n + 1; emit V(n); await B; emit O; }",
                 ["A", "A", "B", "A B", "A"], ["-", "V(1)", "O", "V(2)", "V(3)"],
                 id="every-with-data"),
    pytest.param("repeat 2 { await immediate A; emit O; pause; } emit P;",
                 ["A", "", "A", "A"], ["O", "-", "O", "P"], id="repeat-immediate-await"),
])
def test_regression_programs(body, script, outputs):
    source = mission("input A, B; output O, N, P; output V : int;", body)
    assert agree(_lowered(source), script) == outputs


def test_derived_forms_interpreted_directly_match_their_expansion():
    """A nested abort with handlers, written with the reference's derived-form nodes."""
    x = ref.Abort(ref.Sustain(O1), ir.SigRef(A), True, False, ir.Emit(O2))
    body = ref.Abort(ir.Seq((ref.Repeat(ir.Const(2), ir.Seq((x, ir.Pause()))), ref.Halt())),
                     ir.SigRef(B), False, True, ir.Emit(O1))
    native = ir.Program("Nested", INPUTS, OUTPUTS, body)
    script = ["", "A", "", "A", "", "B", ""]
    assert agree(expand(native), script, native) == ["O1", "O1 O2", "O1", "O1 O2", "-",
                                                     "O1", "-"]


# --------------------------------------------------------------------------- causality

@pytest.mark.parametrize("body, solutions", [
    ("signal S { if S { emit S; } }", 2),
    ("signal S { if S { } else { emit S; } }", 0),
    ("par { if O { emit N; } } || { if N { emit O; } }", 2),
    ("par { if O { emit N; } } || { if N { } else { emit O; } }", 0),
])
def test_non_causal_programs_are_rejected_by_both(body, solutions):
    program = _lowered(mission("input A; output O, N;", body))
    with pytest.raises(OrccadError, match="non-causal"):
        compile_program(program)
    with pytest.raises(NotCoherent) as caught:
        ReferenceReactor(program).react({})
    assert len(caught.value.solutions) == solutions


def test_logically_correct_but_not_constructive_is_rejected_by_the_compiler():
    """The legitimate difference between the two semantics: one coherent solution (S present)
    which nothing forces before S is tested."""
    program = _lowered(mission("output O;", "signal S { if S { emit S; emit O; } else "
                                            "{ emit S; } }"))
    with pytest.raises(OrccadError, match="non-causal"):
        compile_program(program)
    assert ReferenceReactor(program).react({}).outputs == ("O",)
