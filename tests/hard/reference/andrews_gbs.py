# An independent high-precision solution of the test set's equations
# (testset.py's transcription of andfunc), as the index-1 ODE
# [M G^T; G 0][q''; lam] = [f; -b], b = (dG/dt) q' (analytic), by fixed-step
# Gragg-Bulirsch-Stoer extrapolation in mpmath.
import sys, mpmath as mp
import andrews_testset as T
from andrews_testset import parts
mp.mp.dps = int(sys.argv[2]) if len(sys.argv) > 2 else 32
P = T.P
rr, d, ss, e, zt, zf, u = P['rr'], P['d'], P['ss'], P['e'], P['zt'], P['zf'], P['u']

def bvec(y, v):
    be, th, ga, ph, de, om, ep = y
    bp, tp, gp, pp, dp, op, epp = v
    cb, sb = mp.cos(be), mp.sin(be); cbt, sbt = mp.cos(be+th), mp.sin(be+th)
    c1 = -rr*cb*bp**2 + d*cbt*(bp+tp)**2
    s1 = -rr*sb*bp**2 + d*sbt*(bp+tp)**2
    return [c1 + ss*mp.sin(ga)*gp**2,
            s1 - ss*mp.cos(ga)*gp**2,
            c1 + e*mp.sin(ph+de)*(pp+dp)**2 + zt*mp.cos(de)*dp**2,
            s1 - e*mp.cos(ph+de)*(pp+dp)**2 + zt*mp.sin(de)*dp**2,
            c1 + zf*mp.cos(om+ep)*(op+epp)**2 + u*mp.sin(ep)*epp**2,
            s1 + zf*mp.sin(om+ep)*(op+epp)**2 - u*mp.cos(ep)*epp**2]

def kkt(y, v):
    m, ff, gp, g = parts(y, v)
    return T.solve(m, ff, gp, bvec(y, v))

def f(x):
    a, _ = kkt(x[:7], x[7:])
    return x[7:] + a

def add(x, h, y): return [x[i] + h*y[i] for i in range(14)]

def gbs_step(x, H, L):
    Tab = []
    for j in range(1, L+1):
        n = 2*j; h = H/n
        z0 = x; z1 = add(x, h, f(x))
        for k in range(1, n):
            z0, z1 = z1, add(z0, 2*h, f(z1))
        row = [z1]
        for k in range(1, j):
            fac = mp.mpf(n)**2/mp.mpf(n - 2*k)**2 - 1
            prev = Tab[-1][k-1]
            row.append([row[k-1][i] + (row[k-1][i] - prev[i])/fac for i in range(14)])
        Tab.append(row)
    return Tab[-1][-1], max(abs(Tab[-1][-1][i] - Tab[-1][-2][i]) for i in range(14))

if __name__ == '__main__':
    N = int(sys.argv[1]); L = int(sys.argv[3]) if len(sys.argv) > 3 else 8
    q0 = ['-0.0617138900142764496358948458001', '0', '0.455279819163070380255912382449',
          '0.222668390165885884674473185609', '0.487364979543842550225598953530',
          '-0.222668390165885884674473185609', '1.23054744454982119249735015568']
    x = [mp.mpf(s) for s in q0] + [mp.mpf(0)]*7
    H = mp.mpf('0.03')/N; worst = 0
    for k in range(N):
        x, est = gbs_step(x, H, L); worst = max(worst, est)
    a, lam = kkt(x[:7], x[7:])
    g = parts(x[:7], x[7:])[3]
    print('N', N, 'L', L, 'dps', mp.mp.dps, 'worst step estimate', mp.nstr(worst, 3), 'max|g|', mp.nstr(max(abs(v) for v in g), 3))
    for v in x + a + lam:
        print(mp.nstr(v, 25))
