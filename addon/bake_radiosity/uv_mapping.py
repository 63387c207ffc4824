"""The Mapping node between a UV map and an Image Texture, as Cycles applies it
(intern/cycles/kernel/svm/mapping_util.h, svm_mapping): a 3D affine transform of the texture
coordinate (u, v, 0), of which a Flat Image Texture reads x and y.

Point: R (S p) + L. Texture: S^-1 R^T (p - L) (a zero scale gives 0 there). Vector: R (S p).
Normal normalizes its result, which is not affine, and is not followed. R is Cycles'
euler_to_transform of the Rotation (X, then Y, then Z about the fixed axes)."""

import math

import numpy as np

IDENTITY = np.eye(4)


def rotation(euler):
    """Cycles' euler_to_transform: Rz Ry Rx."""
    cx, cy, cz = (math.cos(a) for a in euler)
    sx, sy, sz = (math.sin(a) for a in euler)
    return np.array([[cy * cz, sy * sx * cz - cx * sz, sy * cx * cz + sx * sz],
                     [cy * sz, sy * sx * sz + cx * cz, sy * cx * sz - sx * cz],
                     [-sy, cy * sx, cy * cx]])


def matrix(vector_type, location, euler, scale):
    """The (4, 4) affine matrix of a Mapping node of `vector_type` with these input values, or None
    for a type that is not affine (Normal)."""
    r, s, t = rotation(euler), np.asarray(scale, dtype=np.float64), np.asarray(location, dtype=np.float64)
    m = np.eye(4)
    if vector_type in {"POINT", "VECTOR"}:
        m[:3, :3] = r * s[None, :]
        if vector_type == "POINT":
            m[:3, 3] = t
    elif vector_type == "TEXTURE":
        inverse_scale = np.divide(1.0, s, out=np.zeros(3), where=s != 0.0)
        m[:3, :3] = inverse_scale[:, None] * r.T
        m[:3, 3] = -m[:3, :3] @ t
    else:
        return None
    return m


def node_matrix(node, value_of):
    """The matrix of Mapping `node`, or (None, why not). `value_of(socket)` is the value of an
    input socket nothing drives, or None when nodes drive it."""
    if node.vector_type not in {"POINT", "TEXTURE", "VECTOR"}:
        return None, "Mapping '%s' is of type %s" % (node.name, node.vector_type.title())
    names = ("Location", "Rotation", "Scale") if node.vector_type != "VECTOR" else ("Rotation", "Scale")
    values = {"Location": (0.0, 0.0, 0.0)}
    for name in names:
        values[name] = value_of(node.inputs[name])
        if values[name] is None:
            return None, "the %s of Mapping '%s' is driven by nodes" % (name, node.name)
    return matrix(node.vector_type, values["Location"], values["Rotation"], values["Scale"]), ""


def uv_transform(m):
    """The (2, 3) affine map of (u, v, 1) to the (x, y) a Flat Image Texture reads, from the 3D
    matrix `m` applied to (u, v, 0)."""
    return m[:2, [0, 1, 3]]


def apply(transform, uv):
    """(corners, 2) UVs through a (2, 3) transform, as float32."""
    return (uv.astype(np.float64) @ transform[:, :2].T + transform[:, 2]).astype(np.float32)
