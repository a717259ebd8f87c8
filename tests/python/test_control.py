"""A controller in the loop from Python: ``m.run(controller=f, period=T)``.

The plant is the cart-pole (specs/cartpole.yaml).  The checks are against
values got outside the run: an LQR designed on ``m.linearize()`` (the
Riccati equation solved here by the Hamiltonian's stable subspace), the
closed loop's own linear motion (the zero-order hold's exact discrete
map, and the continuous loop's matrix exponential, both by their series
here), the reference solution against a run at 1e-14, and each failure
of a controller.
"""

import os

import numpy as np
import pytest

import eomc
from conftest import SOURCE, same_bits, spec

T = 0.01  # the sampling period: 100 Hz


def lqr(A, B, Q, R):
    """The continuous-time LQR gain K = R^-1 B^T P, P from the stable
    invariant subspace of the Hamiltonian matrix."""
    n = A.shape[0]
    Ri = np.linalg.inv(R)
    H = np.block([[A, -B @ Ri @ B.T], [-Q, -A.T]])
    w, V = np.linalg.eig(H)
    S = V[:, w.real < 0]
    P = np.real(S[n:] @ np.linalg.inv(S[:n]))
    return Ri @ B.T @ P


def expm(Z):
    """exp(Z) by scaling, its series and squaring (Z small after scaling)."""
    s = max(0, int(np.ceil(np.log2(max(np.abs(Z).sum(axis=1).max(), 1e-300)))) + 1)
    Z = Z / 2 ** s
    E, term = np.eye(len(Z)), np.eye(len(Z))
    for k in range(1, 30):
        term = term @ Z / k
        E = E + term
    for _ in range(s):
        E = E @ E
    return E


def zoh(A, B, h):
    """The zero-order hold's exact map over h: x+ = Phi x + Gamma u."""
    n, m = B.shape
    Z = np.zeros((n + m, n + m))
    Z[:n, :n], Z[:n, n:] = A * h, B * h
    E = expm(Z)
    return E[:n, :n], E[:n, n:]


@pytest.fixture(scope="module")
def plant():
    m = eomc.load(spec("cartpole.yaml"))
    lin = m.linearize(init={"theta": 0})
    assert lin.states == ["x", "theta", "x'", "theta'"] and lin.inputs == ["F"]
    K = lqr(lin.A, lin.B, np.diag([100.0, 100.0, 1.0, 1.0]), 0.1 * np.eye(1))
    return m, lin, K


def state(r, k):
    return np.array([r["x"][k], r["theta"][k], r["x'"][k], r["theta'"][k]])


def test_a_sampled_lqr_balances_the_pole_as_its_linear_loop_says(plant):
    m, lin, K = plant
    calls = []

    def f(t, q, v):
        calls.append(t)
        return -K @ np.concatenate([q, v])

    r = m.run(controller=f, period=T, t_end=5, dt=T)
    # from a 0.3 rad tilt, upright: the pole within 1e-4 of it over the last second
    late = r["t"] >= 4
    assert abs(r["theta"][0] - 0.3) == 0 and np.abs(r["theta"][late]).max() < 1e-4
    # once the tilt is small (t = 2) the motion is the linear sampled loop's:
    # x_{k+1} = (Phi - Gamma K) x_k, its exact map, to the nonlinear terms' size
    Phi, Gam = zoh(lin.A, lin.B, T)
    k2 = int(np.flatnonzero(r["t"] == 2.0)[0])
    x, worst = state(r, k2), 0.0
    for k in range(k2 + 1, len(r)):
        x = (Phi - Gam @ K) @ x
        worst = max(worst, np.abs(state(r, k) - x).max())
    scale = np.abs(state(r, k2)).max()
    assert worst <= 1e-4 * scale, (worst, scale)
    # once a sample, at t0 + k T exactly (500 before t_end)
    assert len(calls) == 500 and calls == [k * T for k in range(500)]


def test_a_dict_by_name_is_the_sequence(plant):
    m, _, K = plant
    seq = m.run(controller=lambda t, q, v: -K @ np.concatenate([q, v]), period=T, t_end=1)
    named = m.run(controller=lambda t, q, v: {"F": float(-K @ np.concatenate([q, v]))},
                  period=T, t_end=1)
    assert seq.columns == named.columns
    assert all(same_bits(seq[c], named[c]) for c in seq.columns)


def test_a_continuous_controller_is_the_closed_loop_ode(plant):
    m, lin, K = plant
    # a tilt of 1e-4: the nonlinear terms are 1e-8 of the linear ones
    r = m.run(controller=lambda t, q, v: -K @ np.concatenate([q, v]), t_end=2, dt=0.1,
              init={"theta": 1e-4}, rtol=1e-12, atol=1e-14)
    x0, Acl, worst = state(r, 0), lin.A - lin.B @ K, 0.0
    for k in range(len(r)):
        worst = max(worst, np.abs(state(r, k) - expm(Acl * r["t"][k]) @ x0).max())
    assert worst <= 1e-7 * np.abs(x0).max(), worst


def test_error_with_a_sampled_controller_is_the_true_error(plant):
    m, _, K = plant

    def f(t, q, v):
        return -K @ np.concatenate([q, v])

    r = m.run(controller=f, period=T, t_end=2, method="rkf45", rtol=1e-6, atol=1e-6, error=True)
    best = m.run(controller=f, period=T, t_end=2, rtol=1e-14, atol=1e-14)
    true = max(np.abs(r[c] - best[c]).max() for c in ["x", "theta", "x'", "theta'"])
    said = r.stats["error_max"]
    assert true > 1e-10 and abs(said - true) <= 1e-2 * true, (said, true)


def test_error_with_switches_under_a_sampled_controller_is_the_true_error():
    """tests/cli/stops.yaml's rotor between compliant stops at +-0.5, driven
    by its motor, saturated at +-1, under a sampled PD loop after a target
    swinging to 0.7: the clamp's switches flip at samples (the command
    jumps across the saturation), the stops' inside steps (located).  The
    reference follows both, so the error a run reports is its true error
    against a run at 1e-14, with the same 17 flips."""
    m = eomc.load(os.path.join(SOURCE, "tests", "cli", "stops.yaml"), effects="stops,motor")

    def f(t, q, v):
        return [8 * (0.7 * np.sin(3 * t) - q[0]) - 0.5 * v[0]]

    r = m.run(controller=f, period=0.01, t_end=3, method="rkf45", rtol=1e-6, atol=1e-6,
              error=True, stats=True)
    best = m.run(controller=f, period=0.01, t_end=3, rtol=1e-14, atol=1e-14)
    assert np.abs(best["theta"]).max() > 0.5  # (in the stops' reach)
    true = max(np.abs(r[c] - best[c]).max() for c in ["theta", "theta'"])
    said = r.stats["error_max"]
    assert true > 1e-8 and abs(said - true) <= 1e-3 * true, (said, true)
    assert r.stats["switches"] == r.stats["reference_switches"] == 17


@pytest.mark.parametrize("bad, why", [
    (lambda t, q, v: [1.0, 2.0], "returned 2 values, and the model has 1 inputs (F)"),
    (lambda t, q, v: [float("nan")], "it set F to nan"),
    (lambda t, q, v: {"G": 1.0}, "'G' is not an input of the model (its inputs: F)"),
    (lambda t, q, v: 1 / 0, "it raised ZeroDivisionError"),
])
def test_a_bad_controller_is_an_exception_naming_the_time(plant, bad, why):
    m, _, K = plant

    def f(t, q, v):
        if t >= 0.5:
            return bad(t, q, v)
        return -K @ np.concatenate([q, v])

    with pytest.raises(eomc.ControllerError) as e:
        m.run(controller=f, period=T, t_end=1, dt=T)
    assert why in str(e.value) and e.value.t == 50 * T
    assert "the controller at t = %r" % (50 * T) in str(e.value)
    rows = e.value.rows  # the rows before it, the last at its sample
    assert len(rows) == 51 and rows["t"][-1] == e.value.t
    if "raised" in why:
        assert isinstance(e.value.__cause__, ZeroDivisionError)


def test_controller_usage(plant):
    m = plant[0]
    with pytest.raises(eomc.UsageError, match="no controller"):
        m.run(period=0.1)
    with pytest.raises(eomc.UsageError, match="period must be positive"):
        m.run(controller=lambda t, q, v: [0.0], period=-1)
    with pytest.raises(eomc.UsageError, match="function"):
        m.run(controller=3)
    with pytest.raises(eomc.UsageError, match="a sweep with a controller"):
        m.run(controller=lambda t, q, v: [0.0], period=0.1, sweep={"theta": "0.1:0.2:2"})


def test_the_same_loop_by_hand_is_the_same_rows_to_the_bit(plant):
    # a sampled controller's run, and the loop written by hand on a Sim:
    # set u at each sample, advance to the next
    m, _, K = plant

    def f(t, q, v):
        return -K @ np.concatenate([q, v])

    r = m.run(controller=f, period=T, t_end=1, dt=T)
    s = m.sim(t_end=1)
    states = [np.concatenate([s.q, s.v])]
    for k in range(100):
        s.u = f(s.t, s.q, s.v)
        s.advance((k + 1) * T)  # the controller's sample times, t0 + (k + 1) T, so rounded
        states.append(np.concatenate([s.q, s.v]))
    hand = np.array(states)
    assert len(r) == 101 and s.t == 1
    for j, c in enumerate(["x", "theta", "x'", "theta'"]):
        assert same_bits(r[c], hand[:, j]), c


def test_a_sim_steps_reads_and_sets(plant):
    m = plant[0]
    s = m.sim(init={"theta": 0.1}, t_end=2)
    assert s.t == 0 and list(s.q) == [0.0, 0.1] and list(s.v) == [0.0, 0.0]
    assert list(s.u) == [0.0]
    t1 = s.step()
    assert 0 < t1 == s.t < 2
    s.u = {"F": 2.0}
    assert list(s.u) == [2.0]
    s.advance(0.5)
    assert s.t == 0.5
    s.v = [1.0, 0.0]  # a jump of the state, the motion goes on from it
    assert list(s.v) == [1.0, 0.0]
    s.advance(2)
    with pytest.raises(eomc.UsageError, match="over"):
        s.step()
    with pytest.raises(eomc.UsageError, match="not an input"):
        m.sim().u = {"G": 1}
    with pytest.raises(eomc.UsageError, match="advance"):
        m.sim(t_end=1).advance(3)


def test_pd_with_gravity_compensation_tracks_as_its_linearization_says():
    # specs/arm.urdf: its joints' torques tau_J are inputs; PD on each joint
    # plus gravity from m.bias(q, 0), tracking q0 + A sin(w t).  For small A
    # the error e = q_d - q obeys the loop's linearization about q0,
    #   M0 e'' + (KD + D) e' + KP e = M0 q_d'' + D q_d',
    # M0 = m.mass(q0), D the joints' damping as the URDF writes it (0.02,
    # 0.05, 0.05); solved here exactly with the reference's oscillator in
    # the state.  What is left is the nonlinear terms: 1.3e-6 of the error.
    import subprocess
    import eomc._build
    if subprocess.run([eomc._build.compiler(), "import", spec("arm.urdf")],
                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode:
        pytest.skip("eomc cannot import URDF here")
    m = eomc.load(spec("arm.urdf"))
    q0 = np.array([0.0, 0.5, -0.8])
    A, w = 1e-3 * np.array([1.0, -0.7, 0.5]), 3.0
    KP, KD = np.diag([40.0, 60.0, 30.0]), np.diag([4.0, 6.0, 3.0])
    zero = np.zeros(3)

    def f(t, q, v):
        qd = q0 + A * np.sin(w * t)
        vd = A * w * np.cos(w * t)
        return KP @ (qd - q) + KD @ (vd - v) + m.bias(q, zero, zero)

    init = {"base_yaw": q0[0], "shoulder": q0[1], "elbow": q0[2]}
    r = m.run(controller=f, t_end=4, dt=0.01, init=init, rtol=1e-10, atol=1e-12)
    names = ["base_yaw", "shoulder", "elbow"]
    e_run = np.array([q0 + A * np.sin(w * t) for t in r["t"]]) - np.column_stack(
        [r[c] for c in names])
    # the linearization: z = (e, e', s, c) with s = sin(w t), c = cos(w t)
    M0, D = m.mass(q0), np.diag([0.02, 0.05, 0.05])
    Mi = np.linalg.inv(M0)
    F = np.zeros((8, 8))
    F[:3, 3:6] = np.eye(3)
    F[3:6, :3] = -Mi @ KP
    F[3:6, 3:6] = -Mi @ (KD + D)
    # forcing M0 q_d'' + D q_d' = -M0 A w^2 s + D A w c
    F[3:6, 6] = Mi @ (-M0 @ (A * w * w))
    F[3:6, 7] = Mi @ (D @ (A * w))
    F[6, 7], F[7, 6] = w, -w
    z0 = np.concatenate([zero, A * w, [0.0, 1.0]])  # e(0) = 0, e'(0) = q_d'(0) - v(0)
    e_lin = np.array([(expm(F * t) @ z0)[:3] for t in r["t"]])
    worst, size = np.abs(e_run - e_lin).max(), np.abs(e_lin).max()
    assert size > 1e-5 and worst <= 1e-5 * size, (worst, size)
