"""Quaternion arithmetic on NumPy arrays, and the turn between gmg's Y-up and Blender's Z-up.

Quaternions are (w, x, y, z), as gmg.Motion.rotations and Blender's rotation_quaternion hold
them. No bpy here: these are the add-on's arithmetic, testable without Blender.
"""
import math

import numpy as np

# Blender is Z-up; gmg's motions are Y-up. A quarter turn about +X takes Y-up to Z-up: (x, y, z)
# becomes (x, -z, y). Rotating the root by it turns a whole Y-up motion into a Z-up one.
Y_UP_TO_Z_UP = np.array([math.cos(math.pi / 4), math.sin(math.pi / 4), 0.0, 0.0])
Z_UP_TO_Y_UP = np.array([Y_UP_TO_Z_UP[0], -Y_UP_TO_Z_UP[1], 0.0, 0.0])


def multiply(a, b):
    """The product a * b (b applied first), broadcast over leading axes."""
    a = np.asarray(a, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    aw, ax, ay, az = a[..., 0], a[..., 1], a[..., 2], a[..., 3]
    bw, bx, by, bz = b[..., 0], b[..., 1], b[..., 2], b[..., 3]
    return np.stack([aw * bw - ax * bx - ay * by - az * bz,
                     aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx,
                     aw * bz + ax * by - ay * bx + az * bw], axis=-1)


def conjugate(q):
    """The inverse of unit quaternions."""
    q = np.asarray(q, dtype=np.float64)
    return q * np.array([1.0, -1.0, -1.0, -1.0])


def rotate(q, v):
    """Vectors v (..., 3) turned by unit quaternions q (..., 4)."""
    v = np.asarray(v, dtype=np.float64)
    p = np.concatenate([np.zeros(v.shape[:-1] + (1,)), v], axis=-1)
    return multiply(multiply(q, p), conjugate(q))[..., 1:]


def normalized(q):
    """Quaternions scaled to length 1; a zero one becomes the identity (Blender's reading of it)."""
    q = np.asarray(q, dtype=np.float64)
    n = np.linalg.norm(q, axis=-1, keepdims=True)
    out = np.where(n > 1e-12, q / np.where(n > 1e-12, n, 1.0), 0.0)
    out[..., 0] = np.where(n[..., 0] > 1e-12, out[..., 0], 1.0)
    return out


def continuous(q):
    """The same rotations with each frame's sign chosen nearest the frame before (axis 0 is time),
    so that keys interpolated between frames never swing the long way round."""
    q = np.array(q, dtype=np.float64)
    if len(q) < 2:
        return q
    flips = np.sum(q[1:] * q[:-1], axis=-1) < 0
    sign = np.cumprod(np.where(flips, -1.0, 1.0), axis=0)
    q[1:] *= sign[..., None]
    return q


_AXES = {"X": 0, "Y": 1, "Z": 2}


def from_euler(angles, order):
    """Blender's Euler angles (..., 3) in radians, order as rotation_mode names it ('XYZ': X turns
    first, then Y, then Z), as quaternions."""
    angles = np.asarray(angles, dtype=np.float64)
    q = np.zeros(angles.shape[:-1] + (4,))
    q[..., 0] = 1.0
    for axis in order:
        k = _AXES[axis]
        half = angles[..., k] / 2
        step = np.zeros_like(q)
        step[..., 0] = np.cos(half)
        step[..., 1 + k] = np.sin(half)
        q = multiply(step, q)
    return q


def from_axis_angle(values):
    """Blender's rotation_axis_angle (angle, x, y, z) (..., 4) as quaternions."""
    values = np.asarray(values, dtype=np.float64)
    axis = values[..., 1:]
    n = np.linalg.norm(axis, axis=-1, keepdims=True)
    axis = np.where(n > 1e-12, axis / np.where(n > 1e-12, n, 1.0), np.array([0.0, 1.0, 0.0]))
    half = values[..., :1] / 2
    return np.concatenate([np.cos(half), axis * np.sin(half)], axis=-1)
