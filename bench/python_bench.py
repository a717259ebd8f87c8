"""What Python costs beside the command line (meson test --benchmark python).

On chain5: a call of Model.accel (ctypes' part included), a load from the
cache, and runs of
1 001, 10 001 and 100 001 rows from Python against `eomc run ... -o
/dev/null` for the same rows: the difference is reading the CSV's text
back, per number.  Prints one line per figure; docs/python.md quotes them.
Then issue 45's figures: the pendulum's 200 001 rows from Python against
`eomc run -o /dev/null` (the rows from memory: no text either way; the
target is at most 1.2 times); a 1 kHz sampled controller from Python on a
6-joint arm imported from MJCF (MuJoCo's loader: skipped without it) over
10 s, what it adds per call beyond its own body; and, with MJ_BENCH set
to bench/mj_bench, accel_derivatives on MuJoCo's humanoid against
MuJoCo's finite differences (one mj_forward per column), and against
accel.
usage: python3 python_bench.py EOMC SOURCE_ROOT
"""

import os
import subprocess
import sys
import tempfile
import time


def main(eomc_path, source):
    os.environ["EOMC"] = eomc_path
    sys.path.insert(0, source)
    import eomc
    spec = os.path.join(source, "specs", "chain5.yaml")
    with tempfile.TemporaryDirectory() as cache:
        os.environ["EOMC_CACHE_DIR"] = cache
        m = eomc.load(spec)
        t0 = time.perf_counter()
        eomc.load(spec)
        print("load from the cache: %.1f ms" % ((time.perf_counter() - t0) * 1e3))
        q, v = m.initial()
        n = 20000
        t0 = time.perf_counter()
        for _ in range(n):
            m.accel(q, v)
        print("Model.accel: %.2f us a call" % ((time.perf_counter() - t0) / n * 1e6))
        # the simulator built into the cache first: its build is not timed
        subprocess.run([eomc_path, "run", spec, "--t-end", "0.01", "-o", os.devnull], check=True)
        for dt in (0.01, 0.001, 0.0001):
            t0 = time.perf_counter()
            r = m.run(dt=dt)
            py = time.perf_counter() - t0
            t0 = time.perf_counter()
            subprocess.run([eomc_path, "run", spec, "--dt", repr(dt), "-o", os.devnull],
                           check=True)
            cli = time.perf_counter() - t0
            cells = len(r) * len(r.columns)
            print("run of %d rows (%d numbers): Python %.3f s, eomc run %.3f s, "
                  "%.2f us a number more" % (len(r), cells, py, cli, (py - cli) / cells * 1e6))


# turns of MuJoCo's timing and eomc's in the derivatives' comparison
ROUNDS = 5


def best(f, k=3):
    """The least wall time of k calls of f, and its last result."""
    t, r = float("inf"), None
    for _ in range(k):
        t0 = time.perf_counter()
        r = f()
        t = min(t, time.perf_counter() - t0)
    return t, r


def issue45(eomc_path, source):
    import numpy as np
    import eomc
    pend = os.path.join(source, "specs", "pendulum.yaml")
    m = eomc.load(pend)
    subprocess.run([eomc_path, "run", pend, "--t-end", "0.01", "-o", os.devnull], check=True)
    py, r = best(lambda: m.run(t_end=20, dt=1e-4))
    cli, _ = best(lambda: subprocess.run([eomc_path, "run", pend, "--t-end", "20", "--dt",
                                          "1e-4", "-o", os.devnull], check=True))
    print("pendulum, %d rows: Python %.3f s, eomc run -o /dev/null %.3f s: %.2f times "
          "(target <= 1.2)" % (len(r), py, cli, py / cli))
    arm = os.path.join(source, "tests", "import", "models", "robots", "servo_arm.xml")
    try:
        a = eomc.load(arm, joint_inputs=True)
    except eomc.EomcError as e:
        print("controller: skipped (%s)" % str(e).splitlines()[0])
        return
    zero = np.zeros(len(a.inputs))

    def body(t, q, v):
        return zero

    n = 100000
    t0 = time.perf_counter()
    for _ in range(n):
        body(0.0, zero, zero)
    own = (time.perf_counter() - t0) / n
    plain, _ = best(lambda: a.run(t_end=10, dt=1e-3, stats=True))
    ctrl, rc = best(lambda: a.run(t_end=10, dt=1e-3, controller=body, period=1e-3,
                                  stats=True))
    calls = 10000
    print("1 kHz controller on servo_arm (%d coordinates, %d inputs), 10 s: %.3f s against "
          "%.3f s without, %d steps: %.1f us a call beyond its body (%.2f us; target <= 20)"
          % (len(a.coordinates), len(a.inputs), ctrl, plain, rc.stats["steps"],
             ((ctrl - plain) / calls - own) * 1e6, own * 1e6))
    mj = os.environ.get("MJ_BENCH")
    hum = "/usr/share/mujoco/model/humanoid/humanoid.xml"
    if not mj or not os.path.exists(hum):
        print("derivatives: skipped (no MJ_BENCH, or no libmujoco-samples)")
        return
    def per_call(f, n=200):
        f()
        t, _ = best(lambda: [f() for _ in range(n)])
        return t / n

    def mj_forward():
        return float(subprocess.run([mj, hum], check=True, stdout=subprocess.PIPE,
                                    text=True).stdout) * 1e-9

    # what mj_bench's mj_forward computes: contact, limits and friction loss off; the
    # Jacobian as --jacobian auto builds a library (unrolled, at this size) and seeded
    # (what auto gives a simulator at this size: less C, slower to run).  MuJoCo and
    # eomc in turns, ROUNDS times, each at its least: a shared machine's slow spells
    # (seen: twice the time for seconds) then reach both or neither
    for jac in (None, "seeded"):
        h = eomc.load(hum, effects=["gravity", "damping", "stiffness", "armature", "actuators"],
                      jacobian=jac)
        q, v = h.initial()
        v = v + 0.2
        fwd = acc = der = float("inf")
        for _ in range(ROUNDS):
            fwd = min(fwd, mj_forward())
            acc = min(acc, per_call(lambda: h.accel(q, v)))
            der = min(der, per_call(lambda: h.accel_derivatives(q, v)))
        cols = 2 * len(h.speeds) + len(h.inputs)
        print("humanoid (nv %d, nu %d), jacobian %s: accel_derivatives %.1f us from Python, "
              "accel %.1f us (%.1f times); MuJoCo's differences %d mj_forward of %.2f us = "
              "%.1f us: %.3f of them (target < 0.1)"
              % (len(h.speeds), len(h.inputs), jac or "auto", der * 1e6, acc * 1e6, der / acc,
                 cols, fwd * 1e6, cols * fwd * 1e6, der / (cols * fwd)))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
    issue45(sys.argv[1], sys.argv[2])
