"""The terminal UI (``orccad tui``), built on Textual.

Only this package imports Textual; the core (``lang``, ``reactive``, ``robottask``,
``verify``, ``executive``, ``trace``, ``pipeline``, ``cli``) never does (a test checks it).
:mod:`.live` and :mod:`.session` hold the non-Textual side: the executive observer and the
CLI's functions the screens call.
"""
