"""Every hook is project-prefixed, documented in its docstring and in docs/plugins.md."""

import inspect
import re

from orccad_app.plugin_host import REGISTRATION_HOOKS, STARTUP_HOOKS, hookspecs

from tests.plugins.conftest import REPO

GUIDE = (REPO / "docs" / "plugins.md").read_text(encoding="utf-8")


def hooks():
    return {name: function for name, function in inspect.getmembers(hookspecs, inspect.isfunction)
            if hasattr(function, "orccad_spec")}


def test_hooks_are_prefixed_and_have_a_docstring():
    assert hooks()
    for name, function in hooks().items():
        assert name.startswith("orccad_"), name
        assert inspect.getdoc(function) and len(inspect.getdoc(function)) > 40, name


def test_every_hook_belongs_to_a_phase():
    phases = [name for name, _ in REGISTRATION_HOOKS] + list(STARTUP_HOOKS)
    assert sorted(phases) == sorted(hooks())


def test_every_hook_is_documented_in_the_plugin_guide():
    documented = set(re.findall(r"^#### `(orccad_\w+)\(", GUIDE, re.MULTILINE))
    assert documented == set(hooks())
    for name, function in hooks().items():
        arguments = ", ".join(inspect.signature(function).parameters)
        assert f"#### `{name}({arguments})`" in GUIDE, name


def test_the_example_plugin_implements_every_hook():
    example = GUIDE.split("## A complete third-party plugin", 1)[1]
    for name in hooks():
        assert f"def {name}(" in example, name


def test_registration_is_driven_by_one_table():
    from orccad_app.plugin_host import CATEGORIES, PluginHost, Registries

    registration = {name for name in hooks() if name.startswith("orccad_register_")}
    assert [c.hook for c in CATEGORIES] == [name for name, _ in REGISTRATION_HOOKS]
    assert {c.hook for c in CATEGORIES} == registration
    registries = Registries.empty()
    assert [name for name, _ in registries.all()] == [c.attribute for c in CATEGORIES]
    host = PluginHost.load()
    for category in CATEGORIES:  # every category is filled through the same path
        assert len(getattr(host.registries, category.attribute)) > 0, category.attribute
