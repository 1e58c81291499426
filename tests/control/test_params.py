"""Parameter specs: coercion, defaults and errors that name the bad value."""

import numpy as np
import pytest

from orccad_app.control.errors import InvalidParameter
from orccad_app.control.params import REQUIRED, ParamSpec, as_call, resolve_params
from orccad_app.diagnostics import OrccadError

SPECS = (
    ParamSpec("kp", "float|vector", REQUIRED, minimum=0.0, exclusive=True),
    ParamSpec("ki", "float", 0.0, minimum=0.0),
    ParamSpec("mode", "string", "fast", choices=("fast", "slow")),
    ParamSpec("n", "int", 3),
    ParamSpec("on", "bool", True),
    ParamSpec("q0", "vector", None),
    ParamSpec("G", "matrix", 1.0),
)


def test_defaults_fill_missing_optional_parameters():
    values = resolve_params("law", SPECS, {"kp": 2})
    assert values == {"kp": 2.0, "ki": 0.0, "mode": "fast", "n": 3, "on": True,
                      "q0": None, "G": 1.0}


def test_vectors_and_matrices_become_read_only_arrays():
    values = resolve_params("law", SPECS, {"kp": [1, 2, 3], "q0": (0.5, 0.5),
                                           "G": [[1, 0], [0, 2]]})
    assert isinstance(values["kp"], np.ndarray) and values["kp"].tolist() == [1, 2, 3]
    assert values["G"].shape == (2, 2)
    with pytest.raises(ValueError):
        values["q0"][0] = 1.0


def test_unknown_parameter_names_close_matches_and_known_ones():
    with pytest.raises(InvalidParameter) as caught:
        resolve_params("pid", SPECS, {"kp": 1.0, "kpp": 2.0})
    message = str(caught.value)
    assert "'kpp'" in message and "did you mean 'kp'" in message and "ki" in message


def test_missing_required_parameter_is_named():
    with pytest.raises(InvalidParameter, match="pid: missing parameter 'kp'"):
        resolve_params("pid", SPECS, {})


@pytest.mark.parametrize("name, value, fragment", [
    ("kp", -1.0, "kp must be > 0, got -1.0"),
    ("kp", [1.0, 0.0], "kp must be > 0, got [1.0, 0.0]"),
    ("ki", -0.5, "ki must be >= 0, got -0.5"),
    ("mode", "medium", "mode must be one of 'fast', 'slow', got 'medium'"),
    ("n", 2.5, "n must be an integer, got 2.5"),
    ("on", 1, "on must be true or false, got 1"),
    ("q0", "abc", "q0 must be a vector, got 'abc'"),
    ("ki", float("nan"), "ki must be a number"),
])
def test_bad_values_are_named_with_the_value(name, value, fragment):
    given = {"kp": 1.0, name: value}
    with pytest.raises(InvalidParameter) as caught:
        resolve_params("pid", SPECS, given)
    assert fragment in str(caught.value)
    assert isinstance(caught.value, OrccadError)


def test_unknown_parameter_type_is_rejected():
    with pytest.raises(InvalidParameter, match="unknown type 'complex'"):
        ParamSpec("x", "complex")


@pytest.mark.parametrize("form, expected", [
    ("cosine", ("cosine", {})),
    (("cosine", {"q0": [1]}), ("cosine", {"q0": [1]})),
    ({"kind": "cosine", "q0": [1]}, ("cosine", {"q0": [1]})),
    (3.0, None),
])
def test_call_forms(form, expected):
    assert as_call(form) == expected


def test_call_form_from_an_object_with_name_and_args():
    class Call:
        name = "min_jerk"
        args = {"goal": [0.0]}
    assert as_call(Call()) == ("min_jerk", {"goal": [0.0]})


def test_trajectory_parameter_rejects_unresolved_values():
    spec = ParamSpec("trajectory", "trajectory", REQUIRED)
    with pytest.raises(InvalidParameter, match="must be a trajectory"):
        spec.coerce("cosine", "joint_tracking")
