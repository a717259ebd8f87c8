"""The functions of a model (issue 45): mass, bias, inverse dynamics and
the derivatives of the accelerations, against values got apart from them:

- the round trip: inverse(q, v, accel(q, v, u), u) is 0 at random states
  (accel is the model's own solve, its unrolled LDL^T or its recursion, not
  M and h), and with the inputs left at 0 it is the inputs' generalized
  force, read off each spec's text;
- accel_derivatives against central differences of the accelerations
  solved in extended precision (accel(extended=True)), by Richardson's
  extrapolation of two steps (error O(h^4)), MuJoCo's humanoid among the
  models (its M solved along its tree).
"""

import os

import numpy as np
import pytest

import eomc
from conftest import spec

# the unconstrained shipped models, and the imported ones
UNCONSTRAINED = ["falling_particle.yaml", "pendulum.yaml", "gear_link.yaml",
                 "double_pendulum.yaml", "chain5.yaml", "kepler.yaml", "arenstorf.yaml",
                 "swing.yaml", "spinning_hoop.yaml", "cartpole.yaml", "arm.urdf",
                 "floating_base.xml"]
STATES = 100


def can_import():
    import subprocess
    import eomc._build
    return subprocess.run([eomc._build.compiler(), "import", spec("arm.urdf")],
                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode == 0


# MuJoCo's humanoid (libmujoco-samples): M along a tree (its free base a
# chain by the fill-in), so accel_derivatives solves every column at once
# by LTDL (la_ltdl_solve_cols_neg), where the small models solve densely
HUMANOID = "/usr/share/mujoco/model/humanoid/humanoid.xml"


def loaded(name):
    if name.endswith((".xml", ".urdf")) and not can_import():
        pytest.skip("eomc cannot import MJCF or URDF here")
    if name == "humanoid.xml":
        if not os.path.exists(HUMANOID):
            pytest.skip("no %s (libmujoco-samples)" % HUMANOID)
        # its smooth effects (contact and limits switch), with the twin
        # the differences need
        return eomc.load(HUMANOID, effects=["gravity", "damping", "stiffness", "armature",
                                            "actuators"], extended=True)
    return eomc.load(spec(name), joint_inputs=name.endswith(".xml") or None)


def random_state(m, rng):
    """q, v, u uniform in [-1, 1], each unit quaternion (four coordinates
    named _qw .. _qz) normalized; kepler's and arenstorf's bodies and the
    rolling disk's lean kept off their singularities (where the
    accelerations' derivatives grow past what differences resolve)."""
    q = rng.uniform(-1, 1, len(m.coordinates))
    names = m.coordinates
    for i, c in enumerate(names):
        if c.endswith("_qw"):
            q[i:i + 4] /= np.linalg.norm(q[i:i + 4])
    if m.name in ("kepler", "arenstorf"):
        q[:2] = 0.5 + 0.5 * np.abs(q[:2])
    if m.name == "rolling_disk":  # its equations are singular at theta = 0
        k = m.coordinates.index("theta")
        q[k] = np.copysign(0.1 + 0.9 * abs(q[k]), q[k])
    return q, rng.uniform(-1, 1, len(m.speeds)), rng.uniform(-1, 1, len(m.inputs))


@pytest.mark.parametrize("name", UNCONSTRAINED)
def test_inverse_of_accel_is_zero(name):
    m = loaded(name)
    rng = np.random.default_rng(45)
    worst = 0.0
    for _ in range(STATES):
        q, v, u = random_state(m, rng)
        a = m.accel(q, v, u if len(u) else None)
        M, h = m.mass(q), m.bias(q, v, u if len(u) else None)
        tau = m.inverse(q, v, a, u if len(u) else None)
        scale = max(np.abs(M @ a).max(), np.abs(h).max())
        worst = max(worst, np.abs(tau).max() / scale)
    assert worst <= 1e-13, worst


@pytest.mark.parametrize("name, force", [
    ("cartpole.yaml", lambda m, u: np.array([u[0], 0.0])),           # F on the cart
    ("gear_link.yaml", lambda m, u: np.array([m.params["r"] * u[0]])),  # r u on the link
    ("arm.urdf", lambda m, u: u),                                     # tau_J on each joint
])
def test_inverse_with_the_inputs_at_zero_is_their_force(name, force):
    m = loaded(name)
    rng = np.random.default_rng(7)
    for _ in range(STATES):
        q, v, u = random_state(m, rng)
        tau = m.inverse(q, v, m.accel(q, v, u), np.zeros(len(u)))
        want = force(m, u)
        assert np.abs(tau - want).max() <= 1e-13 * max(1.0, np.abs(m.bias(q, v, u)).max())


def unit_quaternions(m):
    """The first index of each unit quaternion's four coordinates."""
    return [i for i, c in enumerate(m.coordinates) if c.endswith("_qw")]


def directions(m, q):
    """Directions in the coordinates to difference along (columns): each
    coordinate's own, but for a unit quaternion e three tangent to its
    sphere (the motion's: the accelerations off |e| = 1 belong to no
    motion, and their radial rate is not what the derivatives are)."""
    n, quats = len(q), unit_quaternions(m)
    skip = {i + k for i in quats for k in range(4)}
    cols = [np.eye(n)[:, j] for j in range(n) if j not in skip]
    for i in quats:
        e = q[i:i + 4]
        basis = np.linalg.svd(e.reshape(1, 4))[2][1:]  # the complement of e
        for b in basis:
            d = np.zeros(n)
            d[i:i + 4] = b
            cols.append(d)
    return np.array(cols).T


def on_spheres(m, q):
    q = q.copy()
    for i in unit_quaternions(m):
        q[i:i + 4] /= np.linalg.norm(q[i:i + 4])
    return q


def richardson(f, x, D, h):
    """The derivative of f along each column of D at x: central
    differences at h and h/2, extrapolated (error O(h^4))."""
    cols = []
    for d in D.T:
        def c(s):
            return (f(x + s * d) - f(x - s * d)) / (2 * s)
        cols.append((4 * c(h / 2) - c(h)) / 3)
    return np.array(cols).T


@pytest.mark.parametrize("name", ["pendulum.yaml", "double_pendulum.yaml", "chain5.yaml",
                                  "cartpole.yaml", "gear_link.yaml", "swing.yaml",
                                  "arm.urdf", "floating_base.xml", "humanoid.xml",
                                  # constrained: the KKT solve's derivatives, at states
                                  # on and off the constraints alike
                                  "cartesian_pendulum.yaml", "appell.yaml",
                                  "chaplygin_sleigh.yaml", "rolling_disk.yaml"])
@pytest.mark.filterwarnings("ignore::eomc.EomcWarning")  # (accel off the constraints)
def test_accel_derivatives_are_the_differences_of_accel(name):
    m = loaded(name)
    if not m.extended:
        pytest.skip("built without its extended-precision twin")
    rng = np.random.default_rng(3)
    nq, nv, h, worst = len(m.coordinates), len(m.speeds), 1e-4, 0.0
    for _ in range(STATES):
        q, v, u = random_state(m, rng)
        uu = u if len(u) else None
        dq, dv, du = m.accel_derivatives(q, v, uu)
        Dq = directions(m, q)
        fd = np.hstack([
            richardson(lambda qq: m.accel(on_spheres(m, qq), v, uu, extended=True), q, Dq, h),
            richardson(lambda vv: m.accel(q, vv, uu, extended=True), v, np.eye(nv), h)])
        got = np.hstack([dq @ Dq, dv])
        if len(u):
            fd = np.hstack([fd, richardson(lambda w: m.accel(q, v, w, extended=True), u,
                                           np.eye(len(u)), h)])
            got = np.hstack([got, du])
        worst = max(worst, np.abs(got - fd).max() / np.abs(fd).max())
    assert worst <= 1e-10, worst
