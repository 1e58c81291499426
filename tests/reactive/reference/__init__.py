"""An independent reference interpreter of the reactive kernel (:mod:`orccad_app.reactive.ir`).

It exists to cross-check the compiler (:mod:`orccad_app.reactive.compiler`, built on the
constructive engine of :mod:`orccad_app.reactive.engine`) and is deliberately written with
other techniques, so that one bug is unlikely to be in both:

*Term rewriting instead of numbered pauses.* The control state is the **residual program**:
the term that is left to execute. Reacting a term gives a completion code and a residual
(Berry's behavioural semantics ``p --(E', k)--> p'``):

================================  =============================================================
``pause``                         pauses (k = 1); residual ``nothing``
``p; q``                          if ``p`` pauses with residual ``p'``: residual ``p'; q``
``loop p``                        ``p`` pauses with ``p'``: residual ``p'; loop p`` (the loop
                                  body restarts as a new term); ``p`` terminating at once is
                                  an instantaneous loop
``p || q``                        ``max`` of the codes; residual: the paused branches' residuals
                                  (branches that terminated become ``nothing``)
``trap T p``                      an exit of T becomes termination; residual ``trap T p'``
``suspend p when t``              first instant: ``p`` reacts; residual is a *started* suspend
                                  (:class:`.terms.Suspended`) which, while ``t`` holds, stays as it is
                                  and pauses without doing anything
``signal S p``                    each entry makes a fresh *incarnation* of S; the residual
                                  (:class:`.terms.Scoped`) remembers which incarnation its body uses
================================  =============================================================

Completion codes are 0 (terminated), 1 (paused) and, for ``exit T``, a code that grows as the
trap is further out, so that ``max`` in a parallel gives the outermost exit (weak preemption:
every branch still does its whole reaction of the instant).

*Logical coherence instead of Must/Can.* The statuses of output and local signals are not
computed: they are **guessed**. An instant is executed deterministically under an assumption
(a status for each non-input signal it tests); when execution tests a signal the assumption
does not cover, the search splits on it. A complete run is *coherent* when every assumed
status agrees with what the run emitted. Exactly one coherent run is the reaction; none or
several means the program is not logically correct in that instant (:class:`.errors.NotCoherent`).
Signals that are never tested need no guess: their status is what is emitted.

*Derived forms interpreted directly.* ``await``, ``abort``, ``every``, ``repeat``, ``race`` …
have node classes here (:class:`.terms.Abort`, :class:`.terms.Every` …) with rewriting rules of their own,
from their Esterel v5 meaning (a started strong ``abort`` tests its condition before its body
reacts, a weak one after), so the expansions of :mod:`orccad_app.reactive.derived`, which the
compiler receives, are checked too. ``count``/``duration`` are read when the statement starts.

*Values by a fixpoint instead of scheduling.* ``?S`` reads the value S has at the *end* of the
instant (all its emissions of the instant, combined with its ``combine`` operator; two without
one is a run-time error), or its value before the instant when S is not emitted. The instant is
executed under an assumption on those end-of-instant values (none at first) and re-executed
with the values the run emitted until they agree; a read of a value not known yet abandons the
run (the emissions it made are learned). Each local signal incarnation has its own value.
``pre(S)`` and ``pre(?S)`` read the status and value of the previous instant, kept per key
(for a local, of the previous instant its scope ran: suspended instants do not count).
Variables and the clock are evaluated in program order. As in Esterel, where ``abort``/``suspend`` decide their condition once per
instant, a data test *object* (the expansion of ``abort`` shares one between the suspension and
the watcher) is evaluated once per instant, at its first use.

The package: :mod:`.terms` (the residual terms and the derived forms' nodes), :mod:`.data`
(values, operators and the data memory), :mod:`.run` (one execution of an instant under an
assumption), :mod:`.derived_forms` (the derived forms' rewriting rules), :mod:`.reactor` (the
instant by instant reactor that finds the coherent execution) and :mod:`.errors`.
"""
