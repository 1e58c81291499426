"""Running SPIN on an exported model: one compilation of the verifier, one run per claim.

Needs the ``spin`` executable (Debian package ``spin``) and a C compiler. A claim *holds*
when SPIN finds no acceptance cycle (``errors: 0``) under its never claim.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import tempfile
from pathlib import Path

__all__ = ["spin_available", "run_spin"]


def spin_available() -> str | None:
    """None when SPIN and a C compiler are installed, else why not."""
    for tool in ("spin", "gcc"):
        if shutil.which(tool) is None:
            return f"'{tool}' is not installed (Debian: apt-get install spin gcc)"
    return None


def run_spin(promela: str, claims: list[str], *, timeout: float = 120.0) -> dict[str, bool]:
    """Verdict of SPIN per claim name: True when the claim holds."""
    with tempfile.TemporaryDirectory(prefix="orccad-spin-") as tmp:
        folder = Path(tmp)
        (folder / "model.pml").write_text(promela, encoding="utf-8")
        _run(["spin", "-a", "model.pml"], folder, timeout)
        _run(["gcc", "-O0", "-w", "-DNOREDUCE", "-DVECTORSZ=4096", "-o", "pan", "pan.c"],
             folder, timeout)
        verdicts = {}
        for claim in claims:
            out = _run(["./pan", "-a", "-m1000000", "-N", claim], folder, timeout)
            match = re.search(r"errors: (\d+)", out)
            if match is None:
                raise RuntimeError(f"SPIN gave no verdict for {claim}:\n{out}")
            verdicts[claim] = match.group(1) == "0"
        return verdicts


def _run(command: list[str], folder: Path, timeout: float) -> str:
    result = subprocess.run(command, cwd=folder, capture_output=True, text=True,
                            timeout=timeout)
    if result.returncode != 0 and command[0] != "./pan":
        raise RuntimeError(f"{' '.join(command)} failed:\n{result.stdout}\n{result.stderr}")
    return result.stdout
