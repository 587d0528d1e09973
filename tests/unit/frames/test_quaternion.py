"""Quaternions (scalar first, body -> frame) against analytic rotations and scipy.

Independent references:
* analytic: a right-handed rotation by 90 deg about z takes x to y, y to -x
  (any textbook, e.g. Kuipers, *Quaternions and Rotation Sequences*, 1999);
  by 120 deg about (1, 1, 1) it permutes the axes x -> y -> z -> x.
* peer library, used only here: ``scipy.spatial.transform.Rotation`` (scalar-
  last quaternions, active rotation matrices).
"""

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from rocketsim.frames.quaternion import (
    quat_conjugate,
    quat_from_axis_angle,
    quat_from_matrix,
    quat_multiply,
    quat_normalize,
    quat_rotate,
    quat_to_matrix,
)


def _random_quats(n, seed):
    rng = np.random.default_rng(seed)
    q = rng.normal(size=(n, 4))
    return q / np.linalg.norm(q, axis=1)[:, None]


def _scipy(q):
    """scipy Rotation of our scalar-first quaternion."""
    return Rotation.from_quat([q[1], q[2], q[3], q[0]])


def test_quarter_turn_about_z():
    q = quat_from_axis_angle(np.array([0.0, 0.0, 1.0]), math.pi / 2)
    np.testing.assert_allclose(quat_rotate(q, np.array([1.0, 0.0, 0.0])), [0.0, 1.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(quat_rotate(q, np.array([0.0, 1.0, 0.0])), [-1.0, 0.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(quat_rotate(q, np.array([0.0, 0.0, 2.5])), [0.0, 0.0, 2.5], atol=1e-15)
    # (cos 45 deg, 0, 0, sin 45 deg)
    np.testing.assert_allclose(q, [math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5)], atol=1e-16)


def test_third_turn_about_diagonal_permutes_axes():
    q = quat_from_axis_angle(np.array([1.0, 1.0, 1.0]), 2.0 * math.pi / 3.0)  # axis not unit on purpose
    np.testing.assert_allclose(quat_to_matrix(q), [[0, 0, 1], [1, 0, 0], [0, 1, 0]], atol=1e-15)
    np.testing.assert_allclose(quat_rotate(q, np.array([0.0, 0.0, 1.0])), [1.0, 0.0, 0.0], atol=1e-15)


def test_against_scipy_rotation():
    for q in _random_quats(50, seed=1):
        np.testing.assert_allclose(quat_to_matrix(q), _scipy(q).as_matrix(), atol=1e-15)
        v = np.array([0.3, -1.7, 2.2])
        np.testing.assert_allclose(quat_rotate(q, v), _scipy(q).apply(v), atol=1e-14)
    axis, angle = np.array([0.2, -0.5, 0.8]), 1.234
    expected = Rotation.from_rotvec(axis / np.linalg.norm(axis) * angle).as_quat()   # x y z w
    np.testing.assert_allclose(quat_from_axis_angle(axis, angle), np.roll(expected, 1), atol=1e-15)


def test_rotate_equals_sandwich_product():
    # v' = q (0, v) q*  (Hamilton product)
    v = np.array([1.5, -0.25, 4.0])
    for q in _random_quats(20, seed=2):
        sandwich = quat_multiply(quat_multiply(q, np.array([0.0, *v])), quat_conjugate(q))
        assert abs(sandwich[0]) < 1e-14
        np.testing.assert_allclose(quat_rotate(q, v), sandwich[1:], atol=1e-14)


def test_matrix_round_trip_every_branch_of_shepperd():
    # Rotations by nearly pi about each axis exercise the three non-trace
    # branches; small rotations the trace branch.
    cases = list(_random_quats(200, seed=3))
    for axis in np.eye(3):
        for angle in (1e-9, 0.5, math.pi - 1e-9, math.pi):
            cases.append(quat_from_axis_angle(axis, angle))
    for q in cases:
        q = q if q[0] >= 0 else -q
        back = quat_from_matrix(quat_to_matrix(q))
        assert back[0] >= 0.0
        np.testing.assert_allclose(quat_to_matrix(back), quat_to_matrix(q), atol=2e-15)
        if q[0] > 1e-8:          # at w = 0 both signs are the same rotation
            np.testing.assert_allclose(back, q, atol=2e-15)


def test_from_matrix_matches_scipy():
    for q in _random_quats(50, seed=4):
        m = _scipy(q).as_matrix()
        ref = np.roll(Rotation.from_matrix(m).as_quat(), 1)
        ref = ref if ref[0] >= 0 else -ref
        np.testing.assert_allclose(quat_from_matrix(m), ref, atol=1e-14)


def test_composition_is_matrix_product():
    qs = _random_quats(40, seed=5)
    for a, b in zip(qs[::2], qs[1::2]):
        np.testing.assert_allclose(quat_to_matrix(quat_multiply(a, b)),
                                   quat_to_matrix(a) @ quat_to_matrix(b), atol=1e-15)
        # and it agrees with scipy's composition (a * b applies b first)
        np.testing.assert_allclose(quat_to_matrix(quat_multiply(a, b)),
                                   (_scipy(a) * _scipy(b)).as_matrix(), atol=1e-15)


def test_norm_preserved_and_conjugate_inverts():
    rng = np.random.default_rng(6)
    for q in _random_quats(50, seed=7):
        v = rng.normal(size=3)
        w = quat_rotate(q, v)
        assert np.linalg.norm(w) == pytest.approx(np.linalg.norm(v), rel=1e-15)
        np.testing.assert_allclose(quat_rotate(quat_conjugate(q), w), v, atol=1e-14)
        p = quat_multiply(q, quat_multiply(q, q))
        assert np.linalg.norm(p) == pytest.approx(1.0, abs=1e-15)
        np.testing.assert_allclose(quat_multiply(q, quat_conjugate(q)), [1, 0, 0, 0], atol=1e-15)


def test_normalize():
    np.testing.assert_allclose(quat_normalize(np.array([2.0, 0.0, 0.0, 0.0])), [1, 0, 0, 0])
    q = quat_normalize(np.array([1.0, 2.0, -2.0, 4.0]))
    np.testing.assert_allclose(q, np.array([1.0, 2.0, -2.0, 4.0]) / 5.0, rtol=1e-15)
