"""What Python costs beside the command line (meson test --benchmark python).

On chain5: a call of Model.accel (ctypes' part included), a load from the
cache, and runs of
1 001, 10 001 and 100 001 rows from Python against `eomc run ... -o
/dev/null` for the same rows: the difference is reading the CSV's text
back, per number.  Prints one line per figure; docs/python.md quotes them.
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


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
