"""Forward kinematics (issue 45): position, rotation and jacobian of a
model's places (bodies, particles, frames and points), against values got
apart from the generated velocities:

- closed forms read off the specs' text (the pendulum's bob, the URDF
  arm's first joint);
- the Jacobian's columns against Richardson-extrapolated central
  differences of position and rotation (error O(h^4)): along each
  coordinate where the speeds are the coordinates' rates, and along the
  motion itself where a unit quaternion has speeds (its exponential map,
  exact on the sphere);
- each rotation orthonormal, of determinant 1.
"""

import os

import numpy as np
import pytest

import eomc
from conftest import SOURCE
from test_functions import loaded, random_state

# every shipped spec with a place (gear_link, arenstorf and cartpole have
# none: their energies are written as terms), the imported models, and a
# free top turned by a quaternion with speeds
MODELS = ["falling_particle.yaml", "pendulum.yaml", "double_pendulum.yaml",
          "chain5.yaml", "kepler.yaml", "swing.yaml", "spinning_hoop.yaml",
          "cartesian_pendulum.yaml", "appell.yaml", "chaplygin_sleigh.yaml",
          "rolling_disk.yaml", "bicycle_tree.yaml", "precession.yaml", "bouncing_ball.yaml",
          "central_constant_speed.yaml", "arm.urdf", "floating_base.xml", "free_top"]
STATES = 10
H = 1e-3
# Richardson's O(h^4) at h = 1e-3 on values and derivatives of order 1,
# with rounding of 1e-16 over h: 6.4e-13 at worst here (the floating base);
# a wrong column is off by O(1)
TOL = 1e-11


def load(name):
    if name == "free_top":
        return eomc.load(os.path.join(SOURCE, "tests", "sim", "specs", "free_top.yaml"))
    return loaded(name)


def vee(W):
    """The vector w of a skew matrix W = [w]x (its antisymmetric part)."""
    return 0.5 * np.array([W[2, 1] - W[1, 2], W[0, 2] - W[2, 0], W[1, 0] - W[0, 1]])


def quat_mul(a, b):
    return np.array([a[0] * b[0] - a[1:] @ b[1:],
                     *(a[0] * b[1:] + b[0] * a[1:] + np.cross(a[1:], b[1:]))])


def motion(m):
    """A map (q, v, s) -> q(s): the coordinates moved for a time s at the
    speeds v, exactly where each rate is constant (a coordinate's rate is
    its speed, named q'; a unit quaternion's three speeds w, its angular
    velocity in its own axes, turn it by e (x) exp(s w / 2))."""
    names, speeds = m.coordinates, m.speeds
    plan, i, own = [], 0, [j for j, v in enumerate(speeds) if not v.endswith("'")]
    while i < len(names):
        if names[i] + "'" in speeds:
            plan.append((i, speeds.index(names[i] + "'")))
            i += 1
        else:  # a quaternion's four, its speeds the next three of their own
            plan.append((i, tuple(own[:3])))
            own = own[3:]
            i += 4

    def at(q, v, s):
        q = q.copy()
        for i, j in plan:
            if isinstance(j, tuple):
                w = v[list(j)]
                a = np.linalg.norm(w) * s / 2
                if a == 0:
                    continue
                turn = np.array([np.cos(a), *(np.sin(a) * w / np.linalg.norm(w))])
                q[i:i + 4] = quat_mul(q[i:i + 4], turn)
            else:
                q[i] += s * v[j]
        return q
    return at


def rate(f, h=H):
    """f'(0) by central differences at h and h/2, extrapolated."""
    def c(s):
        return (f(s) - f(-s)) / (2 * s)
    return (4 * c(h / 2) - c(h)) / 3


@pytest.mark.parametrize("name", MODELS)
def test_jacobian_is_the_rate_of_position_and_rotation(name):
    """J v against the rates of position and of rotation (w from R' R^T)
    along motions at unit speeds, one speed at a time, and, where a
    quaternion has speeds, at random speeds along its exponential map."""
    m = load(name)
    rng = np.random.default_rng(45)
    at, nv = motion(m), len(m.speeds)
    assert m.places, "every model here has a place"
    worst = 0.0
    for _ in range(STATES):
        q = random_state(m, rng)[0]
        if name == "free_top":
            q /= np.linalg.norm(q)
        vs = [np.eye(nv)[j] for j in range(nv)] + [rng.uniform(-1, 1, nv)]
        for place in m.places:
            J = m.jacobian(place, q)
            scale = max(1.0, np.abs(J).max())
            for v in vs:
                dp = rate(lambda s: m.position(place, at(q, v, s)))
                worst = max(worst, np.abs(J[:3] @ v - dp).max() / scale)
                if J.shape[0] == 6:
                    R = m.rotation(place, q)
                    w = vee(rate(lambda s: m.rotation(place, at(q, v, s))) @ R.T)
                    worst = max(worst, np.abs(J[3:] @ v - w).max() / scale)
    assert worst <= TOL, worst


@pytest.mark.parametrize("name", MODELS)
def test_rotations_are_rotations(name):
    m = load(name)
    rng = np.random.default_rng(7)
    for _ in range(STATES):
        q = random_state(m, rng)[0]
        if name == "free_top":
            q /= np.linalg.norm(q)
        for place in m.places:
            if m.jacobian(place, q).shape[0] == 6:
                R = m.rotation(place, q)
                assert np.abs(R.T @ R - np.eye(3)).max() <= 1e-14
                assert abs(np.linalg.det(R) - 1) <= 1e-14


def test_pendulum_bob_in_closed_form():
    """specs/pendulum.yaml: the bob at (l sin th, -l cos th), moving at
    (l cos th, l sin th) th'."""
    m = loaded("pendulum.yaml")
    m.set(l=1.7)
    for th in (-2.0, 0.3, 1.1):
        q = np.array([th])
        np.testing.assert_allclose(m.position("bob", q), [1.7 * np.sin(th), -1.7 * np.cos(th), 0],
                                   rtol=0, atol=1e-15)
        np.testing.assert_allclose(m.jacobian("bob", q)[:, 0],
                                   [1.7 * np.cos(th), 1.7 * np.sin(th), 0], rtol=0, atol=1e-15)


def test_arm_first_joint_in_closed_form():
    """specs/arm.urdf: the base joint turns about z at 0.1 above the world's
    origin, so its frame is Rz(yaw) and the upper arm's origin, 0.1 above
    the turret's, is at (0, 0, 0.2) whatever the joints; a yaw rate turns
    every link about z."""
    m = loaded("arm.urdf")
    q = np.array([0.7, -0.4, 1.2])
    c, s = np.cos(0.7), np.sin(0.7)
    np.testing.assert_allclose(m.rotation("base_yaw_axes", q),
                               [[c, -s, 0], [s, c, 0], [0, 0, 1]], rtol=0, atol=1e-15)
    np.testing.assert_allclose(m.position("upper_arm_origin", q), [0, 0, 0.2], rtol=0,
                               atol=1e-15)
    J = m.jacobian("forearm", q)
    np.testing.assert_allclose(J[3:, 0], [0, 0, 1], rtol=0, atol=1e-15)
    # the forearm's centre moves about the z axis at yaw rate 1: z x r
    r = m.position("forearm", q)
    np.testing.assert_allclose(J[:3, 0], np.cross([0, 0, 1], r), rtol=0, atol=1e-15)


def test_places_say_what_they_cannot_give():
    m = loaded("pendulum.yaml")
    assert m.places == ["bob"]
    with pytest.raises(eomc.UsageError, match=r"no place 'bbo' \(did you mean 'bob'\?\)"):
        m.position("bbo", [0.0])
    with pytest.raises(eomc.UsageError, match=r"'bob' is a particle: .* no axes"):
        m.rotation("bob", [0.0])
    with pytest.raises(eomc.UsageError, match=r"q needs 1 entries \(theta\)"):
        m.jacobian("bob", [0.0, 1.0])
    assert m.jacobian("bob", [0.0]).shape == (3, 1)
    g = loaded("gear_link.yaml")
    with pytest.raises(eomc.UsageError, match=r"no place 'link' \(its places: .*: none\)"):
        g.position("link", [0.0])
