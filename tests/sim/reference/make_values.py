#!/usr/bin/env python3
#
# make_values.py -- independent high-precision reference values for the
# eomc simulation tests.  Needs only python3 + mpmath (written against
# mpmath 1.3.0, pure-Python backend, no gmpy2).
#
#     cd tests/sim/reference && python3 make_values.py
#
# rewrites pendulum.csv and chain5.csv (byte-for-byte identical on every
# run: the computation is deterministic and the output format is fixed).
# Run time on the machine used: about 6 minutes in total (two runs took
# 5 min 48 s and 6 min 18 s: pendulum ~5 s, chain run A 150-155 s,
# chain run B 190-220 s).  The script stops with an
# AssertionError if any self-check fails; the CSVs are written only after
# their checks have passed.
#
# Nothing here is taken from any project file: the equations below were
# derived by hand for this script.
#
# ---------------------------------------------------------------------------
# Conventions
# ---------------------------------------------------------------------------
# * g = mpf(9.81) built from the Python float 9.81, i.e. the binary64
#   double nearest to 9.81, exactly
#       9.8100000000000004973799150320701301097869873046875,
#   because that is the value the C code works with.  (With the exact
#   decimal 9.81 the pendulum rows would change by at most 2.0e-15.)
# * l = m = 1, theta0 = 1.0 and q1(0) = 1.0 are exact.
# * The chain's initial angles 0.1 are likewise the binary64 value
#   mpf(0.1) = 0.1000000000000000055511151231257827021181583404541015625.
#   With the exact decimal 0.1 the chain rows would change by at most
#   2.5e-16 (figures from `python3 make_values.py --ic-sensitivity`, an
#   optional study that writes no files).
# * Output: first column t printed exactly (repr of the float i/4 or i);
#   every other value in scientific notation with 25 significant digits,
#   correctly rounded from the working-precision value
#   (e.g. -1.939113769051690654705596e+0).  Values that are exactly zero
#   by construction (theta'(0), q'(0)) are printed as 0.000...0e+0.
#
# ---------------------------------------------------------------------------
# 1. pendulum.csv -- simple pendulum, closed form (mp.dps = 50)
# ---------------------------------------------------------------------------
#   theta from the downward vertical, theta'' = -(g/l) sin(theta),
#   theta(0) = theta0 = 1, theta'(0) = 0.
#   w = sqrt(g/l), k = sin(theta0/2), m = k^2, K = K(m) (mpmath.ellipk).
#   Energy: theta'^2/2 - w^2 cos(theta) = -w^2 cos(theta0).  With
#   sin(theta/2) = k sn(u|m), u = K - w t, this is satisfied identically
#   and sn(K) = 1 gives theta(0) = theta0.  Differentiating,
#       (1/2) cos(theta/2) theta' = k cn(u) dn(u) du/dt = -w k cn(u) dn(u),
#   and cos(theta/2) = +sqrt(1 - k^2 sn^2) = dn(u) (|theta| < pi), so
#       theta  = 2 asin(k sn(K - w t | m)),
#       theta' = -2 k w cn(K - w t | m).
#   Sign: for small t > 0, u < K so cn(u) > 0 and theta' < 0 -- theta
#   decreases from theta0, as it must.  sn, cn from mpmath.ellipfun.
#   Rows t = 0, 0.25, ..., 10 (41 rows), columns t,theta,theta'.
#
#   Self-checks (results of the recorded run):
#   * energy theta'^2/2 - (g/l) cos(theta) vs its initial value, all rows:
#       max deviation 2.1e-50            (required < 1e-35)
#   * central numerical derivative (mpmath.diff) of theta(t) vs theta':
#       max deviation 3.7e-50            (required < 1e-30)
#   * initial condition theta(0) = 1, theta'(0) = 0 from the formula:
#       error 5.8e-52
#   * independent numerical integration of theta'' = -(g/l) sin(theta)
#     with the integrator described below (H = 1/100, order 24):
#       max deviation from the closed form 2.0e-46   (required < 1e-30)
#
# ---------------------------------------------------------------------------
# 2. chain5.csv -- planar chain of 5 point masses
# ---------------------------------------------------------------------------
#   N = 5, m = l = 1, g as above.  Relative joint angles q1..q5; absolute
#   link angle a_k = q1 + ... + qk from the downward vertical; mass k at
#   x_k = sum_{j<=k} l sin(a_j), y_k = -sum_{j<=k} l cos(a_j); massless
#   links, mass m at the end of every link, gravity along -y.
#
#   Lagrangian in absolute angles (1-based i, j):
#     v_k = sum_{j<=k} l a_j' (cos a_j, sin a_j)
#     T = (1/2) sum_{i,j} c_ij cos(a_i - a_j) a_i' a_j',
#         c_ij = m l^2 (N - max(i,j) + 1)   [number of masses beyond both]
#     V = -m g l sum_i (N - i + 1) cos(a_i)
#   Euler-Lagrange equations:
#     sum_j c_ij cos(a_i - a_j) a_j''
#        = - sum_j c_ij sin(a_i - a_j) a_j'^2 - m g l (N - i + 1) sin(a_i)
#   (the a_i' a_j' terms from d/dt dT/da_i' and dT/da_i cancel).  The 5x5
#   symmetric positive definite system is solved by Gaussian elimination
#   in mpmath at every right-hand side; then, since a = L q with L the
#   lower-triangular matrix of ones,
#     q1'' = a1'',  qi'' = ai'' - a(i-1)''  (i = 2..5),  ai' = q1'+...+qi'.
#   sin(a_i - a_j), cos(a_i - a_j) are formed from sin/cos of the a_i.
#   Initial state q = (1.0, 0.1, 0.1, 0.1, 0.1), q' = 0.
#   Rows t = 0, 1, ..., 10 (11 rows), columns t,q1..q5,q1'..q5'.
#
#   Integrator: fixed-step, fixed-order Gragg-Bulirsch-Stoer written here
#   (gbs_step).  Per step H: Gragg's modified midpoint rule with n_j = 2j
#   substeps, j = 1..k, whose end value has an error expansion in even
#   powers of H/n_j; Aitken-Neville extrapolation in (H/n_j)^2 to zero
#   gives order 2k; 1 + k^2 right-hand-side evaluations per step.
#     run A: mp.dps = 50, H = 1/100, k = 12 (order 24), 1000 steps
#     run B: mp.dps = 60, H = 1/160, k = 11 (order 22), 1600 steps
#   chain5.csv is written from run B (higher precision, smaller step).
#   (A trial over 10 steps of H = 1/50 vs 20 of H = 1/100 showed
#   6e-40 difference, i.e. ~1e-47 per step at H = 1/100.)
#
#   Self-checks (results of the recorded run):
#   * the hand-derived equations vs the Lagrangian itself: at three states
#     (the initial state and two arbitrary ones with nonzero velocities)
#     the residual d/dt(dL/dq_i') - dL/dq_i, with every partial derivative
#     of L = T - V (built directly from the Cartesian positions and
#     velocities) taken numerically by mpmath.diff and q'' from the
#     equations above:  max 7.7e-49      (required < 1e-30)
#   * (a) total energy T + V, computed from the Cartesian positions and
#     velocities (not from the mass matrix), relative to E(0), all rows:
#       run A max 1.9e-37, run B max 4.0e-41   (required < 1e-28)
#   * (b) run A vs run B (different dps, step and order), all rows and
#     all 10 state components:
#       max |A - B| = 6.4e-36 (t = 7); <= 7e-41 up to t = 2, <= 7e-38 up
#       to t = 5                               (required < 1e-25)
#   The printed 25 significant digits are therefore far inside the
#   verified accuracy (the largest magnitude in the file is ~3.7, so 25
#   digits means ~1e-25 absolute at most).
#
import sys
import time

import mpmath
from mpmath import mp, mpf
from mpmath.libmp import to_str

OUTDIR = __file__.rsplit("/", 1)[0] if "/" in __file__ else "."


# ---------------------------------------------------------------------------
# formatting
# ---------------------------------------------------------------------------
SIG = 25


def fmt(x):
    """Scientific notation, SIG significant digits, correctly rounded."""
    x = mpf(x)
    if x == 0:
        return "0." + "0" * (SIG - 1) + "e+0"
    return to_str(x._mpf_, SIG, strip_zeros=False, min_fixed=1, max_fixed=0,
                  show_zero_exponent=True)


def write_csv(name, header, rows):
    text = header + "\n" + "".join(",".join(r) + "\n" for r in rows)
    with open(OUTDIR + "/" + name, "w", newline="\n") as f:
        f.write(text)


def log(*a):
    print(*a)
    sys.stdout.flush()


# ---------------------------------------------------------------------------
# generic fixed-step Gragg-Bulirsch-Stoer integrator (fixed order)
# ---------------------------------------------------------------------------
def gbs_step(f, y, H, k):
    """One step of size H for y' = f(y) (autonomous).

    Modified midpoint rule with n_j = 2j substeps (j = 1..k); the final
    value has an asymptotic error expansion in even powers of h = H/n_j
    (Gragg), so Aitken-Neville extrapolation in h^2 to h = 0 over the k
    values gives a method of order 2k.  Cost 1 + k^2 evaluations of f."""
    dim = len(y)
    f0 = f(y)
    T = []  # T[j] = extrapolation row j (list of vectors)
    for j in range(1, k + 1):
        n = 2 * j
        h = H / n
        z0 = y
        z1 = [y[i] + h * f0[i] for i in range(dim)]
        h2 = 2 * h
        for _ in range(n - 1):
            fz = f(z1)
            z0, z1 = z1, [z0[i] + h2 * fz[i] for i in range(dim)]
        row = [z1]
        for i in range(1, j):
            r = (mpf(n) / (2 * (j - i))) ** 2 - 1
            prev = T[j - 2][i - 1]
            cur = row[i - 1]
            row.append([cur[d] + (cur[d] - prev[d]) / r for d in range(dim)])
        T.append(row)
    return T[k - 1][k - 1]


def gbs_integrate(f, y0, H_inv, k, t_out_steps):
    """Integrate with step H = 1/H_inv; return the state after each number
    of steps listed in t_out_steps (increasing)."""
    H = mpf(1) / H_inv
    y = list(y0)
    out = []
    done = 0
    for target in t_out_steps:
        while done < target:
            y = gbs_step(f, y, H, k)
            done += 1
        out.append(list(y))
    return out


# ---------------------------------------------------------------------------
# 1. simple pendulum, closed form
# ---------------------------------------------------------------------------
def pendulum():
    mp.dps = 50
    g = mpf(9.81)          # exact binary64 value of 9.81
    l = mpf(1)
    th0 = mpf(1)
    w = mpmath.sqrt(g / l)
    k = mpmath.sin(th0 / 2)
    m = k * k
    K = mpmath.ellipk(m)

    def closed(t):
        u = K - w * t
        sn, cn = mpmath.ellipfun("sn", u, m=m), mpmath.ellipfun("cn", u, m=m)
        theta = 2 * mpmath.asin(k * sn)
        thetad = -2 * k * w * cn
        return theta, thetad

    def energy(th, thd):
        return thd * thd / 2 - (g / l) * mpmath.cos(th)

    E0 = energy(th0, mpf(0))
    ts = [mpf(i) / 4 for i in range(41)]
    vals = [closed(t) for t in ts]

    # self-check 1: energy
    max_dE = max(abs(energy(th, thd) - E0) for th, thd in vals)
    # self-check 2: numerical derivative of theta(t) vs closed-form theta'
    max_dd = max(abs(mpmath.diff(lambda s: closed(s)[0], t) - thd)
                 for t, (th, thd) in zip(ts, vals))
    # self-check 3: initial condition
    ic = max(abs(vals[0][0] - th0), abs(vals[0][1]))
    # self-check 4: independent numerical integration (GBS, order 24)
    f = lambda y: [y[1], -(g / l) * mpmath.sin(y[0])]
    num = [[th0, mpf(0)]] + gbs_integrate(f, [th0, mpf(0)], 100, 12,
                                          [25 * i for i in range(1, 41)])
    max_num = max(max(abs(a - b) for a, b in zip(nv, cv))
                  for nv, cv in zip(num, vals))
    log("pendulum: max |E - E0|            = %s" % mpmath.nstr(max_dE, 3))
    log("pendulum: max |diff(theta) - theta'| = %s" % mpmath.nstr(max_dd, 3))
    log("pendulum: initial-condition error   = %s" % mpmath.nstr(ic, 3))
    log("pendulum: max |GBS - closed form|   = %s" % mpmath.nstr(max_num, 3))
    assert max_dE < mpf(10) ** -35, "energy check failed"
    assert max_dd < mpf(10) ** -30, "derivative check failed"
    assert max_num < mpf(10) ** -30, "numerical integration check failed"

    rows = []
    for i, (th, thd) in enumerate(vals):
        if i == 0:
            thd = mpf(0)   # exact: cn(K) = 0; numerically ~1e-50
        rows.append([repr(i / 4), fmt(th), fmt(thd)])
    write_csv("pendulum.csv", "t,theta,theta'", rows)


# ---------------------------------------------------------------------------
# 2. planar chain of N point masses, relative joint angles
# ---------------------------------------------------------------------------
N = 5


def chain_params():
    return mpf(1), mpf(1), mpf(9.81)   # m, l, g  (g = binary64 value of 9.81)


def chain_rhs(y):
    """y = (q1..qN, q1'..qN').  Lagrange equations in absolute angles
    a_i = q_1 + ... + q_i (1-based i, j, c_ij = m l^2 (N - max(i,j) + 1)):

      sum_j c_ij cos(a_i - a_j) a_j''
        = - sum_j c_ij sin(a_i - a_j) a_j'^2 - m g l (N - i + 1) sin(a_i)

    then q_1'' = a_1'', q_i'' = a_i'' - a_{i-1}''."""
    m, l, g = chain_params()
    q = y[:N]
    qd = y[N:]
    a = []
    s = mpf(0)
    for x in q:
        s += x
        a.append(s)
    ad = []
    s = mpf(0)
    for x in qd:
        s += x
        ad.append(s)
    S = [mpmath.sin(x) for x in a]
    C = [mpmath.cos(x) for x in a]
    ml2 = m * l * l
    A = [[None] * N for _ in range(N)]
    b = [None] * N
    for i in range(N):          # 0-based: N - max(i,j) + 1 -> N - max(i,j)
        r = mpf(0)
        for j in range(N):
            c = ml2 * (N - max(i, j))
            A[i][j] = c * (C[i] * C[j] + S[i] * S[j])      # c cos(a_i - a_j)
            r -= c * (S[i] * C[j] - C[i] * S[j]) * ad[j] ** 2
        r -= m * g * l * (N - i) * S[i]
        b[i] = r
    # Gaussian elimination; the mass matrix is symmetric positive definite.
    for kk in range(N):
        p = A[kk][kk]
        for i in range(kk + 1, N):
            fct = A[i][kk] / p
            for j in range(kk + 1, N):
                A[i][j] -= fct * A[kk][j]
            b[i] -= fct * b[kk]
    add = [None] * N
    for i in reversed(range(N)):
        s = b[i]
        for j in range(i + 1, N):
            s -= A[i][j] * add[j]
        add[i] = s / A[i][i]
    qdd = [add[0]] + [add[i] - add[i - 1] for i in range(1, N)]
    return list(qd) + qdd


def chain_cartesian(q, qd):
    """Positions and velocities of the masses straight from the geometry."""
    m, l, g = chain_params()
    x = y = vx = vy = mpf(0)
    a = ad = mpf(0)
    P = []
    for i in range(N):
        a += q[i]
        ad += qd[i]
        x += l * mpmath.sin(a)
        y -= l * mpmath.cos(a)
        vx += l * mpmath.cos(a) * ad
        vy += l * mpmath.sin(a) * ad
        P.append((x, y, vx, vy))
    return P


def chain_energy(state):
    """T + V computed from Cartesian positions/velocities (independent of
    the mass matrix used in chain_rhs)."""
    m, l, g = chain_params()
    E = mpf(0)
    for x, y, vx, vy in chain_cartesian(state[:N], state[N:]):
        E += m * (vx * vx + vy * vy) / 2 + m * g * y
    return E


def chain_lagrangian(*z):
    m, l, g = chain_params()
    L = mpf(0)
    for x, y, vx, vy in chain_cartesian(z[:N], z[N:]):
        L += m * (vx * vx + vy * vy) / 2 - m * g * y
    return L


def lagrange_residual(state):
    """max_i | d/dt dL/dq_i' - dL/dq_i | with q'' from chain_rhs, all the
    partial derivatives of the Cartesian Lagrangian taken numerically with
    mpmath.diff (independent of the hand-derived equations)."""
    acc = chain_rhs(state)[N:]
    qd = state[N:]
    res = []
    for i in range(N):
        dd = [0] * (2 * N)
        dd[i] = 1
        r = -mpmath.diff(chain_lagrangian, state, tuple(dd))
        for j in range(N):
            o = [0] * (2 * N)
            o[N + i] += 1
            o[j] += 1
            r += mpmath.diff(chain_lagrangian, state, tuple(o)) * qd[j]
            o = [0] * (2 * N)
            o[N + i] += 1
            o[N + j] += 1
            r += mpmath.diff(chain_lagrangian, state, tuple(o)) * acc[j]
        res.append(abs(r))
    return max(res)


def chain_y0(decimal=False):
    # binary64 values of the decimal initial data (see header);
    # decimal=True gives the exact decimal 0.1 instead (sensitivity study)
    c = mpf("0.1") if decimal else mpf(0.1)
    return [mpf(1), c, c, c, c] + [mpf(0)] * N


def chain_run(dps, H_inv, k, decimal=False):
    mp.dps = dps
    y0 = chain_y0(decimal)
    t0 = time.time()
    out = [y0] + gbs_integrate(chain_rhs, y0, H_inv, k,
                               [H_inv * i for i in range(1, 11)])
    log("chain: run dps=%d H=1/%d order=%d took %.1f s"
        % (dps, H_inv, 2 * k, time.time() - t0))
    return out


def chain():
    # equation check against the numerically differentiated Lagrangian
    mp.dps = 50
    rng_states = [
        chain_y0(),
        [mpf(x) / 7 for x in (3, -5, 2, 9, -4, 6, -11, 1, 8, -2)],
        [mpf(x) / 3 for x in (-4, 7, 1, -6, 5, 2, 9, -8, 3, 10)],
    ]
    maxres = max(lagrange_residual(s) for s in rng_states)
    log("chain: Lagrange residual (numerical diff of L) = %s"
        % mpmath.nstr(maxres, 3))
    assert maxres < mpf(10) ** -30

    runA = chain_run(50, 100, 12)
    runB = chain_run(60, 160, 11)

    mp.dps = 60
    E0 = chain_energy(runB[0])
    maxE = mpf(0)
    for name, run in (("A", runA), ("B", runB)):
        mE = max(abs((chain_energy(st) - E0) / E0) for st in run)
        log("chain: run %s max relative energy error = %s"
            % (name, mpmath.nstr(mE, 3)))
        maxE = max(maxE, mE)
    maxdiff = mpf(0)
    for sa, sb in zip(runA, runB):
        maxdiff = max(maxdiff, max(abs(x - y) for x, y in zip(sa, sb)))
    log("chain: max relative energy error   = %s" % mpmath.nstr(maxE, 3))
    log("chain: max |run A - run B|         = %s" % mpmath.nstr(maxdiff, 3))
    for i, (sa, sb) in enumerate(zip(runA, runB)):
        log("   t=%2d  |A-B| = %s   relE = %s" % (
            i, mpmath.nstr(max(abs(x - y) for x, y in zip(sa, sb)), 3),
            mpmath.nstr(abs((chain_energy(sb) - E0) / E0), 3)))
    assert maxE < mpf(10) ** -28
    assert maxdiff < mpf(10) ** -25

    rows = []
    for i, st in enumerate(runB):
        rows.append([repr(float(i))] + [fmt(x) for x in st])
    write_csv("chain5.csv", "t,q1,q2,q3,q4,q5,q1',q2',q3',q4',q5'", rows)
    return runB


def ic_sensitivity():
    """Optional (not part of the CSV generation): how much the rows change
    if the initial angles 0.1 are the exact decimal 0.1 instead of the
    binary64 value 0.1000000000000000055511151231257827...  Compares a
    decimal-IC run (settings of run A) with the run-B reference."""
    ref = chain_run(60, 160, 11)
    dec = chain_run(50, 100, 12, decimal=True)
    mp.dps = 60
    for i, (sa, sb) in enumerate(zip(ref, dec)):
        log("   t=%2d  max |binary64-IC - decimal-IC| = %s" % (
            i, mpmath.nstr(max(abs(x - y) for x, y in zip(sa, sb)), 3)))


if __name__ == "__main__":
    if "--ic-sensitivity" in sys.argv:
        ic_sensitivity()
        sys.exit(0)
    T0 = time.time()
    log("mpmath %s, backend %s" % (mpmath.__version__, mpmath.libmp.BACKEND))
    pendulum()
    chain()
    log("total run time %.1f s" % (time.time() - T0))
