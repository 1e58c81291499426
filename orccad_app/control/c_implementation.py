"""A Module-Task kind's C, provided by its plugin: :class:`CImplementation`.

``orccad sil`` and ``orccad codegen --module-tasks`` run every Module-Task in C. The built-in
kinds have theirs in the runtime library (``orccad_app/sil/c/orccad_mt_*.c``); a plugin's kind
runs there when the kind says where its C is (:attr:`ModuleKind.c_implementation
<orccad_app.control.module.ModuleKind.c_implementation>`), and is refused with its name and
the reason otherwise. The contract (docs/deploy.md, "A plugin kind's C"): one C99 file that
includes ``orccad_mt.h`` and defines

.. code-block:: c

    void PREFIX_init(orc_mt *m);                 /* at each activation, state already zeroed */
    void PREFIX_compute(orc_mt *m, double t_s);  /* one job: m->in[] -> m->out[] */

reading its inputs from ``m->in[]`` (in the kind's input port order; ``present`` 0: none
yet), its parameters from ``m->p[]`` (the vector :attr:`CImplementation.params` gives), its
state in ``m->s[]`` (160 doubles), and setting ``m->out[k].present`` and ``m->out[k].v`` for
what it writes; no allocation, no recursion, ``-std=c99 -Wall -Wextra -Werror -pedantic``
clean.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from orccad_app.control.errors import ControlError

__all__ = ["CImplementation"]

_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]{0,30}")


@dataclass(frozen=True)
class CImplementation:
    """Where a plugin kind's C is and how an instance's parameters reach it.

    :param source: the C99 file (see the module docstring).
    :param prefix: the C identifier before ``_init`` and ``_compute`` (at most 31 characters),
        unique among the kinds of a mission.
    :param params: an instance's parameter vector ``m->p`` (at most 192 numbers), from the
        :class:`~orccad_app.control.module.ModuleInstance`; called at every start and type-1
        update.
    """

    source: Path
    prefix: str
    params: Callable[[Any], Sequence[float]]

    def __post_init__(self) -> None:
        if not _IDENTIFIER.fullmatch(self.prefix):
            raise ControlError(f"C implementation: prefix {self.prefix!r} is not a C "
                               f"identifier of at most 31 characters")
        object.__setattr__(self, "source", Path(self.source))
