"""Hypothesis strategies: well-typed plan-language missions, as source text, and their inputs.

Missions are generated from the grammar's statements (not token soup) over a fixed interface:
pure inputs ``A``, ``B``, ``C``; valued inputs ``N : int`` and ``F : float``; pure outputs
``O``, ``Q``; valued outputs ``P : int`` and ``R : float``; an integer variable ``x``. Every
loop body ends with ``pause`` (no instantaneous loop), ``exit T`` only appears inside ``trap
T``, ``?N``/``?F`` are read only where ``N``/``F`` is present, local signals are used only in
their scope. Programs may still be refused (a non-causal one), which the harness accepts as
long as the refusal is a located error with exit status 2. :func:`mutated` then damages a
program's text the way a hurried user or a broken generator would.
"""

from __future__ import annotations

from hypothesis import strategies as st

__all__ = ["missions", "task_missions", "scripts", "mutated", "inject_specs", "INTERFACE"]

INTERFACE = ("input A, B, C; input N : int; input F : float;\n"
             "output O, Q; output P : int; output R : float;\n")
_PURE = ("A", "B", "C")
_INT = st.integers(-1000, 1000).map(str)
_FLOAT = st.floats(-1e6, 1e6, allow_nan=False, allow_infinity=False).map(lambda v: f"{v:.6g}")


def _int_expr(depth: int, present: tuple[str, ...]) -> st.SearchStrategy[str]:
    leaves = [_INT, st.just("x")] + ([st.just("?N")] if "N" in present else [])
    leaf = st.one_of(*leaves)
    if depth <= 0:
        return leaf
    sub = _int_expr(depth - 1, present)
    return st.one_of(leaf, st.builds(lambda a, op, b: f"({a} {op} {b})", sub,
                                     st.sampled_from(["+", "-", "*", "/"]), sub))


def _float_expr(present: tuple[str, ...]) -> st.SearchStrategy[str]:
    leaves = [_FLOAT] + ([st.just("?F")] if "F" in present else [])
    leaf = st.one_of(*leaves)
    return st.one_of(leaf, st.builds(lambda a, op, b: f"({a} {op} {b})", leaf,
                                     st.sampled_from(["+", "-", "*"]), leaf))


def _signal_expr(signals: tuple[str, ...]) -> st.SearchStrategy[str]:
    name = st.sampled_from(signals)
    return st.one_of(name, st.builds(lambda a, b: f"({a} or {b})", name, name),
                     st.builds(lambda a, b: f"({a} and not {b})", name, name))


def _duration() -> st.SearchStrategy[str]:
    return st.builds(lambda v, u: f"{v} {u}", st.integers(0, 5), st.sampled_from(["s", "ms"]))


@st.composite
def _block(draw, depth: int, signals: tuple[str, ...], traps: tuple[str, ...],
           present: tuple[str, ...] = ()) -> str:
    count = draw(st.integers(1, 2))
    return "{ " + " ".join(draw(_statement(depth, signals, traps, present))
                           for _ in range(count)) + " }"


def _loop_body(draw, depth, signals, traps) -> str:
    return draw(_block(depth, signals, traps))[:-1] + "pause; }"


@st.composite
def _statement(draw, depth: int, signals: tuple[str, ...], traps: tuple[str, ...],
               present: tuple[str, ...] = ()) -> str:
    simple = [
        st.just("nothing;"), st.just("pause;"), st.just("emit O;"), st.just("emit Q;"),
        _int_expr(2, present).map(lambda e: f"emit P({e});"),
        _float_expr(present).map(lambda e: f"emit R({e});"),
        _int_expr(2, present).map(lambda e: f"x := {e};"),
        _signal_expr(signals).map(lambda e: f"await {e};"),
        st.sampled_from(signals).map(lambda s: f"await immediate {s};"),
        st.builds(lambda k, s: f"await {k} {s};", st.integers(1, 3), st.sampled_from(signals)),
        _duration().map(lambda d: f"await {d};"),
    ]
    if traps:
        simple.append(st.sampled_from(traps).map(lambda t: f"exit {t};"))
    if depth <= 0:
        return draw(st.one_of(*simple))
    inner = depth - 1
    kind = draw(st.sampled_from(["simple", "simple", "if", "ifdata", "loop", "each", "repeat",
                                 "every", "abort", "weak", "suspend", "trap", "par", "race",
                                 "signal", "present"]))
    block = lambda: draw(_block(inner, signals, traps, present))  # noqa: E731
    sig = lambda: draw(_signal_expr(signals))  # noqa: E731
    if kind == "simple":
        return draw(st.one_of(*simple))
    if kind == "if":
        return f"if {sig()} {block()} else {block()}"
    if kind == "ifdata":
        return f"if x > {draw(_INT)} {block()}"
    if kind == "present":
        valued = draw(st.sampled_from(["N", "F"]))
        then = draw(_block(inner, signals, traps, present + (valued,)))
        return f"if {valued} {then}"
    if kind == "loop":
        return f"loop {_loop_body(draw, inner, signals, traps)}"
    if kind == "each":
        return f"loop {block()} each {sig()};"
    if kind == "repeat":
        return f"repeat {draw(st.integers(0, 3))} {block()}"
    if kind == "every":
        trigger = draw(st.one_of(_signal_expr(signals), _duration().filter(
            lambda d: not d.startswith("0 "))))
        return f"every {trigger} {block()}"
    if kind in ("abort", "weak"):
        weak = "weak " if kind == "weak" else ""
        handler = f" do {block()}" if draw(st.booleans()) else ""
        immediate = "immediate " if draw(st.booleans()) and not weak else ""
        return f"{weak}abort {block()} when {immediate}{sig()}{handler};"
    if kind == "suspend":
        return f"suspend {block()} when {sig()};"
    if kind == "trap":
        name = f"T{len(traps)}"
        body = draw(_block(inner, signals, traps + (name,), present))
        handle = f" handle {block()}" if draw(st.booleans()) else ""
        return f"trap {name} {body}{handle}"
    if kind in ("par", "race"):
        branches = [block() for _ in range(draw(st.integers(2, 3)))]
        return f"{kind} " + " || ".join(branches)
    local = f"L{len(signals)}"
    body = draw(_block(inner, signals + (local,), traps, present))
    return f"signal {local} {body}"


@st.composite
def missions(draw, depth: int = 2) -> str:
    """A mission ``M`` over :data:`INTERFACE`, optionally with a property."""
    body = " ".join(draw(_statement(depth, _PURE, ())) for _ in range(draw(st.integers(1, 3))))
    text = f"{INTERFACE}mission M {{\n  var x := 0;\n  {body}\n}}\n"
    if draw(st.booleans()):
        formula = draw(st.sampled_from(["always (O -> once A)", "never (O and Q)",
                                        "always (Q -> previously true)", "eventually done"]))
        text += f"property M.p: {formula};\n"
    return text


#: The Robot-Task of missions/arm_pid.orc, shortened (0.2 s), for generated missions that run.
TASK = """robot arm : arm3dof;
robottask Track(kp: float = 400.0) on arm {
    duration 0.2 s;
    task_function joint_tracking(trajectory = cosine(q0 = [0.5, 0.5, 0.5], omega = pi));
    law pid(kp = kp, kv = 40.0, ki = 10.0);
    exception TrackingLost from tracking_error(max = 0.2) : abort;
}
input Stop;
output Done, Retry;
"""


@st.composite
def _task_statement(draw, depth: int) -> str:
    kp = draw(st.sampled_from(["", "kp = 100.0", "kp = 600.0", "kp = 1e6", "kp = -5.0"]))
    within = draw(st.sampled_from(["", " within 0.1 s", " within 1 s"]))
    run = f"run Track({kp}){within};"
    if depth <= 0:
        return draw(st.sampled_from([run, "emit Done;", "pause;", "await 0.05 s;"]))
    inner = " ".join(draw(_task_statement(depth - 1)) for _ in range(draw(st.integers(1, 2))))
    return draw(st.sampled_from([
        run,
        f"try {{ {inner} }} catch TrackingLost, Timeout {{ emit Retry; }}",
        f"abort {{ {inner} }} when Stop;",
        f"repeat 2 {{ {inner} }}",
        f"par {{ {inner} }} || {{ await 0.1 s; emit Done; }}",
    ]))


@st.composite
def task_missions(draw) -> str:
    """A mission that runs a Robot-Task of the arm (a short one), for ``orccad run``."""
    body = " ".join(draw(_task_statement(2)) for _ in range(draw(st.integers(1, 2))))
    return f"{TASK}mission M {{ {body} emit Done; }}\n"


def _script_line() -> st.SearchStrategy[str]:
    item = st.one_of(st.sampled_from(_PURE), _INT.map(lambda v: f"N({v})"),
                     _FLOAT.map(lambda v: f"F({v})"))
    return st.lists(item, max_size=3, unique_by=lambda s: s.split("(")[0]).map(" ".join)


@st.composite
def scripts(draw) -> str:
    """A react script over :data:`INTERFACE` (times optional, non-decreasing)."""
    lines, clock = [], 0.0
    for _ in range(draw(st.integers(0, 12))):
        line = draw(_script_line())
        if draw(st.booleans()):
            clock += draw(st.sampled_from([0.0, 0.001, 0.5, 1.0, 2.5]))
            line = f"@{clock:g} {line}"
        lines.append(line)
    return "\n".join(lines) + "\n"


_HOSTILE = ["1e400", "nan", "inf", "-1", "0", "9223372036854775808", "1e-400", "99999999999" * 3,
            "\t", "\f", "\u2028", "\ufeff", "#", "\"", "(", ")", "{", "}", ";", "@", "é", "\x00"]


@st.composite
def mutated(draw, text_strategy) -> str:
    """A program or script damaged by a few edits: deleted, duplicated or swapped characters,
    hostile tokens (non-finite and huge numbers, odd whitespace, braces) inserted."""
    text = draw(text_strategy)
    for _ in range(draw(st.integers(1, 4))):
        if not text:
            break
        at = draw(st.integers(0, len(text) - 1))
        edit = draw(st.sampled_from(["delete", "duplicate", "insert", "replace"]))
        if edit == "delete":
            text = text[:at] + text[at + draw(st.integers(1, 8)):]
        elif edit == "duplicate":
            end = min(len(text), at + draw(st.integers(1, 40)))
            text = text[:end] + text[at:end] + text[end:]
        elif edit == "insert":
            text = text[:at] + draw(st.sampled_from(_HOSTILE)) + text[at:]
        else:
            text = text[:at] + draw(st.sampled_from(_HOSTILE)) + text[at + 1:]
    return text


def inject_specs() -> st.SearchStrategy[str]:
    """``--inject`` specs, well-formed or not."""
    name = st.sampled_from(["TrackPID.TrackingLost", "TrackPID.Saturated", "Nope", "arm.leak",
                            "Stop", ""])
    when = st.one_of(st.sampled_from(["0", "0.01", "1e300", "nan", "inf", "-1", "x", ""]),
                     st.floats(0, 0.1).map(lambda v: f"{v:g}"))
    value = st.sampled_from(["", "(3)", "(nan)", "(true)", "(1e400)", "=1", "=nan"])
    return st.builds(lambda n, v, t: f"{n}{v}@{t}", name, value, when)
