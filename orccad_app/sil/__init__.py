"""Software in the loop: the mission's Module-Tasks as C, in a controller process of their own.

- :mod:`.layout`: how a Module-Task instance is described to the C runtime (kind, slots,
  parameter vector), and the refusal of a kind without C;
- :mod:`.emit`: the generated table of a mission (``orccad_modules.c``), generation gap;
- :mod:`.build`: the project's own build step (the C compiler, cached by content);
- :mod:`.controller`: the controller process — started, spoken to over a Unix socket,
  watched by its heartbeat, always killed and reaped;
- :mod:`.remote`: the Module-Task proxy the executive drives;
- :mod:`.lockstep`: ``orccad sil --lockstep``; :mod:`.realtime`: ``orccad sil --realtime``;
- :mod:`.runs`: the run factory through which ``orccad sil`` runs in the run façade.

The C runtime library is ``orccad_app/sil/c`` (C99, no allocation, no recursion).
See docs/deploy.md.
"""

from orccad_app.sil.layout import CLayout, NoCImplementation, c_layout

__all__ = ["CLayout", "NoCImplementation", "c_layout"]
