"""The fcl geometry of SAPIEN bodies: their physx collision shapes (boxes, spheres, capsules,
cylinders, convex and triangle meshes; planes such as the floor are left out) converted once
per episode, for the robot's links and the scene's actors alike."""

from __future__ import annotations

from collections.abc import Iterable

import fcl
import numpy as np
import sapien
import sapien.physx as physx

#: SAPIEN's capsules and cylinders run along local x, fcl's along local z.
_X_TO_Z = sapien.Pose(q=[np.sqrt(0.5), 0.0, np.sqrt(0.5), 0.0])

#: A body's collision geometry: each fcl geometry with its pose (4x4) in the body's frame.
Geometry = list[tuple[fcl.CollisionGeometry, np.ndarray]]


def shape_geometry(shape: physx.PhysxCollisionShape) -> tuple[fcl.CollisionGeometry, sapien.Pose]:
    """The fcl geometry of a SAPIEN collision shape and its pose in the body frame."""
    local = shape.get_local_pose()
    if isinstance(shape, physx.PhysxCollisionShapeBox):
        return fcl.Box(*(2.0 * np.asarray(shape.half_size))), local
    if isinstance(shape, physx.PhysxCollisionShapeSphere):
        return fcl.Sphere(shape.radius), local
    if isinstance(shape, physx.PhysxCollisionShapeCapsule):
        return fcl.Capsule(shape.radius, 2.0 * shape.half_length), local * _X_TO_Z
    if isinstance(shape, physx.PhysxCollisionShapeCylinder):
        return fcl.Cylinder(shape.radius, 2.0 * shape.half_length), local * _X_TO_Z
    if isinstance(
        shape, physx.PhysxCollisionShapeConvexMesh | physx.PhysxCollisionShapeTriangleMesh
    ):
        verts = np.asarray(shape.get_vertices(), dtype=float) * np.asarray(shape.get_scale())
        tris = np.asarray(shape.get_triangles(), dtype=np.int64)
        if isinstance(shape, physx.PhysxCollisionShapeTriangleMesh):
            mesh = fcl.BVHModel()
            mesh.beginModel(len(verts), len(tris))
            mesh.addSubModel(verts, tris)
            mesh.endModel()
            return mesh, local
        faces = np.hstack([np.full((len(tris), 1), 3), tris]).ravel()
        return fcl.Convex(verts, len(tris), faces), local
    raise TypeError(f"unsupported collision shape {type(shape).__name__}")


def body_geometry(shapes: Iterable[physx.PhysxCollisionShape]) -> Geometry:
    """The fcl geometry of a body's collision ``shapes`` (planes left out)."""
    out = []
    for shape in shapes:
        if isinstance(shape, physx.PhysxCollisionShapePlane):
            continue
        geom, local = shape_geometry(shape)
        out.append((geom, local.to_transformation_matrix()))
    return out
