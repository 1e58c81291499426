"""The reference for signal properties: a property's tree written in rtamt's STL and evaluated
by rtamt's offline monitor (a textbook implementation of the discrete-time robustness).

The product evaluates properties with :mod:`orccad_app.verify.stl_eval` (linear in the run);
this module is what that evaluator is tested and benchmarked against
(``tests/verify/test_stl_linear.py``, ``bench/bench_stl.py``). rtamt computes a bounded
``until`` / ``since`` in ``O(n·w²)`` and a bounded ``always`` / ``eventually`` in ``O(n·w)``
for a window of ``w`` samples.
"""

from __future__ import annotations

import functools
import math
import warnings
from typing import Any, Mapping, Sequence

from orccad_app.diagnostics import OrccadError
from orccad_app.verify.stl_tree import (
    Call, Const, Direction, Event, Junction, Margin, Node, Not, Shift, SignalTerm,
    UndefinedRobustness, Var, Window)

__all__ = ["rtamt_text", "rtamt_robustness"]


def _bounds(low_ns: int, high_ns: int | None, horizon_ns: int) -> str:
    if high_ns is None:
        return ""
    # a window reaching past the run reads its recorded part: rtamt's buffers follow the bound
    return f"[{min(low_ns, horizon_ns)}ns:{min(high_ns, horizon_ns)}ns]"


def _term(term: SignalTerm) -> str:
    if isinstance(term, Var):
        return term.name
    if isinstance(term, Const):
        return repr(float(term.value))
    if isinstance(term, Call):
        return f"{term.func}({_term(term.arg)})"
    return f"({_term(term.left)} {term.op} {_term(term.right)})"


def rtamt_text(node: Node, horizon_ns: int) -> str:
    """``node`` in rtamt's language, every time bound at most ``horizon_ns``."""
    if isinstance(node, Margin):
        return f"({_term(node.left)} {node.op} {_term(node.right)})"
    if isinstance(node, Event):
        return f"({node.name} >= 0)"
    if isinstance(node, Not):
        return f"(not{rtamt_text(node.operand, horizon_ns)})"
    if isinstance(node, Junction):
        return (f"({rtamt_text(node.left, horizon_ns)} {node.op} "
                f"{rtamt_text(node.right, horizon_ns)})")
    if isinstance(node, Shift):
        word = "next" if node.direction is Direction.FUTURE else "prev"
        return f"({word}{rtamt_text(node.operand, horizon_ns)})"
    if isinstance(node, Window):
        bounds = _bounds(node.low_ns, node.high_ns, horizon_ns)
        return f"({node.op}{bounds}{rtamt_text(node.operand, horizon_ns)})"
    word = "until" if node.direction is Direction.FUTURE else "since"
    bounds = _bounds(node.low_ns, node.high_ns, horizon_ns)
    return (f"({rtamt_text(node.left, horizon_ns)} {word}{bounds} "
            f"{rtamt_text(node.right, horizon_ns)})")


@functools.lru_cache(maxsize=64)
def _parsed(text: str, period_ns: int, names: tuple[str, ...]) -> Any:
    """rtamt's parsed specification of ``text``, parsed once per process (ANTLR: ~20 ms)."""
    with warnings.catch_warnings():  # antlr4 4.7 imports typing.io (deprecated)
        warnings.simplefilter("ignore", DeprecationWarning)
        import rtamt

    spec = rtamt.StlDiscreteTimeSpecification()
    for name in names:
        spec.declare_var(name, "float")
    spec.spec = text
    spec.set_sampling_period(period_ns, "ns", 0.1)
    try:
        spec.parse()
    except rtamt.RTAMTException as error:  # pragma: no cover - a translation defect
        raise OrccadError(f"internal error: rtamt rejects {text!r}: {error}") from None
    return spec


def _overflowed(node: Node | SignalTerm, data: Mapping[str, Sequence[float]]) -> bool:
    """Some comparison operand leaves the finite numbers on some sample."""
    import numpy as np

    def term(t: SignalTerm) -> Any:
        if isinstance(t, Var):
            return np.asarray(data[t.name], dtype=float)
        if isinstance(t, Const):
            return t.value
        if isinstance(t, Call):
            return (np.abs if t.func == "abs" else np.sqrt)(term(t.arg))
        left, right = term(t.left), term(t.right)
        return {"+": np.add, "-": np.subtract, "*": np.multiply,
                "/": np.divide}[t.op](left, right)

    def walk(n: Any) -> bool:
        if isinstance(n, Margin):
            with np.errstate(all="ignore"):
                return bool(np.any(np.isinf(term(n.left))) or np.any(np.isinf(term(n.right))))
        children = [getattr(n, name) for name in ("operand", "left", "right")
                    if hasattr(n, name)]
        return any(walk(child) for child in children)

    return walk(node)


def rtamt_robustness(tree: Node, samples: Mapping[str, Sequence[float]],
                     period_ns: int) -> float:
    """The robustness at time 0 by rtamt, with the same undefined cases as
    :func:`orccad_app.verify.stl_eval.evaluate` when the undefined value reaches time 0."""
    data = {name: [float(v) for v in values] for name, values in samples.items()}
    length = len(next(iter(data.values())))
    spec = _parsed(rtamt_text(tree, length * period_ns), period_ns, tuple(sorted(data)))
    data["time"] = [k * period_ns / 1e9 for k in range(length)]
    try:
        value = _evaluate(spec, data)
    except ZeroDivisionError:
        raise UndefinedRobustness("a division by zero") from None
    except ValueError:  # math domain error: sqrt of a negative value
        raise UndefinedRobustness("the square root of a negative value") from None
    if math.isnan(value):
        raise UndefinedRobustness("a value that is not a number")
    if math.isinf(value) and _overflowed(tree, data):
        raise UndefinedRobustness("an overflow of its arithmetic to ±inf")
    return value


def _evaluate(spec: Any, data: dict[str, list[float]]) -> float:
    """rtamt 0.4's ``evaluate`` computes a one-sample run's value, then fails checking the
    sampling period of a trace with no interval: its offline interpreter is asked directly."""
    try:
        return float(spec.evaluate(data)[0][1])
    except UnboundLocalError:
        if len(data["time"]) != 1:
            raise
    interpreter = spec.offline_interpreter
    result = interpreter.visitAst(interpreter.ast, 1)
    return float(result[len(result) - 1][0])
