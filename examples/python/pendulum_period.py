"""A pendulum's period against its amplitude, as a sweep, from Python.

The `quarter` scene of specs/swing.yaml releases the pendulum from rest at
theta0 and stops at the bottom (an event): a quarter period.  One sweep
over theta0 runs them all (on two threads), and each period is set beside
the closed form T = 4 K(sin(theta0/2)) / sqrt(g/l), K the complete elliptic
integral of the first kind (by the arithmetic-geometric mean).  With
matplotlib installed it also draws T / T0 against theta0.

    PYTHONPATH=. python3 examples/python/pendulum_period.py [PLOT.png]

(from the repository after the README's build; an installed eomc needs no
PYTHONPATH).  It prints one line per amplitude and exits 1 if a period is
off the closed form by more than 1e-9 of itself.
"""

import math
import os
import sys

import eomc

HERE = os.path.dirname(os.path.abspath(__file__))
SPEC = os.path.join(HERE, "..", "..", "specs", "swing.yaml")


def period(theta0, g=9.81, l=1.0):
    """4 K(k) / sqrt(g/l), k = sin(theta0/2): K = pi / (2 agm(1, sqrt(1 - k^2)))."""
    a, b = 1.0, math.cos(theta0 / 2)
    for _ in range(40):  # quadratic convergence: a handful reach the rounding
        a, b = (a + b) / 2, math.sqrt(a * b)
    return 4 * (math.pi / (2 * a)) / math.sqrt(g / l)


def main(argv):
    m = eomc.load(SPEC, scene="quarter")
    # one run per amplitude; a sweep's rows are each run's end: its time is
    # the stop event's, the quarter period
    sweep = m.run(sweep={"theta0": "0.1:3.0:30"}, threads=2)
    worst = 0.0
    T0 = 2 * math.pi / math.sqrt(9.81)
    print("%8s %20s %20s %10s" % ("theta0", "T (eomc)", "T (closed form)", "T/T0"))
    for a, t in zip(sweep["theta0"], sweep["t"]):
        T, exact = 4 * t, period(a)
        worst = max(worst, abs(T - exact) / exact)
        print("%8.4f %20.15f %20.15f %10.6f" % (a, T, exact, T / T0))
    print("largest relative difference from the closed form: %.2g" % worst)
    if len(argv) > 1:
        try:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            print("matplotlib is not installed: no plot")
        else:
            plt.plot(sweep["theta0"], 4 * sweep["t"] / T0, "o-")
            plt.xlabel("amplitude theta0 (rad)")
            plt.ylabel("period / small-swing period")
            plt.title("specs/swing.yaml, scene quarter")
            plt.savefig(argv[1])
            print("plot:", argv[1])
    return 0 if worst <= 1e-9 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
