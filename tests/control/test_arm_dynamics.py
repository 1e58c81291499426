"""The arm's Pinocchio model, built from robots/arm3dof.xml, equals MuJoCo's dynamics.

M(q) is compared with ``mujoco.mj_fullM(m, d, dst)`` (MuJoCo 4 signature) and the bias
N(q, qdot) = C(q, qdot) qdot + g(q) with ``d.qfrc_bias``. Armature (rotor inertia) is part
of both mass matrices; viscous damping is a passive force in MuJoCo, outside qfrc_bias.
"""

import mujoco
import numpy as np
import pinocchio
import pytest

from orccad_app.control.models import PinocchioModel, perturbed_model

from tests.control.conftest import ARM_XML

TOL = 1e-9


@pytest.fixture(scope="module")
def models():
    mj_model = mujoco.MjModel.from_xml_path(str(ARM_XML))
    pin_model = pinocchio.buildModelFromMJCF(str(ARM_XML))
    return mj_model, mujoco.MjData(mj_model), pin_model, pin_model.createData()


def random_states(count=25, seed=1):
    rng = np.random.default_rng(seed)
    for _ in range(count):
        yield rng.uniform(-1.5, 1.5, 3), rng.uniform(-4.0, 4.0, 3)


def test_the_plugin_loads_the_canonical_mjcf_file(arm):
    assert arm.mjcf_path.resolve() == ARM_XML.resolve()
    assert arm.mjcf_path.read_bytes() == ARM_XML.read_bytes()


def test_both_models_have_the_same_structure(models):
    mj_model, _, pin_model, _ = models
    assert (mj_model.nq, mj_model.nv) == (pin_model.nq, pin_model.nv) == (3, 3)
    np.testing.assert_allclose(pin_model.gravity.linear, mj_model.opt.gravity)
    np.testing.assert_allclose(pin_model.armature, mj_model.dof_armature)
    np.testing.assert_allclose(pin_model.lowerPositionLimit, mj_model.jnt_range[:, 0])


def test_mass_matrix_equals_mujoco_at_random_states(models):
    mj_model, mj_data, pin_model, pin_data = models
    for q, qdot in random_states():
        mj_data.qpos[:], mj_data.qvel[:] = q, qdot
        mujoco.mj_forward(mj_model, mj_data)
        expected = np.zeros((3, 3))
        mujoco.mj_fullM(mj_model, mj_data, expected)
        upper = pinocchio.crba(pin_model, pin_data, q)
        actual = np.triu(upper) + np.triu(upper, 1).T
        np.testing.assert_allclose(actual, expected, rtol=0, atol=TOL)


def test_bias_forces_equal_mujoco_at_random_states(models):
    mj_model, mj_data, pin_model, pin_data = models
    for q, qdot in random_states():
        mj_data.qpos[:], mj_data.qvel[:] = q, qdot
        mujoco.mj_forward(mj_model, mj_data)
        rnea = pinocchio.rnea(pin_model, pin_data, q, qdot, np.zeros(3))
        nle = pinocchio.nonLinearEffects(pin_model, pin_data, q, qdot)
        np.testing.assert_allclose(rnea, mj_data.qfrc_bias, rtol=0, atol=TOL)
        np.testing.assert_allclose(nle, mj_data.qfrc_bias, rtol=0, atol=TOL)


def test_the_library_model_adds_mujoco_joint_damping(arm, models):
    mj_model, mj_data, _, _ = models
    model = PinocchioModel(arm.pinocchio_model())
    for q, qdot in random_states(5):
        mj_data.qpos[:], mj_data.qvel[:] = q, qdot
        mujoco.mj_forward(mj_model, mj_data)
        expected = mj_data.qfrc_bias - mj_data.qfrc_passive
        np.testing.assert_allclose(model.nonlinear_effects(q, qdot), expected, atol=TOL)
        full = np.zeros((3, 3))
        mujoco.mj_fullM(mj_model, mj_data, full)
        np.testing.assert_allclose(model.mass_matrix(q), full, atol=TOL)


def test_end_effector_site_is_the_same_frame(arm, models):
    mj_model, mj_data, pin_model, pin_data = models
    site = mujoco.mj_name2id(mj_model, mujoco.mjtObj.mjOBJ_SITE, "end_effector")
    for q, _ in random_states(5):
        mj_data.qpos[:] = q
        mujoco.mj_forward(mj_model, mj_data)
        pinocchio.framesForwardKinematics(pin_model, pin_data, q)
        frame = pin_model.getFrameId(arm.end_effector)
        np.testing.assert_allclose(pin_data.oMf[frame].translation, mj_data.site_xpos[site],
                                   atol=TOL)


def test_perturbed_model_is_seeded_and_bounded(arm):
    nominal = PinocchioModel(arm.pinocchio_model())
    q = np.array([0.3, 0.8, -0.4])
    first = perturbed_model(arm.pinocchio_model(), 0.2, seed=7)
    again = perturbed_model(arm.pinocchio_model(), 0.2, seed=7)
    other = perturbed_model(arm.pinocchio_model(), 0.2, seed=8)
    np.testing.assert_array_equal(first.mass_matrix(q), again.mass_matrix(q))
    assert not np.allclose(first.mass_matrix(q), other.mass_matrix(q))
    assert not np.allclose(first.mass_matrix(q), nominal.mass_matrix(q))
    gravity = slice(1, 3)  # the waist axis is vertical: no gravity torque on joint 1
    ratio = (first.nonlinear_effects(q, np.zeros(3))[gravity]
             / nominal.nonlinear_effects(q, np.zeros(3))[gravity])
    assert np.all((ratio > 0.8 - 1e-9) & (ratio < 1.2 + 1e-9))
