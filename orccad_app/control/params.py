"""Typed, validated parameters of control-library components and module kinds.

A component (trajectory, task function, control law, module kind, robot type) declares its
parameters as :class:`ParamSpec` s. :func:`resolve_params` checks the values a user gave
against them: unknown names (with close matches), missing required ones, wrong types and
out-of-range values raise :class:`~orccad_app.control.errors.InvalidParameter` naming the
component, the parameter and the bad value.

Parameter types (``ParamSpec.type``):

=================  ==================================================================
``float``          a real number
``int``            an integer
``bool``           ``True`` / ``False``
``string``         a string (optionally one of ``choices``)
``vector``         a 1-D sequence of reals → ``numpy.ndarray``
``float|vector``   a real, or one real per component (e.g. per-joint gains)
``matrix``         a real (× identity), a vector (diagonal) or a square matrix
``trajectory``     a :class:`~orccad_app.control.trajectories.Trajectory` or a call form
                   (see :func:`as_call`) resolved through the trajectory registry
=================  ==================================================================
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from orccad_app.control.errors import InvalidParameter
from orccad_app.diagnostics import cut

__all__ = [
    "REQUIRED",
    "PARAM_TYPES",
    "ParamSpec",
    "resolve_params",
    "as_call",
    "close_matches",
]


class _Required:
    """Sentinel default of a parameter that must be given."""

    def __repr__(self) -> str:
        return "REQUIRED"


#: Default of a :class:`ParamSpec` that has no default: the user must give a value.
REQUIRED: Any = _Required()

PARAM_TYPES: tuple[str, ...] = (
    "float", "int", "bool", "string", "vector", "float|vector", "matrix", "trajectory",
)

#: ``resolver(spec, value) -> value`` turns a call form into an object (e.g. a trajectory).
Resolver = Callable[["ParamSpec", Any], Any]


def close_matches(name: str, candidates: Sequence[str]) -> str:
    """`` (did you mean 'x'?)`` for the closest candidates, or an empty string."""
    found = difflib.get_close_matches(name, list(candidates), n=3, cutoff=0.6)
    if not found:
        return ""
    return " (did you mean " + " or ".join(repr(match) for match in found) + "?)"


def as_call(value: Any) -> tuple[str, dict[str, Any]] | None:
    """The ``(name, args)`` of a call form, or ``None`` if ``value`` is not one.

    Accepted call forms: ``"cosine"``; ``("cosine", {"q0": [...]})``;
    ``{"kind": "cosine", "q0": [...]}``; any object with a ``name`` string and an ``args``
    (or ``params``) mapping, such as a parsed ``cosine(q0 = q0)`` from the plan language.
    """
    if isinstance(value, str):
        return value, {}
    if (isinstance(value, tuple) and len(value) == 2 and isinstance(value[0], str)
            and isinstance(value[1], Mapping)):
        return value[0], dict(value[1])
    if isinstance(value, Mapping) and isinstance(value.get("kind"), str):
        args = {key: item for key, item in value.items() if key != "kind"}
        return value["kind"], args
    name = getattr(value, "name", None)
    args = getattr(value, "args", getattr(value, "params", None))
    if isinstance(name, str) and isinstance(args, Mapping):
        return name, dict(args)
    return None


def _is_real(value: Any) -> bool:
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(
        value, (bool, np.bool_))


@dataclass(frozen=True, slots=True)
class ParamSpec:
    """One parameter: ``name``, ``type`` (one of :data:`PARAM_TYPES`) and ``default``.

    ``default`` is :data:`REQUIRED` when the user must give a value, ``None`` when the
    parameter is optional without a value. ``minimum`` bounds reals element-wise
    (``exclusive`` makes it strict, e.g. gains ``> 0``), ``maximum`` from above (inclusive);
    ``choices`` restricts strings.
    """

    name: str
    type: str
    default: Any = None
    doc: str = ""
    minimum: float | None = None
    exclusive: bool = False
    choices: tuple[str, ...] | None = None
    maximum: float | None = None

    def __post_init__(self) -> None:
        if self.type not in PARAM_TYPES:
            raise InvalidParameter(
                f"parameter {self.name!r} has unknown type {self.type!r}; "
                f"expected one of {', '.join(PARAM_TYPES)}")

    @property
    def required(self) -> bool:
        """True when the parameter has no default."""
        return self.default is REQUIRED

    def coerce(self, value: Any, owner: str) -> Any:
        """``value`` converted to this parameter's type; raises naming ``owner.name``."""
        if value is None and not self.required:
            return None
        converted = self._convert(value, owner)
        self._check_range(converted, owner)
        return converted

    def convert(self, value: Any, owner: str) -> Any:
        """``value`` converted to this parameter's type (finite, right shape), its range not
        checked: what a value computed later must at least be."""
        return self._convert(value, owner)

    def _fail(self, owner: str, expected: str, value: Any) -> InvalidParameter:
        return InvalidParameter(f"{owner}: {self.name} must be {expected}, got {value!r}")

    def _convert(self, value: Any, owner: str) -> Any:
        kind = self.type
        if kind == "float":
            if not _is_real(value) or math.isnan(float(value)):
                raise self._fail(owner, "a number", value)
            if not math.isfinite(float(value)):
                raise self._fail(owner, "a finite number", value)
            return float(value)
        if kind == "int":
            if _is_real(value) and float(value).is_integer():
                return int(value)
            raise self._fail(owner, "an integer", value)
        if kind == "bool":
            if isinstance(value, (bool, np.bool_)):
                return bool(value)
            raise self._fail(owner, "true or false", value)
        if kind == "string":
            if not isinstance(value, str):
                raise self._fail(owner, "a string", value)
            if self.choices is not None and value not in self.choices:
                raise self._fail(owner, "one of " + ", ".join(map(repr, self.choices)), value)
            return value
        if kind == "trajectory":  # call forms are turned into objects by a resolver
            if not callable(getattr(value, "sample", None)):
                raise self._fail(owner, "a trajectory such as cosine(q0 = [...])", value)
            return value
        return self._convert_array(value, owner)

    def _convert_array(self, value: Any, owner: str) -> Any:
        if self.type in ("float|vector", "matrix") and _is_real(value):
            if not math.isfinite(float(value)):
                raise self._fail(owner, "finite", value)
            return float(value)
        try:
            array = np.array(value, dtype=float)
        except (TypeError, ValueError):
            raise self._fail(owner, f"a {self.type}", value) from None
        allowed = {"vector": (1,), "float|vector": (1,), "matrix": (1, 2)}[self.type]
        if array.ndim not in allowed or array.size == 0:
            raise self._fail(owner, f"a {self.type}", value)
        if not np.all(np.isfinite(array)):
            raise self._fail(owner, "finite", value)
        array.setflags(write=False)
        return array

    def _check_range(self, value: Any, owner: str) -> None:
        if not (_is_real(value) or isinstance(value, np.ndarray)):
            return
        data = np.asarray(value, dtype=float)
        if self.maximum is not None and np.any(data > self.maximum):
            shown = value.tolist() if isinstance(value, np.ndarray) else value
            raise InvalidParameter(
                f"{owner}: {self.name} must be <= {self.maximum:g}, got {cut(repr(shown))}")
        if self.minimum is None:
            return
        bad = data <= self.minimum if self.exclusive else data < self.minimum
        if np.any(bad):
            relation = ">" if self.exclusive else ">="
            shown = value.tolist() if isinstance(value, np.ndarray) else value
            raise InvalidParameter(
                f"{owner}: {self.name} must be {relation} {self.minimum:g}, "
                f"got {cut(repr(shown))}")


def resolve_params(owner: str, specs: Sequence[ParamSpec], given: Mapping[str, Any],
                   resolver: Resolver | None = None) -> dict[str, Any]:
    """Validated values for every spec: given ones coerced, the others defaulted.

    Raises :class:`InvalidParameter` for an unknown name (listing close matches and the
    known parameters), a missing required parameter, or a bad value.
    """
    by_name = {spec.name: spec for spec in specs}
    for name in given:
        if name not in by_name:
            known = ", ".join(by_name) or "none"
            raise InvalidParameter(
                f"{owner} has no parameter {name!r}{close_matches(name, list(by_name))}; "
                f"its parameters: {known}")
    values: dict[str, Any] = {}
    for spec in specs:
        if spec.name in given:
            value = given[spec.name]
            if resolver is not None and spec.type == "trajectory" and value is not None:
                value = resolver(spec, value)
            values[spec.name] = spec.coerce(value, owner)
        elif spec.required:
            raise InvalidParameter(f"{owner}: missing parameter {spec.name!r} ({spec.type})")
        else:
            values[spec.name] = spec.default
    return values
