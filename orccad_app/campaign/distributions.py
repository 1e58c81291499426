"""Distributions of a campaign spec: what a run's setting is drawn from.

A value in a spec is a number, or one of (case-insensitive names):

==================  =========================================================================
``U(a, b)``         uniform real in ``[a, b]``
``UI(a, b)``        uniform integer in ``{a, …, b}``
``N(mu, sigma)``    normal; ``N(mu, sigma, lo, hi)`` truncated to ``[lo, hi]`` (redrawn)
``choice(v, …)``    one of the values, equally likely
``B(p)``            Bernoulli: 1 with probability ``p``, else 0
==================  =========================================================================

Real draws are rounded to 6 significant digits (:func:`round_sig`) so that a run's replay
command stays readable; the rounded value is the one the run uses. Falsification searches each
distribution's *support* (:attr:`Distribution.bounds`): ``[a, b]`` for ``U``, ``mu ± 4 sigma``
(or ``[lo, hi]``) for ``N``, the values of ``choice``.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from enum import Enum
from typing import Any

import numpy as np

from orccad_app.diagnostics import cut
from orccad_app.lang.literals import LiteralError, read_literal

__all__ = ["Kind", "Distribution", "DistributionError", "parse_distribution", "round_sig",
           "truncated_mass", "MIN_TRUNCATED_MASS"]

_CALL = re.compile(r"^\s*([A-Za-z]+)\s*\((.*)\)\s*$", re.S)
_MAX_REDRAWS = 1000
MIN_TRUNCATED_MASS = 0.05
"""Least probability of ``[lo, hi]`` under ``N(mu, sigma)`` for ``N(mu, sigma, lo, hi)``: its
draws are redrawn until one falls in ``[lo, hi]``, at most ``_MAX_REDRAWS`` times, which then
all fail with a chance of at most ``0.95**1000`` (about 5e-23)."""


def truncated_mass(mu: float, sigma: float, low: float, high: float) -> float:
    """The probability of ``[low, high]`` under the normal ``N(mu, sigma)``."""
    def cdf(x: float) -> float:
        return 0.5 * math.erfc(-(x - mu) / (sigma * math.sqrt(2.0)))
    return cdf(high) - cdf(low)


class DistributionError(ValueError):
    """A malformed distribution (the spec loader adds the location)."""


class Kind(Enum):
    """The family of a :class:`Distribution`."""

    CONSTANT = "constant"
    UNIFORM = "U"
    UNIFORM_INT = "UI"
    NORMAL = "N"
    CHOICE = "choice"
    BERNOULLI = "B"


def round_sig(value: float, digits: int = 6) -> float:
    """``value`` rounded to ``digits`` significant digits."""
    if value == 0 or not math.isfinite(value):
        return value
    return round(value, digits - 1 - int(math.floor(math.log10(abs(value)))))


@dataclass(frozen=True)
class Distribution:
    """One distribution; ``args`` as written (see the module docstring)."""

    kind: Kind
    args: tuple[float, ...]
    text: str

    def sample(self, rng: np.random.Generator) -> float | int:
        """One draw."""
        kind, args = self.kind, self.args
        if kind is Kind.CONSTANT:
            return args[0]
        if kind is Kind.UNIFORM:
            return round_sig(float(rng.uniform(args[0], args[1])))
        if kind is Kind.UNIFORM_INT:
            return int(rng.integers(int(args[0]), int(args[1]) + 1))
        if kind is Kind.CHOICE:
            return args[int(rng.integers(len(args)))]
        if kind is Kind.BERNOULLI:
            return int(rng.random() < args[0])
        return self._normal(rng)

    def _normal(self, rng: np.random.Generator) -> float:
        mu, sigma = self.args[:2]
        low, high = self.bounds
        for _ in range(_MAX_REDRAWS):
            value = float(rng.normal(mu, sigma))
            if len(self.args) == 2 or low <= value <= high:
                return round_sig(value)
        # unreachable for a parsed spec: [lo, hi] holds at least MIN_TRUNCATED_MASS of the
        # normal's mass (a chance below 1e-22 of failing); never silently the mean
        raise DistributionError(f"{cut(repr(self.text))}: {_MAX_REDRAWS} redraws all fell "
                                f"outside [{low:g}, {high:g}]")

    @property
    def bounds(self) -> tuple[float, float]:
        """The support searched by falsification ``(low, high)``."""
        kind, args = self.kind, self.args
        if kind is Kind.NORMAL:
            if len(args) == 4:
                return args[2], args[3]
            return args[0] - 4 * args[1], args[0] + 4 * args[1]
        if kind is Kind.BERNOULLI:
            return 0.0, 1.0
        if kind in (Kind.CHOICE, Kind.CONSTANT):
            return min(args), max(args)
        return args[0], args[1]

    @property
    def choices(self) -> tuple[Any, ...] | None:
        """The finite set of values (choice, Bernoulli, constant), else ``None``."""
        if self.kind is Kind.CHOICE or self.kind is Kind.CONSTANT:
            return self.args
        if self.kind is Kind.BERNOULLI:
            return (0, 1)
        return None

    @property
    def integral(self) -> bool:
        """Every draw is an integer."""
        if self.kind is Kind.UNIFORM_INT or self.kind is Kind.BERNOULLI:
            return True
        return self.choices is not None and all(isinstance(v, int) for v in self.args)


def _number(text: str) -> float | int:
    """A number of the literal grammar (:mod:`orccad_app.lang.literals`)."""
    try:
        value: float | int = read_literal(text, "number")
    except LiteralError as error:
        raise DistributionError(error.message) from None
    return value


_ARITY = {Kind.UNIFORM: (2,), Kind.UNIFORM_INT: (2,), Kind.NORMAL: (2, 4),
          Kind.BERNOULLI: (1,)}
_NAMES = {"u": Kind.UNIFORM, "uniform": Kind.UNIFORM, "ui": Kind.UNIFORM_INT,
          "randint": Kind.UNIFORM_INT, "n": Kind.NORMAL, "normal": Kind.NORMAL,
          "choice": Kind.CHOICE, "b": Kind.BERNOULLI, "bernoulli": Kind.BERNOULLI}


def parse_distribution(value: Any) -> Distribution:
    """A number or a distribution's text; raise :class:`DistributionError`."""
    if isinstance(value, bool):
        raise DistributionError(f"expected a number or a distribution, got {cut(repr(value))}")
    if isinstance(value, (int, float)):
        if not math.isfinite(value):
            raise DistributionError(f"{cut(repr(value))} is not a finite number")
        return Distribution(Kind.CONSTANT, (value,), repr(value))
    if not isinstance(value, str):
        raise DistributionError(f"expected a number or a distribution such as 'U(0, 1)', "
                                f"got {cut(repr(value))}")
    match = _CALL.match(value)
    if match is None:
        return Distribution(Kind.CONSTANT, (_number(value),), value.strip())
    name, inner = match.groups()
    kind = _NAMES.get(name.lower())
    if kind is None:
        raise DistributionError(f"unknown distribution {cut(repr(name))} in "
                                f"{cut(repr(value))} (expected U, UI, N, choice or B)")
    args = tuple(_number(part) for part in inner.split(",")) if inner.strip() else ()
    _check(kind, args, value)
    return Distribution(kind, args, value.strip())


def _check(kind: Kind, args: tuple, text: str) -> None:
    arity = _ARITY.get(kind)
    if arity is not None and len(args) not in arity:
        counts = " or ".join(map(str, arity))
        raise DistributionError(f"{cut(repr(text))}: {kind.value}(…) takes {counts} numbers, "
                                f"got {len(args)}")
    if kind is Kind.CHOICE and not args:
        raise DistributionError(f"{cut(repr(text))}: choice(…) needs at least one value")
    if kind in (Kind.UNIFORM, Kind.UNIFORM_INT) and not args[0] <= args[1]:
        raise DistributionError(f"{cut(repr(text))}: the lower bound exceeds the upper bound")
    if kind is Kind.UNIFORM_INT and not all(float(a).is_integer() for a in args):
        raise DistributionError(f"{cut(repr(text))}: UI(a, b) takes integer bounds")
    if kind is Kind.NORMAL:
        if not args[1] > 0:
            raise DistributionError(f"{cut(repr(text))}: sigma must be > 0")
        if len(args) == 4 and not args[2] <= args[0] <= args[3]:
            raise DistributionError(f"{cut(repr(text))}: the mean must lie in [lo, hi]")
        if len(args) == 4 and truncated_mass(*args) < MIN_TRUNCATED_MASS:
            raise DistributionError(
                f"{cut(repr(text))}: [lo, hi] holds {truncated_mass(*args):.2g} of the "
                f"normal's probability, less than the {MIN_TRUNCATED_MASS:g} its redraws need "
                f"(a draw outside [lo, hi] is drawn again, at most {_MAX_REDRAWS} times): "
                f"widen [lo, hi] or reduce sigma")
    if kind is Kind.BERNOULLI and not 0 <= args[0] <= 1:
        raise DistributionError(f"{cut(repr(text))}: p must be in [0, 1]")
