"""The C helper functions of a generated automaton: checked 64-bit arithmetic, the finiteness
of a real result and the exact comparison of an integer with a real.

Each is a ``static`` function included only when the generated code calls it (an unused static
function is a warning, and the generated code compiles with ``-Werror``). They call nothing
and need no header beyond ``<stdint.h>``: the object file needs no library, not even libm
(``nm -u`` lists nothing), and the step builds freestanding (``-ffreestanding -nostdinc``).
"""

from __future__ import annotations

import re

__all__ = ["HELPERS", "helpers_for"]

#: name -> C definition. Each returns 0, or 1 on overflow (2: division by zero).
HELPERS: dict[str, str] = {
    "ck_add": """\
static int ck_add(int64_t a, int64_t b, int64_t *r)
{
    if ((b > 0 && a > INT64_MAX - b) || (b < 0 && a < INT64_MIN - b)) return 1;
    *r = a + b;
    return 0;
}""",
    "ck_sub": """\
static int ck_sub(int64_t a, int64_t b, int64_t *r)
{
    if ((b < 0 && a > INT64_MAX + b) || (b > 0 && a < INT64_MIN + b)) return 1;
    *r = a - b;
    return 0;
}""",
    "ck_mul": """\
static int ck_mul(int64_t a, int64_t b, int64_t *r)
{
    if (a > 0) {
        if (b > 0) { if (a > INT64_MAX / b) return 1; }
        else if (b < INT64_MIN / a) return 1;
    } else if (a < 0) {
        if (b > 0) { if (a < INT64_MIN / b) return 1; }
        else if (b < 0 && a < INT64_MAX / b) return 1;
    }
    *r = a * b;
    return 0;
}""",
    "ck_div": """\
static int ck_div(int64_t a, int64_t b, int64_t *r)
{
    if (b == 0) return 2;
    if (a == INT64_MIN && b == -1) return 1;
    *r = a / b; /* C99 truncates toward zero, as the plan language's '/' on integers */
    return 0;
}""",
    "ck_neg": """\
static int ck_neg(int64_t a, int64_t *r)
{
    if (a == INT64_MIN) return 1;
    *r = -a;
    return 0;
}""",
    "ck_finite": """\
/* 1 when the real x is finite: x - x is then 0, and NaN for an infinity or a NaN (IEEE 754
   arithmetic, as isfinite() of <math.h>, which the step does not include) */
static int ck_finite(double x)
{
    return x - x == 0.0;
}""",
    "cmp_if": """\
/* -1, 0 or 1 as the integer a is below, equal to or above the (finite) real b, compared
   exactly as Python compares an int with a float (no rounding of a to a double) */
static int cmp_if(int64_t a, double b)
{
    int64_t whole;
    double fraction;
    if (b >= 9223372036854775808.0) return -1;
    if (b < -9223372036854775808.0) return 1;
    whole = (int64_t)b; /* truncated toward zero: exact, |b| < 2^63 */
    if (a < whole) return -1;
    if (a > whole) return 1;
    fraction = b - (double)whole;
    return fraction > 0.0 ? -1 : (fraction < 0.0 ? 1 : 0);
}""",
}


def helpers_for(code: str) -> str:
    """The definitions of the helpers ``code`` calls, in a fixed order."""
    used = [name for name in HELPERS if re.search(rf"\b{name}\(", code)]
    return "\n\n".join(HELPERS[name] for name in used)
