"""Hypothesis strategies: random well-formed kernel programs and random input sequences.

Programs are built as IR objects directly: kernel statements (:mod:`orccad_app.reactive.ir`)
and derived forms (``await``, ``abort``, ``every``, ``repeat``, ``race`` …) as the node classes
of :mod:`tests.reactive.reference`, which that interpreter runs by their own rules;
:func:`expand` replaces them by the expansions of :mod:`orccad_app.reactive.derived` to give
the kernel program the compiler receives. The interface is fixed: pure inputs ``A``, ``B``,
``C``, a valued input ``D : int`` (given a value in the first instant), pure outputs ``O1``,
``O2``, a valued output ``V : int``, a valued output ``T : int := 0 combine +`` (emitted from
several places: its emissions combine) and a data variable ``n`` (set to 0 first). Local
signals (pure, or valued ``int`` with an initial value, read with ``?L`` in other
parallel branches) and traps are made fresh where they are declared and only used inside
their scope. Tests and values use ``pre(S)`` and ``pre(?T)``; counted ``abort``; sub-mission
regions (``Mark``, what ``run mission`` inlines to); programs sometimes declare
``relation A # B`` (the tests then drop B from instants with A).

Well-formedness is by construction: every loop body ends with a ``pause`` (or is a derived
form that cannot terminate at once), and ``exit T`` only appears inside ``trap T``. Programs
may still be rejected by the compiler (non-causal); the tests skip those.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from hypothesis import strategies as st

from orccad_app.reactive import derived as d
from orccad_app.reactive import ir
from orccad_app.reactive.labels import MissionLabel
from tests.reactive.reference import terms as ref

__all__ = ["INPUTS", "OUTPUTS", "programs", "input_sequences", "expand", "show_program"]

A, B, C = (ir.SignalDecl(n, ir.INPUT) for n in "ABC")
D = ir.SignalDecl("D", ir.INPUT, "int")
O1, O2 = (ir.SignalDecl(n, ir.OUTPUT) for n in ("O1", "O2"))
V = ir.SignalDecl("V", ir.OUTPUT, "int")
T = ir.SignalDecl("T", ir.OUTPUT, "int", init=0, combine="+")
N = ir.VarDecl("n")
INPUTS = (A, B, C, D)
OUTPUTS = (O1, O2, V, T)


@dataclass(frozen=True)
class _Ctx:
    """What a statement may refer to: enclosing traps and local signals; remaining depth."""

    depth: int
    traps: tuple[ir.TrapDecl, ...] = ()
    locals: tuple[ir.SignalDecl, ...] = ()

    @property
    def valued(self) -> tuple[ir.SignalDecl, ...]:
        return tuple(s for s in self.locals if s.valued)

    @property
    def pure(self) -> tuple[ir.SignalDecl, ...]:
        return tuple(s for s in self.locals if not s.valued)

    def deeper(self, **changes) -> "_Ctx":
        return replace(self, depth=self.depth - 1, **changes)


# --------------------------------------------------------------------------- tests

def _data_tests(ctx: "_Ctx | None" = None) -> st.SearchStrategy[ir.DataTest]:
    small = st.integers(0, 3).map(ir.Const)
    n, value, clock = ir.VarRef(N), ir.SigValue(D), ir.Clock()
    options = [
        st.builds(lambda op, k: ir.DataTest(ir.Binary(op, n, k)),
                  st.sampled_from([">=", "=="]), small),
        small.map(lambda k: ir.DataTest(ir.Binary(">", value, k))),
        st.integers(1, 12).map(lambda k: ir.DataTest(ir.Binary(">=", clock, ir.Const(k)))),
        small.map(lambda k: ir.DataTest(ir.Binary(">", ir.PreValue(T), k))),
    ]
    if ctx is not None and ctx.valued:  # a read that must wait for the other branches
        options.append(st.builds(lambda s, k: ir.DataTest(ir.Binary(">", ir.SigValue(s), k)),
                                 st.sampled_from(ctx.valued), small))
    return st.one_of(*options)


@st.composite
def _signal_test(draw, ctx: _Ctx, depth: int = 2) -> ir.Test:
    if depth == 0 or draw(st.integers(0, 2)) > 0:
        if draw(st.integers(0, 7)) == 0:
            return ir.PreRef(draw(st.sampled_from((A, B, O1, *ctx.locals))))
        if ctx.locals and draw(st.integers(0, 2)) == 0:
            return ir.SigRef(draw(st.sampled_from(ctx.locals)))
        if draw(st.integers(0, 5)) == 0:
            return ir.SigRef(draw(st.sampled_from((O1, O2))))
        return ir.SigRef(draw(st.sampled_from((A, B, C))))
    kind = draw(st.sampled_from(["not", "and", "or"]))
    left = draw(_signal_test(ctx, depth - 1))
    if kind == "not":
        return ir.SigNot(left)
    right = draw(_signal_test(ctx, depth - 1))
    return (ir.SigAnd if kind == "and" else ir.SigOr)(left, right)


def _test(ctx: _Ctx) -> st.SearchStrategy[ir.Test]:
    return st.one_of(_signal_test(ctx), _signal_test(ctx), _data_tests(ctx))


# --------------------------------------------------------------------------- statements

@st.composite
def _leaf(draw, ctx: _Ctx):
    emittable = (O1, O2, *ctx.pure)
    options = ["nothing", "pause", "pause", "emit", "emit", "emit", "emitv", "emitv", "assign",
               "if",
               "if", "if", "await", "await_n", "await_t"] + ["exit"] * (3 if ctx.traps else 0)
    if draw(st.integers(0, 19)) == 0:
        options = ["halt"]
    kind = draw(st.sampled_from(options))
    if kind == "nothing":
        return ir.Nothing()
    if kind == "pause":
        return draw(_marked(ir.Pause()))
    if kind == "emit":
        if ctx.pure and draw(st.booleans()):
            return ir.Emit(draw(st.sampled_from(ctx.pure)))
        return ir.Emit(draw(st.sampled_from(emittable)))
    if kind == "emitv":
        sources = [ir.VarRef(N), ir.SigValue(D), ir.PreValue(T),
                   *(ir.SigValue(s) for s in ctx.valued)]
        value = ir.Binary("+", draw(st.sampled_from(sources)), ir.Const(draw(st.integers(0, 2))))
        target = draw(st.sampled_from((V, T, T, *ctx.valued)))
        if target is not V and isinstance(value.left, ir.SigValue) \
                and value.left.signal is target:
            value = ir.Binary("+", ir.VarRef(N), value.right)  # not a value cycle
        return ir.Emit(target, value)
    if kind == "assign":
        return ir.Assign(N, ir.Binary("+", ir.VarRef(N), ir.Const(draw(st.integers(1, 2)))))
    if kind == "await":
        return ref.Await(draw(_test(ctx)), draw(st.booleans()))
    if kind == "await_n":
        return ref.AwaitCount(ir.Const(draw(st.integers(0, 2))), draw(_test(ctx)))
    if kind == "await_t":
        return ref.AwaitDuration(ir.Const(draw(st.integers(1, 4))))
    if kind == "if":
        then = ir.Emit(draw(st.sampled_from(emittable)))
        orelse = draw(st.sampled_from([ir.Nothing(), ir.Emit(draw(st.sampled_from(emittable)))]))
        return ir.Present(draw(_test(ctx)), then, orelse)
    if kind == "halt":
        return ref.Halt() if draw(st.booleans()) else ref.Sustain(draw(st.sampled_from(emittable)))
    return ir.Exit(draw(st.sampled_from(ctx.traps)))


@st.composite
def _marked(draw, stmt):
    """``stmt``, sometimes followed by the emission of an output (a visible progress mark)."""
    mark = draw(st.sampled_from([None, O1, O2, V]))
    if mark is None:
        return stmt
    value = ir.Binary("+", ir.VarRef(N), ir.Const(draw(st.integers(0, 2)))) if mark is V else None
    return d.seq(stmt, ir.Emit(mark, value))


def _nonzero(body):
    """``body; pause``: a loop body that cannot terminate in the instant it starts."""
    return d.seq(body, ir.Pause())


@st.composite
def statements(draw, ctx: _Ctx, compound: bool = False):
    """A random statement of at most ``ctx.depth`` nested compound levels."""
    if ctx.depth <= 0 or (not compound and draw(st.integers(0, 3)) == 0):
        return draw(_leaf(ctx))
    kind = draw(st.sampled_from([
        "seq", "seq", "par", "present", "loop", "trap", "trap", "suspend", "local",
        "abort", "race", "every", "repeat", "each", "handle", "schizo", "mission"]))
    sub = ctx.deeper()
    stmt = lambda c=sub: draw(statements(c))  # noqa: E731 - local shorthand
    if kind == "seq":  # with progress marks, so that the instant each item ends shows
        return d.seq(*(draw(_marked(stmt())) for _ in range(draw(st.integers(2, 3)))))
    if kind == "par":
        return ir.Par(tuple(stmt() for _ in range(draw(st.integers(2, 3)))))
    if kind == "present":
        return ir.Present(draw(_test(ctx)), stmt(), stmt())
    if kind == "loop":
        return ir.Loop(_nonzero(stmt()))
    if kind in ("trap", "handle"):
        trap = ir.TrapDecl(f"T{len(ctx.traps)}")
        body = stmt(ctx.deeper(traps=(*ctx.traps, trap)))
        return ref.TrapHandle(trap, body, stmt()) if kind == "handle" else ir.Trap(trap, body)
    if kind == "suspend":
        test = draw(_test(ctx))
        return ref.SuspendNow(stmt(), test) if draw(st.booleans()) else ir.Suspend(test, stmt())
    if kind in ("local", "schizo"):
        if kind == "local" and draw(st.booleans()):
            # always an initial value: a data test whose outcome does not matter is dropped
            # from the automaton, so an unset read there is not an error in the compiled
            # program while the reference would report it (unit tests cover unset reads)
            init = draw(st.sampled_from([0, 1, 3]))
            signal = ir.SignalDecl(f"L{len(ctx.locals)}", ir.LOCAL, "int", init=init)
        else:
            signal = ir.SignalDecl(f"S{len(ctx.locals)}", ir.LOCAL)
        inner = ctx.deeper(locals=(*ctx.locals, signal))
        if kind == "local":
            return ir.Local((signal,), stmt(inner))
        return draw(_schizophrenic(inner, signal))
    if kind == "abort":
        handler = stmt() if draw(st.booleans()) else None
        if draw(st.integers(0, 3)) == 0:
            return ref.AbortCount(stmt(), ir.Const(draw(st.integers(0, 3))), draw(_test(ctx)),
                                  draw(st.booleans()), handler)
        return ref.Abort(stmt(), draw(_test(ctx)), draw(st.booleans()), draw(st.booleans()),
                         handler)
    if kind == "mission":
        return ir.Mark(MissionLabel("Sub", len(ctx.traps)), stmt())
    if kind == "race":
        return ref.Race((stmt(), stmt()))
    if kind == "every":
        return ref.Every(draw(_test(ctx)), stmt(), draw(st.booleans()))
    if kind == "repeat":
        return ref.Repeat(ir.Const(draw(st.integers(0, 3))), _nonzero(stmt()))
    return ref.LoopEach(stmt(), draw(_test(ctx)))


@st.composite
def _schizophrenic(draw, ctx: _Ctx, signal: ir.SignalDecl):
    """``loop { signal S { …test S…; pause; …; emit S } }``: a fresh incarnation of S is
    tested in the instant the previous one is emitted (Esterel's schizophrenia)."""
    test = ir.SigRef(signal) if draw(st.booleans()) else ir.SigNot(ir.SigRef(signal))
    first = ir.Present(test, draw(statements(ctx)), draw(statements(ctx)))
    if draw(st.booleans()):
        first = ir.Par((first, draw(statements(ctx))))
    last = d.seq(draw(statements(ctx)), ir.Emit(signal))
    return ir.Loop(ir.Local((signal,), d.seq(first, ir.Pause(), last)))


@st.composite
def programs(draw, max_depth: int = 4) -> ir.Program:
    """A random program: ``n := 0`` then one or two random compound statements, often
    restarted by ``C`` (``loop … each C``) so that runs visit more states."""
    ctx = _Ctx(depth=max_depth)
    body = d.seq(*(draw(statements(ctx, compound=True)) for _ in range(draw(st.integers(1, 2)))))
    if draw(st.booleans()):
        body = ref.LoopEach(body, ir.SigRef(C))
    relations = (ir.Relation("#", (A, B)),) if draw(st.integers(0, 3)) == 0 else ()
    return ir.Program("Random", INPUTS, OUTPUTS, d.seq(ir.Assign(N, ir.Const(0)), body),
                      relations=relations)


# --------------------------------------------------------------------------- inputs

@st.composite
def _instant(draw, first: bool) -> tuple[dict, int]:
    inputs: dict = {s.name: None for s in (A, B, C) if draw(st.booleans())}
    if first or draw(st.integers(0, 2)) == 0:
        inputs["D"] = draw(st.integers(0, 4))  # D has a value from the first instant on
    return inputs, draw(st.integers(0, 2))


@st.composite
def input_sequences(draw, min_size: int = 10, max_size: int = 20) -> list[tuple[dict, int]]:
    """``[(inputs, clock_ns)]``: inputs map names to values (``None`` for pure signals)."""
    size = draw(st.integers(min_size, max_size))
    steps = [draw(_instant(i == 0)) for i in range(size)]
    clock, out = 0, []
    for inputs, delta in steps:
        clock += delta
        out.append((inputs, clock))
    return out


# --------------------------------------------------------------------------- expansion

def expand(stmt):
    """The kernel IR of a generated statement: derived forms (the node classes of
    :mod:`tests.reactive.reference`) replaced by their :mod:`~orccad_app.reactive.derived`
    expansions, as the compiler receives them from the lowering."""
    kind = type(stmt)
    if kind is ir.Program:
        return ir.Program(stmt.name, stmt.inputs, stmt.outputs, expand(stmt.body), stmt.loc,
                          relations=stmt.relations)
    if kind is ir.Mark:
        return ir.Mark(stmt.label, expand(stmt.body), stmt.loc)
    if kind is ir.Seq:
        return ir.Seq(tuple(expand(s) for s in stmt.items), stmt.loc)
    if kind is ir.Par:
        return ir.Par(tuple(expand(s) for s in stmt.branches), stmt.loc)
    if kind is ir.Present:
        return ir.Present(stmt.test, expand(stmt.then), expand(stmt.orelse), stmt.loc)
    if kind is ir.Loop:
        return ir.Loop(expand(stmt.body), stmt.loc, stmt.what)
    if kind is ir.Trap:
        return ir.Trap(stmt.trap, expand(stmt.body), stmt.loc)
    if kind is ir.Suspend:
        return ir.Suspend(stmt.test, expand(stmt.body), stmt.loc)
    if kind is ir.Local:
        return ir.Local(stmt.signals, expand(stmt.body), stmt.loc)
    derived = _DERIVED.get(kind)
    return stmt if derived is None else derived(stmt)


def _opt(stmt):
    return None if stmt is None else expand(stmt)


_DERIVED = {
    ref.Halt: lambda s: d.halt(),
    ref.Sustain: lambda s: d.sustain(s.signal),
    ref.Await: lambda s: d.await_signal(s.test, immediate=s.immediate),
    ref.AwaitCount: lambda s: d.await_count(s.count, s.test),
    ref.AwaitDuration: lambda s: d.await_duration(s.duration),
    ref.Abort: lambda s: d.abort(expand(s.body), s.test, weak=s.weak, immediate=s.immediate,
                                 handler=_opt(s.handler)),
    ref.AbortCount: lambda s: d.abort_count(expand(s.body), s.count, s.test, weak=s.weak,
                                            handler=_opt(s.handler)),
    ref.SuspendNow: lambda s: d.suspend(expand(s.body), s.test, immediate=True),
    ref.LoopEach: lambda s: d.loop_each(expand(s.body), s.test),
    ref.Every: lambda s: d.every_signal(s.test, expand(s.body), immediate=s.immediate),
    ref.Repeat: lambda s: d.repeat(s.count, expand(s.body)),
    ref.Race: lambda s: d.race(tuple(expand(b) for b in s.branches)),
    ref.TrapHandle: lambda s: d.trap_handle(s.trap, expand(s.body), expand(s.handler)),
}


# --------------------------------------------------------------------------- printing

def show_program(stmt, indent: int = 0) -> str:
    """An indented, Esterel-like rendering of a generated program, for failure reports."""
    pad = "  " * indent
    if isinstance(stmt, ir.Program):
        return show_program(stmt.body, indent)
    if isinstance(stmt, ir.Seq):
        return f"{pad}seq\n" + "\n".join(show_program(s, indent + 1) for s in stmt.items)
    if isinstance(stmt, (ir.Par, ref.Race)):
        word = "par" if isinstance(stmt, ir.Par) else "race"
        return f"{pad}{word}\n" + f"\n{pad}||\n".join(
            show_program(s, indent + 1) for s in stmt.branches)
    head, children = [], []
    for name in stmt.__dataclass_fields__:
        value = getattr(stmt, name)
        if name == "loc" or (name == "what" and value == "loop"):
            continue
        if isinstance(value, (ir.Stmt.__args__, *_DERIVED)):
            children.append((name, value))
        else:
            head.append(f"{name}={_atom(value)}")
    text = f"{pad}{type(stmt).__name__.lower()}({', '.join(head)})"
    for name, child in children:
        text += f"\n{pad} {name}:\n{show_program(child, indent + 1)}"
    return text


def _atom(value) -> str:
    from orccad_app.reactive.expr import format_expr, format_test

    if isinstance(value, (ir.SignalDecl, ir.VarDecl)):
        return value.name
    if isinstance(value, ir.TrapDecl):
        return f"{value.name}@{id(value) % 997}"  # same-named traps are different traps
    if isinstance(value, ir.Test.__args__):
        return format_test(value)
    if isinstance(value, ir.Expr.__args__):
        return format_expr(value)
    if isinstance(value, tuple):
        return "(" + ", ".join(_atom(v) for v in value) + ")"
    return repr(value)
