"""The plugin seam: built-in plugins and the guide's example import only the public API."""

from __future__ import annotations

import ast
import re
from pathlib import Path

import orccad_app.plugin_api as api

ROOT = Path(__file__).resolve().parents[2]
GUIDE = ROOT / "docs" / "plugins.md"


def _core_imports(source: str) -> list[str]:
    """Every ``orccad_app`` module ``source`` imports (module level or inside functions)."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names = [node.module]
        elif isinstance(node, ast.Import):
            names = [alias.name for alias in node.names]
        else:
            continue
        found += [name for name in names if name.split(".")[0] == "orccad_app"]
    return found


def test_built_in_plugins_import_only_the_plugin_api():
    files = sorted((ROOT / "plugins").rglob("*.py"))
    assert files
    offending = {str(f.relative_to(ROOT)): bad for f in files
                 if (bad := [m for m in _core_imports(f.read_text(encoding="utf-8"))
                             if m != "orccad_app.plugin_api"])}
    assert offending == {}


def test_the_guide_s_example_plugin_imports_only_the_plugin_api():
    blocks = re.findall(r"^```python[^\n]*\n(.*?)^```", GUIDE.read_text(encoding="utf-8"),
                        re.DOTALL | re.MULTILINE)
    imports = [m for block in blocks for m in _core_imports(block)]
    assert imports and set(imports) == {"orccad_app.plugin_api"}


def test_every_public_name_resolves():
    for name in api.__all__:
        assert getattr(api, name) is not None, name
