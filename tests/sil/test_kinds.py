"""Each C Module-Task kind computes what its Python kind computes, on the same inputs: bit for
bit for the arm's PID kinds (the same IEEE operations in the same order), within 1e-12
relative for the AUV's (distances through hypot, whose last bit may differ from Python's
math.dist) and for computed torque (the C rigid-body dynamics against Pinocchio's)."""

from __future__ import annotations

import numpy as np
import pytest

from orccad_app.mission.plan import SiteModules
from orccad_app.sil.lockstep import lockstep, random_inputs
from orccad_app.sil.controller.remote import RemoteModule

from tests.sil.helpers import plan_of


def _same(expected: dict, got: dict, exact: bool) -> None:
    assert expected.keys() == got.keys()
    for name, value in expected.items():
        want = np.asarray(value, dtype=float)
        have = np.asarray(got[name], dtype=float)
        if exact:
            assert want.tobytes() == have.tobytes(), name
        else:
            np.testing.assert_allclose(have, want, rtol=1e-12, atol=1e-300, err_msg=name)


CASES = [("arm_pid.orc", None, True, 0.6), ("arm_retune.orc", None, True, 0.6),
         ("arm_recovery.orc", None, True, 0.6), ("auv_survey.orc", None, False, 20.0),
         ("auv_waypoints.orc", None, False, 20.0),
         ("arm_computed_torque.orc", None, False, 0.6),
         ("arm_computed_torque_multirate.orc", None, False, 0.6)]


@pytest.mark.parametrize("file,mission,exact,scale", CASES)
def test_each_c_kind_computes_what_its_python_kind_computes(file, mission, exact, scale):
    plan = plan_of(file, mission)
    rng = np.random.default_rng(7)
    with lockstep(plan, file) as started:
        for site in started.plan.sites:
            remotes = site.fresh_computes()
            pythons = SiteModules.fresh_computes(site)  # new Python instances, same args
            for name, remote in remotes.items():
                assert isinstance(remote, RemoteModule)
                python = pythons[name]
                python.init()
                remote.init()
                for job in range(60):
                    t_s = 0.001 * job
                    inputs = random_inputs(python, rng, scale)
                    _same(python.compute(t_s, inputs), remote.compute(t_s, inputs), exact)
        assert started.controller.alive
