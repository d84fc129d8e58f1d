"""The Blender add-on's quaternion arithmetic (engine/blender/gmg_blender/rotations.py), which needs
no Blender: checked against rotation matrices written out here, and against Blender's own
conventions (Euler order 'XYZ' turns about X first; axis-angle is (angle, x, y, z))."""
import importlib.util
import math
from pathlib import Path

import numpy as np

_path = Path(__file__).resolve().parents[2] / "engine" / "blender" / "gmg_blender" / "rotations.py"
_spec = importlib.util.spec_from_file_location("gmg_blender_rotations", _path)
rot = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(rot)


def rx(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def ry(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def matrix(q):
    """The rotation matrix of a unit quaternion (w, x, y, z), written out."""
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def test_y_up_turns_into_z_up_and_back():
    np.testing.assert_allclose(rot.rotate(rot.Y_UP_TO_Z_UP, [1.0, 2.0, 3.0]), [1.0, -3.0, 2.0], atol=1e-15)
    np.testing.assert_allclose(rot.rotate(rot.Z_UP_TO_Y_UP, [1.0, -3.0, 2.0]), [1.0, 2.0, 3.0], atol=1e-15)
    np.testing.assert_allclose(matrix(rot.Y_UP_TO_Z_UP), rx(math.pi / 2), atol=1e-15)


def test_product_applies_the_right_factor_first():
    a = np.array([math.cos(0.3), math.sin(0.3), 0, 0])  # 0.6 rad about X
    b = np.array([math.cos(0.4), 0, 0, math.sin(0.4)])  # 0.8 rad about Z
    np.testing.assert_allclose(matrix(rot.multiply(a, b)), rx(0.6) @ rz(0.8), atol=1e-15)
    v = np.array([0.2, -1.0, 0.5])
    np.testing.assert_allclose(rot.rotate(rot.multiply(a, b), v), rx(0.6) @ rz(0.8) @ v, atol=1e-15)
    np.testing.assert_allclose(rot.multiply(a, rot.conjugate(a)), [1, 0, 0, 0], atol=1e-15)


def test_euler_orders_as_blender_names_them():
    e = np.array([0.3, -0.7, 1.1])
    np.testing.assert_allclose(matrix(rot.from_euler(e, "XYZ")), rz(1.1) @ ry(-0.7) @ rx(0.3), atol=1e-14)
    np.testing.assert_allclose(matrix(rot.from_euler(e, "ZXY")), ry(-0.7) @ rx(0.3) @ rz(1.1), atol=1e-14)
    many = rot.from_euler(np.tile(e, (4, 2, 1)), "YZX")
    assert many.shape == (4, 2, 4)
    np.testing.assert_allclose(matrix(many[3, 1]), rx(0.3) @ rz(1.1) @ ry(-0.7), atol=1e-14)


def test_axis_angle_and_its_zero_axis():
    q = rot.from_axis_angle([0.9, 0.0, 0.0, 2.0])  # the axis need not have length 1
    np.testing.assert_allclose(matrix(q), rz(0.9), atol=1e-15)
    np.testing.assert_allclose(rot.from_axis_angle([0.0, 0.0, 0.0, 0.0]), [1, 0, 0, 0], atol=0)


def test_normalized_and_the_zero_quaternion():
    np.testing.assert_allclose(rot.normalized([[2.0, 0, 0, 0], [0, 3.0, 4.0, 0], [0, 0, 0, 0]]),
                               [[1, 0, 0, 0], [0, 0.6, 0.8, 0], [1, 0, 0, 0]], atol=1e-15)


def test_continuous_signs_follow_the_frame_before():
    q = np.array([[[1.0, 0, 0, 0]], [[-1.0, 0, 0, 0]], [[-0.8, -0.6, 0, 0]], [[0.6, 0.8, 0, 0]]])
    out = rot.continuous(q)
    np.testing.assert_array_equal(out[:, 0, 0], [1.0, 1.0, 0.8, 0.6])
    np.testing.assert_array_equal(out[:, 0, 1], [0.0, 0.0, 0.6, 0.8])
    np.testing.assert_array_equal(q[1, 0], [-1.0, 0, 0, 0])  # the input is not changed
