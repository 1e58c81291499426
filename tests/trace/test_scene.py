"""The robot's frames and geometry from MJCF (orccad_app/trace/scene.py): every geom type
Foxglove can draw, on an inline model."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from orccad_app.trace.scene import robot_scene

MJCF = """
<mujoco>
  <asset>
    <mesh name="tetra" vertex="0 0 0  1 0 0  0 1 0  0 0 1"/>
  </asset>
  <worldbody>
    <geom name="ground" type="plane" size="0 0 1"/>
    <body name="base" pos="1 0 0">
      <joint name="slide" type="slide" axis="1 0 0"/>
      <geom name="box" type="box" size="0.1 0.2 0.3"/>
      <body>
        <joint name="hinge" type="hinge" axis="0 0 1"/>
        <geom name="ball" type="sphere" size="0.05" pos="0 0 1"/>
        <geom name="egg" type="ellipsoid" size="0.1 0.2 0.3"/>
        <geom name="rod" type="capsule" fromto="0 0 0 0 0 0.5" size="0.02"/>
        <geom name="can" type="cylinder" size="0.1 0.2"/>
        <geom name="shape" type="mesh" mesh="tetra"/>
      </body>
    </body>
    <body name="float" pos="0 0 2">
      <freejoint/>
      <geom type="sphere" size="0.1"/>
    </body>
  </worldbody>
</mujoco>
"""


@pytest.fixture(scope="module")
def scene():
    return robot_scene("r", mujoco.MjModel.from_xml_string(MJCF))


def test_every_geom_type_becomes_foxglove_primitives(scene):
    kinds = {e.entity_id: [p.kind for p in e.primitives] for e in scene.entities}
    assert kinds == {"r/ground": ["cubes"], "r/box": ["cubes"], "r/ball": ["spheres"],
                     "r/egg": ["spheres"], "r/rod": ["cylinders", "spheres", "spheres"],
                     "r/can": ["cylinders"], "r/shape": ["triangles"], "r/geom7": ["spheres"]}
    by_id = {e.entity_id: e for e in scene.entities}
    assert by_id["r/box"].primitives[0].size == pytest.approx((0.2, 0.4, 0.6))
    assert by_id["r/egg"].primitives[0].size == pytest.approx((0.2, 0.4, 0.6))
    assert by_id["r/ground"].primitives[0].size[:2] == (10.0, 10.0)  # infinite: 10 m
    assert len(by_id["r/shape"].primitives[0].points) == 12  # 4 faces, 3 vertices each
    assert by_id["r/ball"].frame_id == "r/body2" and by_id["r/ground"].frame_id == "world"


def test_frames_and_joints_of_the_tree(scene):
    assert [(f.frame_id, f.parent_id) for f in scene.frames] == [
        ("r/base", "world"), ("r/body2", "r/base"), ("r/float", "world")]
    assert scene.joints.names == ("slide", "hinge") and scene.floating == ("r/float",)
    qpos = np.zeros(scene.model.nq)
    qpos[0], qpos[1] = 0.5, math.pi / 2  # slide 0.5 m, hinge a quarter turn
    qpos[2:5], qpos[5:9] = (0, 0, 2), (1, 0, 0, 0)
    base, body, floating = scene.transforms(qpos)
    assert base.translation == pytest.approx((1.5, 0, 0))
    assert body.rotation == pytest.approx((0, 0, math.sin(math.pi / 4), math.cos(math.pi / 4)))
    assert floating.translation == pytest.approx((0, 0, 2))
