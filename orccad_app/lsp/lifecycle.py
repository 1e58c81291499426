"""The server's lifecycle, as the LSP specifies it: ``initialize``, the work, ``shutdown``,
``exit``.

- before ``initialize``: a request is answered ``ServerNotInitialized`` (-32002), a
  notification dropped (``exit`` excepted);
- a second ``initialize`` is an invalid request (the client may send it once);
- after ``shutdown``: a request is an invalid request, a notification dropped (``exit``
  excepted);
- ``exit`` ends the server with status 0 if ``shutdown`` came before, else 1.
"""

from __future__ import annotations

from enum import Enum

from orccad_app.lsp.jsonrpc import ErrorCode, Incoming, Kind, Refusal

__all__ = ["Phase", "Lifecycle", "INITIALIZE", "SHUTDOWN", "EXIT"]

INITIALIZE = "initialize"
SHUTDOWN = "shutdown"
EXIT = "exit"


class Phase(Enum):
    """Where the server is in its lifecycle."""

    WAITING = "waiting"
    """Before a well-formed ``initialize`` request."""
    RUNNING = "running"
    """Initialized: every method is served."""
    SHUT_DOWN = "shut down"
    """``shutdown`` received: only ``exit`` is left."""


class Lifecycle:
    """Admits messages by the phase, and moves through the phases."""

    def __init__(self) -> None:
        self.phase = Phase.WAITING

    def refusal(self, message: Incoming) -> Refusal | None:
        """Why ``message`` is not served now, or ``None`` (responses always are)."""
        if message.kind is Kind.RESPONSE:
            return None
        answered = message.kind is Kind.REQUEST
        if self.phase is Phase.WAITING and message.method != INITIALIZE:
            return Refusal(ErrorCode.SERVER_NOT_INITIALIZED,
                           f"{message.method}: the server is not initialized (send "
                           "initialize first)", message.id, answered)
        if self.phase is not Phase.WAITING and message.method == INITIALIZE:
            return Refusal(ErrorCode.INVALID_REQUEST, "initialize: the server is already "
                                                      "initialized (initialize is sent once)",
                           message.id, answered)
        if self.phase is Phase.SHUT_DOWN:
            return Refusal(ErrorCode.INVALID_REQUEST, f"{message.method}: the server is "
                                                      "shutting down (shutdown was received; "
                                                      "only exit is left)", message.id,
                           answered)
        if message.method == INITIALIZE and not answered:
            return Refusal(ErrorCode.INVALID_REQUEST, "initialize is a request (it needs an "
                                                      "id)", None, False)
        return None

    def served(self, message: Incoming) -> None:
        """``message`` was handed to its handler: ``initialize`` and ``shutdown`` move on."""
        if message.method == INITIALIZE:
            self.phase = Phase.RUNNING
        elif message.method == SHUTDOWN and message.kind is Kind.REQUEST:
            self.phase = Phase.SHUT_DOWN

    def exit_status(self) -> int:
        """The status of ``exit`` now: 0 after ``shutdown``, else 1."""
        return 0 if self.phase is Phase.SHUT_DOWN else 1
