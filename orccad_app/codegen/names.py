"""C names of a generated automaton: the prefix of its files and identifiers, and the program's
names (signals, variables) made C identifiers that no header and no compiler owns.

The generated files include ``<stdbool.h>``, ``<stddef.h>``, ``<stdint.h>`` (``PREFIX.h``),
``<math.h>`` (``PREFIX.c``, only when its step checks a real result) and ``<errno.h>``,
``<stdio.h>``, ``<stdlib.h>``, ``<string.h>``, ``<sys/stat.h>`` (``PREFIX_main.c``). A
struct field named as one of their macros (``bool NAN;``, ``bool errno;``) does not compile,
nor does one named as a keyword, a macro the compiler predefines (``linux`` in GNU C) or one
the header defines itself (``ABRO_DONE``), and
names beginning with ``_`` and a capital or a second ``_`` are the implementation's (C99
7.1.3). :func:`c_identifier` gives such a name a prefix (``NAN`` → ``s_NAN``): the header's
comment on each field says which signal it is.

A prefix names files too (``PREFIX.h``): :func:`check_prefix` refuses one that is a system
header's name (``stdint.h`` would be found for ``<stdint.h>`` with ``-I DIR``) and
:func:`default_prefix` makes a mission's name a prefix that passes (``Main`` → ``main``,
``Int`` → ``mission_int``).
"""

from __future__ import annotations

import re

from orccad_app.diagnostics import OrccadError

__all__ = ["C_KEYWORDS", "LIBRARY_NAMES", "SYSTEM_HEADERS", "MACRO_SUFFIXES", "reserved",
           "c_identifier", "check_prefix", "default_prefix", "header_guard", "own_macros"]

#: the keywords of C99, C11 and C23 (C23 makes ``bool``, ``true`` and ``false`` keywords)
C_KEYWORDS = frozenset(
    "auto break case char const continue default do double else enum extern float for goto "
    "if inline int long register restrict return short signed sizeof static struct switch "
    "typedef union unsigned void volatile while _Bool _Complex _Imaginary _Alignas _Alignof "
    "_Atomic _Generic _Noreturn _Static_assert _Thread_local alignas alignof bool constexpr "
    "false nullptr static_assert thread_local true typeof typeof_unqual _BitInt _Decimal32 "
    "_Decimal64 _Decimal128 asm fortran".split())

#: macros (and a few other names) of the headers the generated files include, by header, as
#: C99, POSIX and the GNU C library define them, and the compilers' predefined macros without
#: a leading underscore; the families of :data:`_LIBRARY_PATTERN` are not repeated here
LIBRARY_NAMES = frozenset("""
    NULL offsetof ptrdiff_t size_t wchar_t max_align_t
    bool true false
    int8_t int16_t int32_t int64_t uint8_t uint16_t uint32_t uint64_t intptr_t uintptr_t
    intmax_t uintmax_t
    INFINITY NAN HUGE MAXFLOAT MATH_ERRNO MATH_ERREXCEPT math_errhandling float_t double_t
    fpclassify isfinite isinf isnan isnormal signbit isgreater isgreaterequal isless
    islessequal islessgreater isunordered iscanonical iseqsig issignaling issubnormal iszero
    DOMAIN SING OVERFLOW UNDERFLOW TLOSS PLOSS X_TLOSS
    errno
    EOF BUFSIZ FILENAME_MAX FOPEN_MAX L_tmpnam L_ctermid L_cuserid P_tmpdir TMP_MAX
    SEEK_CUR SEEK_END SEEK_SET SEEK_DATA SEEK_HOLE stdin stdout stderr FILE fpos_t
    RENAME_EXCHANGE RENAME_NOREPLACE RENAME_WHITEOUT
    EXIT_FAILURE EXIT_SUCCESS RAND_MAX MB_CUR_MAX alloca div_t ldiv_t lldiv_t
    WCONTINUED WEXITED WEXITSTATUS WIFCONTINUED WIFEXITED WIFSIGNALED WIFSTOPPED WNOHANG
    WNOWAIT WSTOPPED WSTOPSIG WTERMSIG WUNTRACED WCOREDUMP WCOREFLAG W_EXITCODE W_STOPCODE
    BIG_ENDIAN LITTLE_ENDIAN PDP_ENDIAN BYTE_ORDER FD_CLR FD_ISSET FD_SET FD_SETSIZE FD_ZERO
    NFDBITS be16toh be32toh be64toh htobe16 htobe32 htobe64 htole16 htole32 htole64 le16toh
    le32toh le64toh strdupa strndupa
    ACCESSPERMS ALLPERMS DEFFILEMODE UTIME_NOW UTIME_OMIT
    linux unix i386 sun sparc mips vax
""".split())

#: families of reserved names: C99 7.1.3 (``_`` and a capital or ``_``), ``<errno.h>``'s
#: ``E…`` (7.26.3), ``<stdint.h>``'s limits and constant macros (7.26.8), ``<math.h>``'s
#: ``FP_…`` and ``M_…`` (with the GNU library's ``HUGE_VAL…`` and ``SNAN…`` variants),
#: ``<sys/stat.h>``'s ``S_…``, ``st_…`` and ``STATX…`` (POSIX)
_LIBRARY_PATTERN = re.compile(
    r"_[A-Z_]\w*|E[0-9A-Z]\w*|U?INT\w*_(?:MAX|MIN|C|WIDTH)"
    r"|(?:PTRDIFF|SIZE|WCHAR|WINT|SIG_ATOMIC|U?INTPTR|U?INTMAX)_\w+"
    r"|FP_[A-Z]\w*|M_\w+|HUGE_VAL\w*|SNAN\w*|S_[A-Z]\w*|st_\w+|STATX\w*")

#: the names of the C standard's and POSIX's headers (a prefix names files: ``PREFIX.h``)
SYSTEM_HEADERS = frozenset("""
    assert complex ctype errno fenv float inttypes iso646 limits locale math setjmp signal
    stdalign stdarg stdatomic stdbit stdbool stdckdint stddef stdint stdio stdlib stdnoreturn
    string tgmath threads time uchar wchar wctype
    aio cpio dirent dlfcn fcntl fmtmsg fnmatch ftw glob grp iconv langinfo libgen libintl
    monetary mqueue ndbm netdb nl_types poll pthread pwd regex sched search semaphore spawn
    strings stropts syslog tar termios trace ulimit unistd utime utmpx wordexp
    alloca endian err error execinfo features getopt malloc memory sysexits values
""".split())

#: the names generated code uses of its own inside the structs (``out->status``) and the
#: step function (``m``, ``in``, ``out``): a field never takes one
_OWN = frozenset("m in out status state unused".split())

_IDENTIFIER = re.compile(r"[A-Za-z][A-Za-z0-9_]{0,62}")
_PREFIX_MAX = 63


def reserved(name: str) -> bool:
    """``name`` is a C keyword, a name of a header the generated files include, a macro the
    compiler predefines, or the implementation's (C99 7.1.3)."""
    return (name in C_KEYWORDS or name in LIBRARY_NAMES
            or _LIBRARY_PATTERN.fullmatch(name) is not None)


def c_identifier(name: str, taken: set[str], macros: frozenset[str] = frozenset()) -> str:
    """``name`` as a C identifier that is not :func:`reserved`, not the generated code's own
    (``macros``: those of the header, :func:`own_macros`) and not in ``taken`` (which it is
    added to, with its ``_value`` field)."""
    base = re.sub(r"[^A-Za-z0-9_]", "_", name) or "_"
    if base[0].isdigit() or base[0] == "_" or reserved(base) or base in _OWN \
            or reserved(base + "_value") or base in macros or base + "_value" in macros:
        base = "s_" + base
    candidate, number = base, 1
    while candidate in taken or f"{candidate}_value" in taken:
        number += 1
        candidate = f"{base}_{number}"
    taken.add(candidate)
    taken.add(f"{candidate}_value")
    return candidate


def _problem(prefix: str) -> str | None:
    """Why ``prefix`` cannot prefix the generated files and identifiers, or ``None``."""
    if not _IDENTIFIER.fullmatch(prefix):
        return ("is not a C identifier prefix (letters, digits and _, starting with a letter: "
                "names beginning with _ are the C implementation's; at most 63 characters)")
    if prefix in C_KEYWORDS:
        return "is a C keyword"
    if prefix.lower() in SYSTEM_HEADERS:
        return (f"would name the file {prefix}.h, a system header's name (a build with -I "
                f"on the folder would include it for <{prefix.lower()}.h>)")
    if prefix.upper() == "ORCCAD" or prefix.lower().startswith("orccad_"):
        return "begins with orccad_, the generated headers' own prefix"
    return None


def check_prefix(prefix: str) -> str:
    """``prefix`` (``--name``) when it can prefix the generated files and identifiers, else
    an :class:`OrccadError` saying why."""
    problem = _problem(prefix)
    if problem is not None:
        raise OrccadError(f"--name '{prefix}' {problem}")
    return prefix


def default_prefix(mission: str) -> str:
    """The prefix of a mission's files when no ``--name`` is given: its name in snake case
    (``ArmRecovery`` → ``arm_recovery``), made usable (``Int`` → ``mission_int``)."""
    words = re.sub(r"(?<=[a-z0-9])(?=[A-Z])", "_", mission).lower()
    prefix = re.sub(r"[^a-z0-9_]", "_", words).strip("_")[:_PREFIX_MAX].rstrip("_")
    if _problem(prefix) is not None:
        prefix = ("mission_" + prefix)[:_PREFIX_MAX].rstrip("_")
    return prefix


#: the suffixes of the macros ``PREFIX.h`` defines (``PREFIX_RUNNING`` …)
MACRO_SUFFIXES = ("RUNNING", "DONE", "FAILED", "ABORTED", "STATE_COUNT", "SITE_COUNT",
                  "STRING_COUNT", "ERROR_COUNT", "INPUT_COUNT", "OUTPUT_COUNT")


def own_macros(prefix: str) -> frozenset[str]:
    """Every macro ``PREFIX.h`` defines: no field may be one (``bool ABRO_DONE;``)."""
    return frozenset({f"{prefix.upper()}_{suffix}" for suffix in MACRO_SUFFIXES}
                     | {header_guard(prefix), "ORCCAD_GENERATED_COMMON"})


def header_guard(prefix: str) -> str:
    """The include guard of ``PREFIX.h``: in the generator's own ``ORCCAD_GENERATED_``
    namespace, so that no prefix makes it a system header's (``_STDINT_H``) or the runtime
    library's (``ORCCAD_RT_H``)."""
    return f"ORCCAD_GENERATED_{prefix.upper()}_H"
