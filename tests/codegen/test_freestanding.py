"""The step files build freestanding (issue 34, item 3): ``PREFIX.h`` and ``PREFIX.c``
include only ``<stdbool.h>``, ``<stddef.h>`` and ``<stdint.h>`` (headers a freestanding
implementation provides, C99 §4) and call no library function, libm included: a build with
``-ffreestanding -nostdinc`` and only the compiler's own include folder succeeds for every
shipped mission and for real arithmetic (``tests/codegen/data/values.orc``)."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

from tests.codegen.cbuild import STRICT, compiler
from tests.codegen.conftest import SHIPPED, generated
from tests.codegen.helpers import make
from tests.codegen.test_values import DATA


def _programs():
    yield from (generated(stem, mission).program for stem, mission in SHIPPED)
    yield make(DATA / "values.orc", "values").program


def test_every_step_builds_freestanding_and_needs_no_library(tmp_path):
    cc = compiler()
    own = subprocess.run([cc, "-print-file-name=include"], capture_output=True, text=True,
                         check=True).stdout.strip()
    if not (own and (Path(own) / "stdint.h").exists()):
        pytest.skip(f"{cc} names no include folder of its own")
    has_nm = shutil.which("nm") is not None
    reals = 0
    for program in _programs():
        included = re.findall(r"#include <([^>]+)>", program.header + program.source)
        assert sorted(set(included)) == ["stdbool.h", "stddef.h", "stdint.h"], program.prefix
        reals += "ck_finite(" in program.source
        for name, text in program.files.items():
            (tmp_path / name).write_text(text)
        done = subprocess.run([cc, *STRICT, "-O0", "-ffreestanding", "-nostdinc", "-isystem",
                               own, "-c", f"{program.prefix}.c"], cwd=tmp_path,
                              capture_output=True, text=True)
        assert done.returncode == 0, f"{program.prefix}: {done.stderr[:2000]}"
        if has_nm:
            undefined = subprocess.run(["nm", "-u", f"{program.prefix}.o"], cwd=tmp_path,
                                       capture_output=True, text=True, check=True).stdout
            assert undefined.split() == [], f"{program.prefix} calls {undefined}"
    assert reals >= 1  # values.orc checks real results: still no <math.h>, no libm
