"""The Python package against the command line (to the bit), closed forms,
and every exception path.

Each value asserted is obtained apart from the package: the CLI's CSV read
by Python's own float(), a closed form, a quantity computed here from the
rows, or the same run made alone.
"""

import math
import os
import threading
import warnings

import numpy as np
import pytest

import eomc
from conftest import SOURCE, cli_csv, same_bits, spec


@pytest.fixture(scope="module")
def chain5():
    return eomc.load(spec("chain5.yaml"))


@pytest.fixture(scope="module")
def pendulum():
    return eomc.load(spec("pendulum.yaml"))


# ---- the same numbers as the command line ----

def test_default_run_is_the_cli_to_the_bit(chain5):
    status, columns, rows, _ = cli_csv(spec("chain5.yaml"))
    r = chain5.run()
    assert status == 0
    assert r.columns == columns
    for j, name in enumerate(columns):
        assert same_bits(r[name], rows[:, j]), name
    # the check: the last row's q1
    assert r["q1"][-1] == rows[-1, columns.index("q1")]


def test_options_are_the_cli_options_to_the_bit(chain5):
    status, columns, rows, _ = cli_csv(spec("chain5.yaml"), "--init", "q1=1.0", "--t-end", "3",
                                       "--dt", "0.125", "--method", "rkf45", "--rtol", "1e-9",
                                       "--atol", "1e-11", "--set", "l=1.25")
    m = eomc.load(spec("chain5.yaml"))
    m.set(l=1.25)
    r = m.run(t_end=3, dt=0.125, method="rkf45", rtol=1e-9, atol=1e-11, init={"q1": 1.0})
    assert status == 0 and r.columns == columns and len(r) == 25
    assert all(same_bits(r[c], rows[:, j]) for j, c in enumerate(columns))


def test_model_describes_itself(chain5):
    assert chain5.name == "chain5"
    assert chain5.coordinates == ["q1", "q2", "q3", "q4", "q5"]
    assert chain5.parameters == ["m", "l", "g"]
    assert chain5.params == {"m": 1.0, "l": 1.0, "g": 9.81}
    assert chain5.inputs == [] and chain5.constraints == []
    q, v = chain5.initial()
    assert q[0] == 0.5 and not v.any()


# ---- closed forms ----

def test_falling_particle_is_the_parabola():
    # m y'' = f - m g: y = 10 + (f/m - g) t^2 / 2 (specs/falling_particle.yaml)
    m = eomc.load(spec("falling_particle.yaml"))
    r = m.run()  # rtol = atol = 1e-12 (the scene's)
    a = 5.0 / 2.0 - 9.81
    y = 10 + a * r["t"] ** 2 / 2
    assert len(r) == 101 and r["t"][-1] == 1.0
    assert np.max(np.abs(r["y"] - y)) <= 1e-12 * 10
    assert np.max(np.abs(r["y'"] - a * r["t"])) <= 1e-12 * 10
    np.testing.assert_allclose(m.accel([3.0], [0.25]), [a], rtol=1e-15)


def test_pendulum_accel_and_parameters(pendulum):
    theta = 0.7
    a = pendulum.accel([theta], [1.5])
    assert abs(a[0] + 9.81 * math.sin(theta)) <= 2e-16 * 9.81
    m = eomc.load(spec("pendulum.yaml"))
    m.set(l=2.0, g=1.62)
    assert abs(m.accel([theta], [0.0])[0] + 1.62 / 2.0 * math.sin(theta)) <= 2e-16
    assert m.params["l"] == 2.0
    # the other model is untouched
    assert pendulum.params["l"] == 1.0


def test_small_swings_have_the_harmonic_period(pendulum):
    # theta = 1e-6 cos(sqrt(g/l) t) to first order in the amplitude (the
    # next term is 1e-18); the tolerance relative to that amplitude
    r = pendulum.run(init={"theta": 1e-6}, t_end=2, dt=0.25, rtol=1e-13, atol=1e-22)
    w = math.sqrt(9.81)
    assert np.max(np.abs(r["theta"] - 1e-6 * np.cos(w * r["t"]))) <= 1e-16 + 1e-12 * 1e-6


def test_reference_is_the_parabola():
    m = eomc.load(spec("falling_particle.yaml"))
    ref = m.reference()
    y = 10 + (2.5 - 9.81) * ref["t"] ** 2 / 2
    assert len(ref) == 101 and np.max(np.abs(ref["y"] - y)) <= 1.1e-15 * 10


def test_linearize_the_pendulum_at_rest(pendulum):
    lin = pendulum.linearize(init={"theta": 0.0})
    assert lin.states == ["theta", "theta'"]
    np.testing.assert_array_equal(lin.A, [[0.0, 1.0], [-9.81, 0.0]])
    assert lin.B.shape == (2, 0)
    np.testing.assert_allclose(sorted(lin.eigenvalues.imag), [-math.sqrt(9.81), math.sqrt(9.81)],
                               rtol=1e-15)
    assert np.all(np.abs(lin.eigenvalues.real) <= 1e-15)


def test_linearize_away_from_rest_warns(pendulum):
    # at theta = 0.7 q'' = -g/l sin(0.7), not 0: an EomcWarning names it,
    # and A is still the Jacobian there, [[0, 1], [-g/l cos(0.7), 0]]
    with pytest.warns(eomc.EomcWarning, match=r"q'' is not 0 here \(theta'' = ") as said:
        lin = pendulum.linearize(init={"theta": 0.7})
    text = str(said[0].message)
    got = float(text.split("theta'' = ")[1].split(")")[0])
    assert abs(got + 9.81 * math.sin(0.7)) <= 1e-15 * 9.81
    np.testing.assert_allclose(lin.A, [[0.0, 1.0], [-9.81 * math.cos(0.7), 0.0]], rtol=1e-14)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # at rest: nothing to say
        pendulum.linearize(init={"theta": 0.0})


def test_linearize_in_a_stop_and_on_its_edge():
    # tests/cli/stops.yaml's rotor (I = 1, stops of k = 100, c = 4 at +-0.5):
    # inside its upper stop A = [[0, 1], [-k, -c]] (q'' is not 0 there, which
    # is warned of); on the stop's edge, the outer side's A, and an
    # EomcWarning naming both of the stop's switches
    m = eomc.load(os.path.join(SOURCE, "tests", "cli", "stops.yaml"))
    with pytest.warns(eomc.EomcWarning, match="q'' is not 0 here"):
        lin = m.linearize(init={"theta": 0.6, "theta'": 0.0})
    np.testing.assert_allclose(lin.A, [[0.0, 1.0], [-100.0, -4.0]], rtol=1e-15)
    with pytest.warns(eomc.EomcWarning,
                      match="on the kinks of stops.theta.hi.push and stops.theta.hi"):
        lin = m.linearize(init={"theta": 0.5, "theta'": 0.0})
    np.testing.assert_array_equal(lin.A, [[0.0, 1.0], [0.0, 0.0]])


def test_equilibrium_that_runs_away_raises():
    # the arm of tests/sim/specs/arm4.yaml from shoulder = 1.5: Newton's
    # method follows q'' out along the slide, where it only falls as 1/extend
    m = eomc.load(os.path.join(SOURCE, "tests", "sim", "specs", "arm4.yaml"))
    with pytest.raises(eomc.NumericalFailure, match="Newton's method runs away"):
        m.equilibrium()


def test_equilibrium_of_the_double_pendulum():
    m = eomc.load(spec("double_pendulum.yaml"))
    eq = m.equilibrium(init={"th1": 0.2, "th2": -0.1})
    assert abs(eq.q["th1"]) <= 1e-15 and abs(eq.q["th2"]) <= 1e-15
    # hanging down: four imaginary eigenvalues; w^2 = g (2 +- sqrt 2) for unit masses and rods
    w = sorted(np.abs(eq.eigenvalues.imag))
    want = sorted([math.sqrt(9.81 * (2 - math.sqrt(2)))] * 2 + [math.sqrt(9.81 * (2 + math.sqrt(2)))] * 2)
    np.testing.assert_allclose(w, want, rtol=1e-13)
    assert eq.stable and "stable" in eq.verdict and eq.iterations >= 1


def test_accuracy_rows_measure_the_runs():
    m = eomc.load(spec("falling_particle.yaml"))
    rep = m.accuracy(methods=["rk4"], tolerances=[1e-6], steps=[0.01])
    assert list(rep["method"]) == ["rk4", "rk4"]
    fixed = rep["fixed_step"][1]
    assert fixed == 0.01
    # the fixed-step run's largest error, measured here against the parabola
    # (rk4 is exact on a quadratic up to rounding)
    r = m.run(method="rk4", fixed_step=0.01)
    y = 10 + (2.5 - 9.81) * r["t"] ** 2 / 2
    assert rep["error_max"][1] <= 1e-13 and np.max(np.abs(r["y"] - y)) <= 1e-13
    assert "rk4" in rep.text


# ---- exceptions ----

def test_spec_error_has_its_place(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: bad\nparameters: {m: 1}\ncoordinates: [x]\n"
                   "particles:\n  p: {mass: m, position: [x, y_undefined]}\n")
    with pytest.raises(eomc.SpecError) as e:
        eomc.load(str(bad))
    assert e.value.file == str(bad) and e.value.line == 5
    # the column of y_undefined, counted here
    assert e.value.column == bad.read_text().splitlines()[4].index("y_undefined") + 1
    assert "^" in e.value.message and "y_undefined" in e.value.message


def test_usage_errors(chain5):
    with pytest.raises(eomc.UsageError, match="did you mean 'rk8pd'"):
        chain5.run(method="rk8p")
    with pytest.raises(eomc.UsageError, match="unknown"):
        chain5.run(no_such_option=True)
    with pytest.raises(eomc.UsageError):
        chain5.set(lenght=2.0)
    with pytest.raises(eomc.UsageError, match="m"):
        chain5.set(m=-1.0)
    assert chain5.params["m"] == 1.0  # a refused set leaves every value as it was
    with pytest.raises(eomc.UsageError):
        chain5.accel([0.0] * 4, [0.0] * 5)
    with pytest.raises(eomc.UsageError):
        eomc.load(chain5.path, scene="x")
    with pytest.raises(eomc.EomcError, match="cannot read"):
        eomc.load("/nonexistent/spec.yaml")


def test_numerical_failure_keeps_the_rows(chain5):
    status, columns, rows, err = cli_csv(spec("chain5.yaml"), "--max-steps", "20")
    assert status == 3
    with pytest.raises(eomc.NumericalFailure) as e:
        chain5.run(max_steps=20)
    kept = e.value.rows
    assert len(kept) == len(rows) > 1
    assert all(same_bits(kept[c], rows[:, j]) for j, c in enumerate(columns))
    assert e.value.t is not None and e.value.t >= kept["t"][-1]
    assert "too many steps" in e.value.message


def test_singular_accel_is_a_numerical_failure():
    m = eomc.load(spec("pendulum.yaml"))
    m.set(m=0.0)  # no mass: M = 0
    with pytest.raises(eomc.NumericalFailure, match="mass matrix"):
        m.accel([0.1], [0.0])


def test_warnings_become_python_warnings(pendulum):
    # rk4 in steps of 0.5 (a period is 2.1 s) keeps no digit of E; computed
    # here from the rows (m = l = 1): E = theta'^2/2 - g cos(theta)
    with pytest.warns(eomc.EomcWarning, match="fixed steps of 0.5: the conserved quantity E"):
        r = pendulum.run(method="rk4", fixed_step=0.5)
    e = r["theta'"] ** 2 / 2 - 9.81 * np.cos(r["theta"])
    assert np.max(np.abs(e - e[0])) > 0.01 * np.max(r["theta'"] ** 2 / 2)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        pendulum.run(method="rk4", fixed_step=0.1)


# ---- no global state ----

def test_two_models_side_by_side(chain5, pendulum):
    alone = chain5.run(t_end=1)
    p1 = pendulum.run(t_end=1)
    both = [chain5.run(t_end=1), pendulum.run(t_end=1)]
    assert same_bits(both[0].array(), alone.array())
    assert same_bits(both[1].array(), p1.array())


def test_runs_in_threads_do_not_interfere(chain5, pendulum):
    jobs = [(chain5, 1.0), (pendulum, 2.0), (chain5, 1.5), (pendulum, 0.5)] * 2
    alone = [m.run(t_end=t, init={m.coordinates[0]: 0.3}) for m, t in jobs]
    got = [None] * len(jobs)

    def work(k):
        m, t = jobs[k]
        got[k] = m.run(t_end=t, init={m.coordinates[0]: 0.3})

    threads = [threading.Thread(target=work, args=(k,)) for k in range(len(jobs))]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    for a, g in zip(alone, got):
        assert g.columns == a.columns and same_bits(g.array(), a.array())


def test_nothing_printed_to_the_process(capfd, chain5):
    with pytest.warns(eomc.EomcWarning):
        eomc.load(spec("pendulum.yaml")).run(method="rk4", fixed_step=0.5)
    with pytest.raises(eomc.UsageError):
        chain5.run(method="nope")
    out, err = capfd.readouterr()
    assert out == "" and err == ""


def test_an_urdf_model_is_the_cli_to_the_bit():
    # through MuJoCo's loader (eomc built with libmujoco-dev), as eomc run takes it
    import subprocess
    import eomc._build
    probe = subprocess.run([eomc._build.compiler(), "import", spec("arm.urdf")],
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if probe.returncode != 0:
        pytest.skip("eomc cannot import URDF here: " + probe.stderr.strip())
    status, columns, rows, _ = cli_csv(spec("arm.urdf"), "--t-end", "1", "--init", "shoulder=0.4")
    m = eomc.load(spec("arm.urdf"))
    r = m.run(t_end=1, init={"shoulder": 0.4})
    assert status == 0 and m.coordinates == ["base_yaw", "shoulder", "elbow"]
    assert r.columns == columns and all(same_bits(r[c], rows[:, j]) for j, c in enumerate(columns))


def test_an_urdf_model_has_joint_inputs_and_its_values_as_parameters():
    # the names and values are the URDF file's own (specs/arm.urdf)
    import subprocess
    import eomc._build
    probe = subprocess.run([eomc._build.compiler(), "import", spec("arm.urdf")],
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if probe.returncode != 0:
        pytest.skip("eomc cannot import URDF here: " + probe.stderr.strip())
    m = eomc.load(spec("arm.urdf"), parameters=True)
    assert m.inputs == ["tau_base_yaw", "tau_shoulder", "tau_elbow"]
    p = m.params
    assert (p["mass_turret"], p["mass_upper_arm"], p["mass_forearm"]) == (1, 1.5, 0.8)
    assert (p["damping_base_yaw"], p["damping_shoulder"], p["damping_elbow"]) == (0.02, 0.05, 0.05)
    assert (p["inertia_upper_arm_yy"], p["armature_elbow"], p["stiffness_elbow"]) == (0.02, 0, 0)
    with pytest.raises(eomc.UsageError, match="MJCF or URDF"):
        eomc.load(spec("pendulum.yaml"), parameters=True)


def test_taylor_from_python_is_the_cli_to_the_bit(pendulum):
    opts = ("--method", "taylor", "--rtol", "1e-14", "--atol", "1e-14")
    status, columns, rows, _ = cli_csv(spec("pendulum.yaml"), *opts)
    r = pendulum.run(method="taylor", rtol=1e-14, atol=1e-14, stats=True)
    assert status == 0 and r.columns == columns
    assert all(same_bits(r[c], rows[:, j]) for j, c in enumerate(columns))
    # its order from the tolerance (docs/accuracy.md), and rows off its polynomials
    assert r.stats["order_mean"] == 18 and r.stats["side_steps"] == 0


# ---- speeds that are not the coordinates' rates (a free body) ----

# tests/runtime/freebody.c as a model's library (tests/runtime/meson.build):
# q = (root_x, root_y, root_z, root_e0 .. root_e3), v = (root_x', root_y',
# root_z', root_wx, root_wy, root_wz), p = (m, I1, I2, I3, g) = (2, 1, 2, 3, 9.81)
FREEBODY = os.environ.get("EOMC_TEST_FREEBODY")
needs_freebody = pytest.mark.skipif(not FREEBODY, reason="EOMC_TEST_FREEBODY not set "
                                    "(meson test sets it)")


@needs_freebody
def test_a_free_body_has_speeds_of_its_own():
    m = eomc.load(FREEBODY)
    assert m.coordinates == ["root_x", "root_y", "root_z", "root_e0", "root_e1", "root_e2",
                             "root_e3"]
    assert m.speeds == ["root_x'", "root_y'", "root_z'", "root_wx", "root_wy", "root_wz"]
    assert "and 6 speeds" in repr(m)
    q, v = m.initial()
    assert q.shape == (7,) and v.shape == (6,)
    # v' by Euler's equations and gravity, computed here
    In, g = np.array([1.0, 2.0, 3.0]), 9.81
    w = np.array([0.5, -1.0, 2.0])
    want = np.array([0, 0, -g, -(In[2] - In[1]) * w[1] * w[2] / In[0],
                     -(In[0] - In[2]) * w[0] * w[2] / In[1],
                     -(In[1] - In[0]) * w[0] * w[1] / In[2]])
    a = m.accel(q, np.concatenate([v[:3], w]))
    assert a.shape == (6,) and np.max(np.abs(a - want)) <= 4 * np.finfo(float).eps * g
    with pytest.raises(eomc.UsageError, match="root_wx"):
        m.accel(q, np.zeros(7))  # v has the speeds' 6 entries, not the coordinates' 7


@needs_freebody
def test_a_free_body_runs_by_its_speeds_names():
    m = eomc.load(FREEBODY)
    m.set(I2=1.0)  # symmetric about its axis: wz constant
    r = m.run(init={"root_wx": 1.5, "root_y'": -0.5}, t_end=1.0, dt=0.1)
    assert r.columns[:14] == ["t"] + m.coordinates + m.speeds
    assert r["root_wx"][0] == 1.5 and r["root_y'"][0] == -0.5
    t = r["t"]
    # the centre's parabola, from the first row
    x0 = {c: r[c][0] for c in r.columns}
    z = x0["root_z"] + x0["root_z'"] * t - 9.81 * t * t / 2
    assert np.max(np.abs(r["root_z"] - z)) < 1e-9
    assert np.max(np.abs(r["root_y"] - (x0["root_y"] - 0.5 * t))) < 1e-9
    assert np.max(np.abs(r["root_wz"] - x0["root_wz"])) < 1e-9
    # every row's quaternion of length 1, to rounding
    e = np.array([r["root_e%d" % k] for k in range(4)])
    assert np.max(np.abs(np.sqrt((e * e).sum(axis=0)) - 1)) <= 8 * np.finfo(float).eps


def test_a_free_body_linearizes_in_its_tangent_space():
    # spinning at w about its minor axis (I1 < I2 < I3), without gravity (a
    # steady motion): the rotation's error dtheta' = dw - w0 x dtheta gives
    # +-i w, Euler's equations +-i w sqrt((I2 - I1)(I3 - I1) / (I2 I3))
    m = eomc.load(FREEBODY)
    m.set(g=0.0)
    w = 0.7
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a steady motion: nothing to say
        lin = m.linearize(init={"root_wx": w, "root_wy": 0.0, "root_wz": 0.0})
    assert lin.states == (["root_x", "root_y", "root_z", "root_rx", "root_ry", "root_rz"]
                          + m.speeds)
    rot = lin.A[3:6, 3:6]
    np.testing.assert_array_equal(rot, [[0, 0, 0], [0, 0, w], [0, -w, 0]])
    np.testing.assert_array_equal(lin.A[3:6, 9:12], np.eye(3))
    lam = w * math.sqrt((2.0 - 1.0) * (3.0 - 1.0) / (2.0 * 3.0))
    want = sorted([w, -w, lam, -lam])
    got = sorted(z.imag for z in lin.eigenvalues if abs(z) > 1e-12)
    np.testing.assert_allclose(got, want, rtol=1e-13)
