"""The label of a sub-mission's region (``run mission M``) in a compiled mission's states.

Like the Robot-Task labels (:mod:`orccad_app.robottask.labels`), it marks an
:class:`~orccad_app.reactive.ir.Mark` region, so every state says which sub-missions it is in.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["MissionLabel"]


@dataclass(frozen=True, order=True)
class MissionLabel:
    """The region of one inlined ``run mission M``.

    :param mission: the sub-mission's name ``M``.
    :param site: its call site's number (from 1, in lowering order).
    """

    mission: str
    site: int
