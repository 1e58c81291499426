"""Registries: providers, duplicates, unknown names with close matches."""

import pytest

from orccad_app.control.catalogue import CONSTANT, COSINE, MINIMUM_JERK
from orccad_app.diagnostics import OrccadError
from orccad_app.plugin_host import Registries, Registry


def test_items_remember_their_plugin_in_registration_order():
    registry = Registry("trajectory")
    registry.add(COSINE, "alpha")
    registry.add(MINIMUM_JERK, "beta")
    assert registry.names() == ["cosine", "min_jerk"] and len(registry) == 2
    assert registry.get("cosine") is COSINE and registry.plugin_of("min_jerk") == "beta"
    assert [entry.plugin for entry in registry.entries()] == ["alpha", "beta"]
    assert "cosine" in registry and list(registry) == [COSINE, MINIMUM_JERK]


def test_unknown_names_raise_with_close_matches_and_the_known_names():
    registry = Registry("trajectory")
    for kind in (COSINE, MINIMUM_JERK, CONSTANT):
        registry.add(kind, "p")
    with pytest.raises(OrccadError) as caught:
        registry.get("cosin")
    assert str(caught.value) == ("unknown trajectory 'cosin' (did you mean 'cosine'?); "
                                 "known: cosine, min_jerk, constant")
    with pytest.raises(OrccadError, match="unknown trajectory 'bezier'; known:"):
        registry.get("bezier")


def test_an_empty_registry_says_nothing_is_installed():
    with pytest.raises(OrccadError, match="known: none installed"):
        Registry("robot type").get("arm3dof")


def test_duplicates_and_invalid_items_are_refused():
    registries = Registries.empty()
    registries.trajectories.add(COSINE, "alpha")
    with pytest.raises(OrccadError, match="already provided by plugin 'alpha'"):
        registries.trajectories.add(COSINE, "beta")
    with pytest.raises(OrccadError, match="must be a LawKind"):
        registries.control_laws.add(COSINE, "alpha")
    with pytest.raises(OrccadError, match="has no name"):
        registries.trajectories.add(object(), "alpha")


def test_observers_need_an_event_output(host):
    registries = Registries.empty()
    with pytest.raises(OrccadError, match="needs at least one 'event' output port"):
        registries.observers.add(host.module_kind("trajectory"), "p")
    registries.observers.add(host.module_kind("at_rest"), "p")


def test_remove_plugin_withdraws_its_items():
    registries = Registries.empty()
    registries.trajectories.add(COSINE, "alpha")
    registries.trajectories.add(CONSTANT, "beta")
    registries.remove_plugin("alpha")
    assert registries.trajectories.names() == ["constant"]
