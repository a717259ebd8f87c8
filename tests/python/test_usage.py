"""What a new user of the package meets first (issue 42): values refused
where they are given, accel's warning off the constraints, a run's
figures to the last bit, the default scene's name, and importing from the
folder above a clone.

Each value asserted is obtained apart from the package: the CLI's own
lines, the reference's rows compared here, or the header's constant.
"""

import math
import os
import re
import subprocess
import sys
import warnings

import numpy as np
import pytest

import eomc
import eomc._build
import eomc._lib
from conftest import SOURCE, cli_csv, same_bits, spec


def sim_spec(name):
    return os.path.join(SOURCE, "tests", "sim", "specs", name)


# ---- set refuses what it cannot take, and changes nothing ----

@pytest.mark.parametrize("name, value", [("g", math.nan), ("l", math.inf), ("m", -math.inf),
                                         ("g", True), ("l", "abc")])
def test_set_refuses_a_value_that_is_not_a_finite_number(name, value):
    m = eomc.load(spec("chain5.yaml"))
    m.set(l=1.25)
    before, run = dict(m.params), m.run(t_end=1)
    other = "m" if name != "m" else "g"
    with pytest.raises(eomc.UsageError) as e:
        m.set(**{other: 2.0, name: value})
    # the name and the value given, not a later call's blame
    assert "set: %s = %r" % (name, value) in e.value.message
    assert m.params == before  # the good value given beside it is not set either
    after = m.run(t_end=1)
    assert same_bits(after.array(), run.array())
    lin = m.linearize(init={"q1": 0.0})  # the other tasks take the values as before
    assert lin.A.shape == (10, 10)


def test_set_refuses_an_unphysical_value_and_changes_nothing():
    m = eomc.load(spec("pendulum.yaml"))
    a = m.accel([0.7], [0.0])
    with pytest.raises(eomc.UsageError, match=r"m = -2"):
        m.set(l=3.0, m=-2.0)  # a negative mass: the runtime's check, at set
    assert m.params["l"] == 1.0 and m.params["m"] == 1.0
    assert same_bits(m.accel([0.7], [0.0]), a)


# ---- accel checks its state as a run checks its start ----

def test_accel_warns_at_a_quaternion_of_norm_2():
    path = sim_spec("floating_arm.yaml")
    m = eomc.load(path)
    q, v = m.initial()
    e = m.coordinates.index("e0")
    assert abs(np.dot(q[e:e + 4], q[e:e + 4]) - 1) <= 1e-15  # the scene starts on it
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        m.accel(q, v)  # on the constraints: no warning
    q2 = q.copy()
    q2[e:e + 4] *= 2
    # the command line's warning for the same state as a start, figure and all
    init = []
    for i, name in enumerate(m.coordinates):
        init += ["--init", "%s=%r" % (name, q2[i]), "--init", "%s'=%r" % (name, v[i])]
    _, _, _, err = cli_csv(path, "--t-end", "0.01", *init)
    said = re.search(r"the initial state is off (the constraint body_axes_unit \(positions: "
                     r"its residual is [0-9.e+-]+ of the size of its terms\))", err)
    assert said, err
    with pytest.warns(eomc.EomcWarning) as w:
        m.accel(q2, v)
    assert len(w) == 1 and "accel: the state is off " + said.group(1) in str(w[0].message)
    # unit norm but e' along e: off at velocity level
    v2 = v.copy()
    v2[e:e + 4] = q[e:e + 4]
    with pytest.warns(eomc.EomcWarning, match=r"off the constraint body_axes_unit "
                                              r"\(velocities: its residual is"):
        m.accel(q, v2)


def test_accels_threshold_is_the_runtimes():
    with open(os.path.join(SOURCE, "runtime", "include", "eomc.h")) as f:
        header = re.search(r"#define EOMC_INCONSISTENT (\S+)", f.read())
    assert float(header.group(1)) == eomc._lib.INCONSISTENT


# ---- a run's figures, to the last bit ----

def test_error_run_has_its_figures_to_the_last_bit():
    m = eomc.load(spec("chain5.yaml"))
    r = m.run(t_end=1, error=True)  # no stats=True
    ref = m.reference(t_end=1)
    # |x - x_ref| over the coordinates and velocities, computed here from the rows
    cols = m.coordinates + [c + "'" for c in m.coordinates]
    err = np.array([np.abs(r[c] - ref[c]) for c in cols])
    assert r.stats["error_max"] == np.max(err) and r.stats["error_end"] == np.max(err[:, -1])
    assert r.stats["reference_error"] > 0 and r.stats["steps"] == int(r.stats["steps"])
    # the CLI's --stats lines, read back by Python's float, are the same figures
    _, _, _, cli = cli_csv(spec("chain5.yaml"), "--t-end", "1", "--error", "--stats")
    lines = dict(line.split(" ", 1) for line in cli.splitlines() if line.startswith("error_"))
    assert float(lines["error_max"]) == r.stats["error_max"]
    # the one-line report is still said, with the component that keeps the fewest digits
    assert "keeps the fewest digits" in r.messages


# ---- the default scene ----

def test_scene_of_the_spec_s_unnamed_scene_is_none():
    m = eomc.load(spec("chain5.yaml"))  # `scene:`, unnamed
    assert m.scene is None
    again = eomc.load(spec("chain5.yaml"), scene=m.scene)  # what load takes
    assert again.path == m.path  # the same library from the cache
    swing = eomc.load(spec("swing.yaml"))  # `scenes:`: the first is the default
    assert swing.scene == "free" and eomc.load(spec("swing.yaml"), scene="damped").scene == "damped"


# ---- importing from the folder above a clone ----

def test_import_from_the_folder_above_a_clone(tmp_path):
    clone = tmp_path / "eomc"
    clone.symlink_to(SOURCE, target_is_directory=True)
    script = tmp_path / "script.py"
    script.write_text("import eomc\nprint(eomc.load.__module__, eomc.__file__)\n")
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    p = subprocess.run([sys.executable, str(script)], cwd=str(tmp_path), env=env,
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert p.returncode != 0
    last = p.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: %s is eomc's repository, not its package" % clone)
    assert "PYTHONPATH=%s" % clone in last
    # with the clone on the path as the message says, the package is imported
    env["PYTHONPATH"] = str(clone)
    p = subprocess.run([sys.executable, str(script)], cwd=str(tmp_path), env=env,
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert p.returncode == 0, p.stderr
    module, where = p.stdout.split()
    assert module == "eomc._model"
    assert os.path.realpath(where) == os.path.realpath(os.path.join(SOURCE, "eomc", "__init__.py"))


# ---- errors in Python's terms (issue 45) ----

@pytest.mark.parametrize("kw, said", [
    (dict(tend=3), "unknown keyword 'tend' (did you mean 't_end'?)"),
    (dict(stabilise="project"), "unknown keyword 'stabilise' (did you mean 'stabilize'?)"),
    (dict(fixed_step="a"), "fixed_step: 'a' is not a finite number"),
])
def test_a_usage_error_names_the_keyword_not_the_flag(kw, said):
    m = eomc.load(spec("pendulum.yaml"))
    with pytest.raises(eomc.UsageError) as e:
        m.run(**kw)
    assert said in e.value.message and "--" not in e.value.message


@pytest.mark.parametrize("name", ["nope.yaml", "nope.xml", "nope.urdf", "nope.so"])
def test_a_missing_file_is_a_file_not_found_error(tmp_path, name):
    path = str(tmp_path / name)
    with pytest.raises(FileNotFoundError) as e:
        eomc.load(path)
    assert isinstance(e.value, eomc.EomcError) and e.value.filename == path
    assert str(e.value) == "cannot read %s: no such file" % path


@pytest.mark.parametrize("name, text, line, column", [
    ("bad.xml", '<mujoco><worldbody><body><geom type="sphere" size="0.1"/>'
     '<joint type="hinge"/></body></worldbody><bogus/></mujoco>', 1, 98),
    ("bad.urdf", '<robot name="r"><link name="a"/><joint name="j" type="revolute">'
     '<parent link="a"/><child link="b"/></joint></robot>', 1, 33),
])
def test_a_broken_model_file_is_a_spec_error_at_its_place(tmp_path, name, text, line, column):
    probe = subprocess.run([eomc._build.compiler(), "import", spec("arm.urdf")],
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if probe.returncode != 0:
        pytest.skip("eomc cannot import MJCF or URDF here: " + probe.stderr.strip())
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(eomc.SpecError) as e:
        eomc.load(str(path))
    assert (e.value.file, e.value.line, e.value.column) == (str(path), line, column)
    assert "MuJoCo cannot load it" in e.value.message
