"""The robot as Foxglove's 3D panel draws it: frames of the MJCF kinematic tree and geometry.

:func:`robot_scene` reads a compiled MuJoCo model (the plant's ``MjModel``) once:

- one **frame** per body, ``<robot>/<body>`` (an unnamed body is ``<robot>/body<i>``), whose
  parent is its parent body's frame, or ``world`` for a body attached to the world body: the
  frames of every robot of a mission form one tree rooted at ``world``;
- one **entity** per geom (``<robot>/<geom>``), in its body's frame (``world`` for the world
  body's geoms: the floor, a pedestal), with the geom's pose in that frame: a ``box`` is a
  cube, a ``sphere`` or an ``ellipsoid`` a sphere (Foxglove's sphere has a size per axis), a
  ``cylinder`` a cylinder, a ``capsule`` a cylinder with a sphere at each end, a ``plane`` a
  thin cube (10 m wide when MJCF leaves it infinite), a ``mesh`` a triangle list of the
  compiled mesh's vertices (MuJoCo has loaded and centred the file); height fields are left
  out. Colours are the geom's ``rgba`` (its material's when it has one).

:meth:`RobotScene.transforms` gives the transform of every body relative to its parent frame
from the body's generalized coordinates ``qpos`` (the plant's state), computed on a scratch
``MjData`` (``mj_kinematics``): the plant's own data is never touched, so observing a run does
not change it.

Messages follow Foxglove's ``foxglove.FrameTransforms`` and ``foxglove.SceneUpdate`` (their
fields as Foxglove names them: a JSON message Foxglove decodes by schema name);
:data:`FRAME_TRANSFORMS_SCHEMA` and :data:`SCENE_UPDATE_SCHEMA` are those schemas' fields that
these messages use, as JSON Schemas.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import mujoco
import numpy as np

__all__ = ["WORLD", "BodyFrame", "Joints", "Primitive", "GeomEntity", "Transform", "RobotScene",
           "robot_scene", "FRAME_TRANSFORMS_SCHEMA", "SCENE_UPDATE_SCHEMA", "stamp",
           "transforms_message", "scene_message"]

WORLD = "world"
"""The root frame of every robot's tree."""

_PLANE_SIZE_M = 10.0
"""The side [m] of a plane MJCF declares infinite (size 0)."""
_PLANE_THICKNESS_M = 0.002
"""A plane is drawn as a cube this thick [m], its top face at the plane."""


@dataclass(frozen=True)
class BodyFrame:
    """One body's frame: ``frame_id`` (``arm/link2``) under ``parent_id`` (``arm/link1`` or
    :data:`WORLD`); ``body`` its index in the model."""

    frame_id: str
    parent_id: str
    body: int
    parent_body: int


@dataclass(frozen=True)
class Primitive:
    """One Foxglove primitive of an entity.

    :param kind: ``cubes``, ``spheres``, ``cylinders`` or ``triangles`` (the entity's field).
    :param position: its centre in the entity's frame [m].
    :param orientation: its orientation ``(x, y, z, w)`` in the entity's frame.
    :param size: its extent along its own axes [m] (a cube's sides, a sphere's or cylinder's
        diameters and height); unused by triangles.
    :param points: a triangle list's vertices [m] (three per triangle).
    """

    kind: str
    position: tuple[float, float, float]
    orientation: tuple[float, float, float, float]
    size: tuple[float, float, float] = (0.0, 0.0, 0.0)
    points: tuple[tuple[float, float, float], ...] = ()


@dataclass(frozen=True)
class GeomEntity:
    """One geom drawn: ``entity_id`` (``arm/forearm``) in frame ``frame_id``, colour ``rgba``
    in [0, 1], its primitives."""

    entity_id: str
    frame_id: str
    rgba: tuple[float, float, float, float]
    primitives: tuple[Primitive, ...]


@dataclass(frozen=True)
class Transform:
    """A child frame's pose in its parent frame: ``translation`` [m] and ``rotation``
    ``(x, y, z, w)``."""

    parent_id: str
    child_id: str
    translation: tuple[float, float, float]
    rotation: tuple[float, float, float, float]


@dataclass(frozen=True)
class Joints:
    """A robot's hinge and slide joints, as ``sensor_msgs/JointState`` lists them: their MJCF
    ``names`` and their indices in ``qpos`` and ``qvel`` (a free or ball joint is a body's
    pose, not a joint state: see :attr:`RobotScene.floating`)."""

    names: tuple[str, ...]
    qpos: tuple[int, ...]
    dof: tuple[int, ...]


@dataclass
class RobotScene:
    """The frames and geometry of one robot's model (see the module docstring).

    :param floating: the frames of bodies on a free joint (the AUV's hull): their pose in
        ``world`` is the robot's pose.
    """

    robot: str
    model: Any
    frames: tuple[BodyFrame, ...]
    entities: tuple[GeomEntity, ...]
    joints: Joints = Joints((), (), ())
    floating: tuple[str, ...] = ()
    _scratch: Any = field(default=None, repr=False)

    def transforms(self, qpos: np.ndarray) -> list[Transform]:
        """Every body's transform in its parent frame for the coordinates ``qpos``."""
        if self._scratch is None:
            self._scratch = mujoco.MjData(self.model)
        data = self._scratch
        data.qpos[:] = qpos
        mujoco.mj_kinematics(self.model, data)
        xpos, xquat = data.xpos, data.xquat
        found = []
        for frame in self.frames:
            parent = frame.parent_body
            translation, rotation = _relative(xpos[parent], xquat[parent], xpos[frame.body],
                                              xquat[frame.body])
            found.append(Transform(frame.parent_id, frame.frame_id, translation, rotation))
        return found


def _xyzw(wxyz: Any) -> tuple[float, float, float, float]:
    w, x, y, z = (float(v) for v in wxyz)
    return (x, y, z, w)


def _relative(parent_pos: np.ndarray, parent_quat: np.ndarray, pos: np.ndarray,
              quat: np.ndarray) -> tuple[tuple[float, float, float],
                                         tuple[float, float, float, float]]:
    """The pose ``(pos, quat)`` (world, MuJoCo's ``wxyz``) in the frame ``(parent_pos,
    parent_quat)``: translation and ``xyzw`` rotation."""
    inverse = np.empty(4)
    mujoco.mju_negQuat(inverse, parent_quat)
    local = np.empty(3)
    mujoco.mju_rotVecQuat(local, pos - parent_pos, inverse)
    rotation = np.empty(4)
    mujoco.mju_mulQuat(rotation, inverse, quat)
    mujoco.mju_normalize4(rotation)
    return (float(local[0]), float(local[1]), float(local[2])), _xyzw(rotation)


def _frame_id(robot: str, model: Any, body: int) -> str:
    if body == 0:
        return WORLD
    name = model.body(body).name or f"body{body}"
    return f"{robot}/{name}"


def _rgba(model: Any, geom: int) -> tuple[float, float, float, float]:
    material = int(model.geom_matid[geom])
    rgba = model.mat_rgba[material] if material >= 0 else model.geom_rgba[geom]
    r, g, b, a = (min(1.0, max(0.0, float(v))) for v in rgba)
    return (r, g, b, a)


def _offset(orientation_wxyz: np.ndarray, along_z_m: float) -> np.ndarray:
    """The vector ``along_z_m`` on the local z axis of ``orientation_wxyz``, in its parent."""
    out = np.empty(3)
    mujoco.mju_rotVecQuat(out, np.array([0.0, 0.0, along_z_m]), orientation_wxyz)
    return out


def _vec(values: Any) -> tuple[float, float, float]:
    x, y, z = (float(v) for v in values)
    return (x, y, z)


def _primitives(model: Any, geom: int) -> tuple[Primitive, ...]:
    kind = int(model.geom_type[geom])
    size = model.geom_size[geom]
    pos, quat = model.geom_pos[geom], model.geom_quat[geom]
    orientation = _xyzw(quat)
    types = mujoco.mjtGeom
    if kind == types.mjGEOM_BOX:
        return (Primitive("cubes", _vec(pos), orientation, _vec(2 * size)),)
    if kind == types.mjGEOM_SPHERE:
        d = 2 * float(size[0])
        return (Primitive("spheres", _vec(pos), orientation, (d, d, d)),)
    if kind == types.mjGEOM_ELLIPSOID:
        return (Primitive("spheres", _vec(pos), orientation, _vec(2 * size)),)
    if kind == types.mjGEOM_CYLINDER:
        d = 2 * float(size[0])
        return (Primitive("cylinders", _vec(pos), orientation, (d, d, 2 * float(size[1]))),)
    if kind == types.mjGEOM_CAPSULE:
        d, half = 2 * float(size[0]), float(size[1])
        ends = [pos + _offset(quat, sign * half) for sign in (-1.0, 1.0)]
        return (Primitive("cylinders", _vec(pos), orientation, (d, d, 2 * half)),
                *(Primitive("spheres", _vec(end), orientation, (d, d, d)) for end in ends))
    if kind == types.mjGEOM_PLANE:
        sx = 2 * float(size[0]) if size[0] > 0 else _PLANE_SIZE_M
        sy = 2 * float(size[1]) if size[1] > 0 else _PLANE_SIZE_M
        below = pos + _offset(quat, -_PLANE_THICKNESS_M / 2)
        return (Primitive("cubes", _vec(below), orientation, (sx, sy, _PLANE_THICKNESS_M)),)
    if kind == types.mjGEOM_MESH:
        return (_mesh(model, int(model.geom_dataid[geom]), pos, orientation),)
    return ()  # a height field: not drawn


def _mesh(model: Any, mesh: int, pos: np.ndarray,
          orientation: tuple[float, float, float, float]) -> Primitive:
    start, count = int(model.mesh_vertadr[mesh]), int(model.mesh_vertnum[mesh])
    vertices = model.mesh_vert[start:start + count]
    face_start, faces = int(model.mesh_faceadr[mesh]), int(model.mesh_facenum[mesh])
    points = tuple(_vec(vertices[index]) for face in model.mesh_face[face_start:face_start + faces]
                   for index in face)
    return Primitive("triangles", _vec(pos), orientation, points=points)


def robot_scene(robot: str, model: Any) -> RobotScene:
    """The frames and geometry of ``robot``'s compiled MuJoCo ``model``."""
    frames = tuple(BodyFrame(_frame_id(robot, model, body),
                             _frame_id(robot, model, int(model.body_parentid[body])), body,
                             int(model.body_parentid[body]))
                   for body in range(1, model.nbody))
    entities = []
    for geom in range(model.ngeom):
        primitives = _primitives(model, geom)
        if primitives:
            name = model.geom(geom).name or f"geom{geom}"
            entities.append(GeomEntity(f"{robot}/{name}",
                                       _frame_id(robot, model, int(model.geom_bodyid[geom])),
                                       _rgba(model, geom), primitives))
    return RobotScene(robot, model, frames, tuple(entities), _joints(model),
                      tuple(_frame_id(robot, model, int(model.jnt_bodyid[j]))
                            for j in range(model.njnt)
                            if int(model.jnt_type[j]) == int(mujoco.mjtJoint.mjJNT_FREE)))


def _joints(model: Any) -> Joints:
    kept = [j for j in range(model.njnt)
            if int(model.jnt_type[j]) in (int(mujoco.mjtJoint.mjJNT_HINGE),
                                          int(mujoco.mjtJoint.mjJNT_SLIDE))]
    return Joints(tuple(model.joint(j).name or f"joint{j}" for j in kept),
                  tuple(int(model.jnt_qposadr[j]) for j in kept),
                  tuple(int(model.jnt_dofadr[j]) for j in kept))


# -- messages ---------------------------------------------------------------------------------

def stamp(time_ns: int) -> dict[str, int]:
    """Foxglove's ``time``: ``{"sec", "nsec"}``."""
    return {"sec": time_ns // 1_000_000_000, "nsec": time_ns % 1_000_000_000}


def _xyz(values: tuple[float, ...]) -> dict[str, float]:
    return dict(zip("xyz", values))


def _quaternion(values: tuple[float, ...]) -> dict[str, float]:
    return dict(zip("xyzw", values))


def transforms_message(time_ns: int, transforms: list[Transform]) -> dict[str, Any]:
    """A ``foxglove.FrameTransforms`` message."""
    when = stamp(time_ns)
    return {"transforms": [{"timestamp": when, "parent_frame_id": t.parent_id,
                            "child_frame_id": t.child_id, "translation": _xyz(t.translation),
                            "rotation": _quaternion(t.rotation)} for t in transforms]}


def _primitive(primitive: Primitive, color: dict[str, float]) -> dict[str, Any]:
    pose = {"position": _xyz(primitive.position),
            "orientation": _quaternion(primitive.orientation)}
    if primitive.kind == "triangles":
        return {"pose": pose, "points": [_xyz(p) for p in primitive.points], "color": color,
                "colors": [], "indices": []}
    found = {"pose": pose, "size": _xyz(primitive.size), "color": color}
    if primitive.kind == "cylinders":
        found.update(bottom_scale=1.0, top_scale=1.0)
    return found


def scene_message(time_ns: int, scenes: list[RobotScene]) -> dict[str, Any]:
    """A ``foxglove.SceneUpdate`` adding every geom of ``scenes``, each following its frame
    (``frame_locked``) for as long as the scene is shown (lifetime zero)."""
    when = stamp(time_ns)
    entities = []
    for scene in scenes:
        for entity in scene.entities:
            color = dict(zip("rgba", entity.rgba))
            found: dict[str, Any] = {
                "timestamp": when, "frame_id": entity.frame_id, "id": entity.entity_id,
                "lifetime": {"sec": 0, "nsec": 0}, "frame_locked": True,
                "metadata": [{"key": "robot", "value": scene.robot}],
                "arrows": [], "cubes": [], "spheres": [], "cylinders": [], "lines": [],
                "triangles": [], "texts": [], "models": []}
            for primitive in entity.primitives:
                found[primitive.kind].append(_primitive(primitive, color))
            entities.append(found)
    return {"deletions": [], "entities": entities}


# -- schemas ----------------------------------------------------------------------------------

_NUMBER = {"type": "number"}
_STRING = {"type": "string"}
_TIME = {"type": "object", "title": "time",
         "properties": {"sec": {"type": "integer", "minimum": 0},
                        "nsec": {"type": "integer", "minimum": 0, "maximum": 999_999_999}},
         "required": ["sec", "nsec"]}
_DURATION = {"type": "object", "title": "duration",
             "properties": {"sec": {"type": "integer"},
                            "nsec": {"type": "integer", "minimum": 0, "maximum": 999_999_999}},
             "required": ["sec", "nsec"]}


def _object(title: str, fields: dict[str, Any]) -> dict[str, Any]:
    return {"title": title, "type": "object", "properties": fields, "required": list(fields)}


def _array(items: dict[str, Any]) -> dict[str, Any]:
    return {"type": "array", "items": items}


_VECTOR3 = _object("foxglove.Vector3", {"x": _NUMBER, "y": _NUMBER, "z": _NUMBER})
_QUATERNION = _object("foxglove.Quaternion", {"x": _NUMBER, "y": _NUMBER, "z": _NUMBER,
                                              "w": _NUMBER})
_POSE = _object("foxglove.Pose", {"position": _VECTOR3, "orientation": _QUATERNION})
_COLOR = _object("foxglove.Color", {"r": _NUMBER, "g": _NUMBER, "b": _NUMBER, "a": _NUMBER})
_SHAPE = {"pose": _POSE, "size": _VECTOR3, "color": _COLOR}
_TRIANGLES = _object("foxglove.TriangleListPrimitive", {
    "pose": _POSE, "points": _array(_VECTOR3), "color": _COLOR, "colors": _array(_COLOR),
    "indices": _array({"type": "integer", "minimum": 0})})

FRAME_TRANSFORMS_SCHEMA = _object("foxglove.FrameTransforms", {
    "transforms": _array(_object("foxglove.FrameTransform", {
        "timestamp": _TIME, "parent_frame_id": _STRING, "child_frame_id": _STRING,
        "translation": _VECTOR3, "rotation": _QUATERNION}))})
"""Foxglove's ``foxglove.FrameTransforms``, as a JSON Schema."""

_EMPTY = {"type": "array", "maxItems": 0}
"""A primitive list these scenes never fill (arrows, lines, texts, models)."""

SCENE_UPDATE_SCHEMA = _object("foxglove.SceneUpdate", {
    "deletions": _array(_object("foxglove.SceneEntityDeletion", {
        "timestamp": _TIME, "type": {"type": "integer", "minimum": 0, "maximum": 1},
        "id": _STRING})),
    "entities": _array(_object("foxglove.SceneEntity", {
        "timestamp": _TIME, "frame_id": _STRING, "id": _STRING, "lifetime": _DURATION,
        "frame_locked": {"type": "boolean"},
        "metadata": _array(_object("foxglove.KeyValuePair", {"key": _STRING,
                                                              "value": _STRING})),
        "arrows": _EMPTY,
        "cubes": _array(_object("foxglove.CubePrimitive", _SHAPE)),
        "spheres": _array(_object("foxglove.SpherePrimitive", _SHAPE)),
        "cylinders": _array(_object("foxglove.CylinderPrimitive", {
            **_SHAPE, "bottom_scale": _NUMBER, "top_scale": _NUMBER})),
        "lines": _EMPTY, "triangles": _array(_TRIANGLES), "texts": _EMPTY,
        "models": _EMPTY}))})
"""Foxglove's ``foxglove.SceneUpdate`` (the fields these scenes use), as a JSON Schema."""
