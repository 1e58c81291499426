"""One reaction of a prepared program, by Esterel's constructive semantics.

The control state is the set of active pauses. A reaction walks the program in *surface*
mode (statements started in this instant) or *depth* mode (statements resumed from an active
pause), computing completion codes (0 terminated, 1 paused, ≥ 2 trap exits; ``max`` wins in
parallel) exactly as Berry's structural semantics do.

Signal statuses are found constructively. One walk computes, for the current knowledge of
signal statuses, what *must* be emitted (on paths that are sure to run) and what *can* be
emitted (on every path that may run). Signals tested while unknown are then set present if they
must be emitted and absent if they cannot be; the walk is repeated until every tested signal is
known. If a walk makes no progress, the program is not constructive for that state and inputs
(a non-causal program):
a compile error names the signal and the test that depends on it.

Inputs and data tests are decided by an *oracle*, which is how :mod:`.compiler` explores all
cases symbolically: it asks for an input's presence or a data test's outcome when the walk
needs it, never earlier. The last walk (no unknowns left) records, in order, the data actions
to perform at run time (assignments, valued emissions, data tests) and the next control state.
"""

from __future__ import annotations

from bisect import bisect_left
from dataclasses import dataclass
from typing import Any

from orccad_app.diagnostics import OrccadError
from orccad_app.reactive import ir
from orccad_app.reactive.prepare import Prepared
from orccad_app.reactive.reads import made
from orccad_app.reactive.walk import Oracle, Values, Walk

__all__ = ["Outcome", "react", "BOOT"]

#: The control state before the first instant (nothing started yet).
BOOT: tuple[int, ...] | None = None


@dataclass(frozen=True, slots=True)
class Outcome:
    """What one reaction does.

    ``events`` are the run-time actions in execution order: ``("assign", VarDecl, Expr)``,
    ``("emit", SignalDecl, Expr)`` for a valued emission, ``("test", number, bool)`` for a
    data test and its outcome. ``emitted`` holds the output signals emitted, ``code`` the
    completion code of the program and ``state`` the next control state (sorted pauses).
    """

    events: tuple[tuple[Any, ...], ...]
    emitted: frozenset[ir.SignalDecl]
    code: int
    state: tuple[int, ...]


#: Walks allowed for one reaction (each walk decides at least one status or value).
MAX_WALKS = 10_000


def react(prep: Prepared, state: tuple[int, ...] | None, oracle: Oracle) -> Outcome:
    """One reaction from ``state`` (``BOOT`` for the first instant) under ``oracle``."""
    env: dict = {}
    depth = state is not None
    active = state or ()
    values = Values()
    while True:
        walk = Walk(prep, active, oracle, env, values)
        must, _ = walk.go(prep.root, depth, True, {})
        if not walk.unknown and not walk.blocked:
            break
        progress = False
        for key in walk.unknown:
            if key in walk.must:
                env[key] = progress = True
            elif key not in walk.can:
                env[key] = False
                progress = True
        if values.not_ready is None or walk.unready != values.not_ready:
            progress = True
        values.not_ready = walk.unready
        if len(walk.events) > values.sure_events:
            values.sure_events = len(walk.events)
            progress = True
        values.round += 1
        if not progress or values.round > MAX_WALKS:
            if walk.unknown:
                _non_causal(walk)
            key, loc = walk.blocked[0]
            name = key[0].name if type(key) is tuple else key.name
            raise OrccadError(f"non-causal program: the value of {name} is read in an instant "
                              "where its emission depends on that read", loc)
    assert must is not None
    emitted = frozenset(k for k in walk.must if isinstance(k, ir.SignalDecl) and k.kind == ir.OUTPUT)
    events = _schedule(prep, walk)
    state_out = sorted(set(walk.next))
    for k, decl in enumerate(prep.pre_signals):
        if decl.kind == ir.INPUT:
            present = oracle.input(decl)
        elif decl.kind == ir.LOCAL:
            present = (decl, decl not in walk.fresh) in walk.must
            if _suspended(prep, walk, decl):  # its previous instant is its last one running
                present = prep.pre_base + k in walk.active_set
        else:
            present = decl in walk.must
        if present:
            state_out.append(prep.pre_base + k)
    return Outcome(events, emitted, must, tuple(state_out))


def _suspended(prep: Prepared, walk: Walk, decl: ir.SignalDecl) -> bool:
    """The declaration of the local ``decl`` is alive inside a suspend frozen in this instant
    (Esterel v5: ``pre(S)`` of a local refers to the previous instant its scope ran)."""
    for index, lo, hi in prep.local_nodes.get(decl, ()):
        if lo == hi or bisect_left(walk.active, hi) == bisect_left(walk.active, lo):
            continue  # no pause inside: not alive across instants
        for frozen_index, frozen_lo, frozen_hi in walk.frozen:
            if frozen_index < index and frozen_lo <= lo and hi <= frozen_hi:
                return True
    return False


def _non_causal(walk: Walk):
    key, decl = next(iter(walk.unknown.items()))
    names = ", ".join(sorted({d.name for d in walk.unknown.values()}))
    raise OrccadError(
        f"non-causal program: the status of signal{'s' if ',' in names else ''} {names} "
        f"cannot be decided in this instant (it depends on itself)", walk.unknown_at[key])


def _schedule(prep: Prepared, walk: Walk) -> tuple:
    """The instant's run-time events in execution order (see :class:`Values`).

    A second emission of a valued signal combines with the first (``combine``); without
    ``combine`` it is a compile error when no data test of the instant could rule it out, and
    otherwise a :class:`~orccad_app.reactive.ir.Fault` raised at run time if it happens. With
    ``prep.defer_double_emissions`` (a run: ``orccad react``, the generated C) it is always
    the fault: an error of the instant whose inputs make it, not of the program.
    """
    ordered = [event for _, event in sorted(walk.events, key=lambda e: e[0])]
    first_at: dict = {}
    written: set = set()
    tested = False
    out: list = []
    for kind, target, expr, key, reads, loc in ordered:
        for read in reads:
            if type(read) is tuple and read[1] and (read[0], False) in written:
                raise OrccadError(
                    f"the value of the previous incarnation of local signal {read[0].name} is "
                    "read after its new incarnation was given a value in the same instant "
                    "(not supported: read it before the loop restarts)", loc)
        if kind == "test":
            tested = True
            out.append(("test", target, expr))
        elif kind == "assign":
            out.append(("assign", target, expr))
        elif kind == "init":
            written.add(key)
            value = made(prep, ("init", target), lambda: ir.Const(
                ir.NO_VALUE if target.init is None else target.init, loc))
            out.append(("emit", target, value))
        else:
            written.add(key)
            if key not in first_at:
                first_at[key] = loc
                out.append(("emit", target, expr))
            elif target.combine is not None:
                out.append(("emit", target, made(prep, ("combine", id(expr)), lambda: ir.Binary(
                    target.combine, ir.SigValue(target, loc), expr, loc))))
            else:
                message = (f"signal {target.name} is emitted twice in one instant (first at "
                           f"{first_at[key]}): declare how its values combine, e.g. "
                           f"'output {target.name} : {target.type} combine +;'")
                if not (tested or prep.defer_double_emissions):
                    raise OrccadError(message, loc)
                out.append(("emit", target, made(prep, ("fault", id(expr)),
                                                  lambda: ir.Fault(message, loc))))
    return tuple(out)
