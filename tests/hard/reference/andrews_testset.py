# The test set's andrews equations (src/Ex_andrews.f, andfunc), transcribed,
# in mpmath: M q'' = f - G^T lam, with g'' = 0 (G q'' + (dG/dt) q' = 0).
import mpmath as mp, random, subprocess, sys
mp.mp.dps = 40
P = dict(m1=.04325, m2=.00365, m3=.02373, m4=.00706, m5=.07050, m6=.00706, m7=.05498,
         xa=-.06934, ya=-.00227, xb=-0.03635, yb=.03273, xc=.014, yc=.072, c0=4530,
         i1=2.194e-6, i2=4.410e-7, i3=5.255e-6, i4=5.667e-7, i5=1.169e-5, i6=5.667e-7, i7=1.912e-5,
         d=28e-3, da=115e-4, e=2e-2, ea=1421e-5, rr=7e-3, ra=92e-5, l0=7785e-5,
         ss=35e-3, sa=1874e-5, sb=1043e-5, sc=18e-3, sd=2e-2, ta=2308e-5, tb=916e-5,
         u=4e-2, ua=1228e-5, ub=449e-5, zf=2e-2, zt=4e-2, fa=1421e-5, mom=33e-3)
P = {k: mp.mpf(repr(v)) for k, v in P.items()}
globals().update(P)

def parts(y, yp):
    sibe, sith, siga, siph, side, siom, siep = [mp.sin(x) for x in y]
    cobe, coth, coga, coph, code, coom, coep = [mp.cos(x) for x in y]
    sibeth, siphde, siomep = mp.sin(y[0]+y[1]), mp.sin(y[3]+y[4]), mp.sin(y[5]+y[6])
    cobeth, cophde, coomep = mp.cos(y[0]+y[1]), mp.cos(y[3]+y[4]), mp.cos(y[5]+y[6])
    bep, thp, php, dep, omp, epp = yp[0], yp[1], yp[3], yp[4], yp[5], yp[6]
    m = mp.zeros(7, 7)
    m[0,0] = m1*ra**2 + m2*(rr**2-2*da*rr*coth+da**2) + i1 + i2
    m[1,0] = m2*(da**2-da*rr*coth) + i2
    m[1,1] = m2*da**2 + i2
    m[2,2] = m3*(sa**2+sb**2) + i3
    m[3,3] = m4*(e-ea)**2 + i4
    m[4,3] = m4*((e-ea)**2+zt*(e-ea)*siph) + i4
    m[4,4] = m4*(zt**2+2*zt*(e-ea)*siph+(e-ea)**2) + m5*(ta**2+tb**2) + i4 + i5
    m[5,5] = m6*(zf-fa)**2 + i6
    m[6,5] = m6*((zf-fa)**2-u*(zf-fa)*siom) + i6
    m[6,6] = m6*((zf-fa)**2-2*u*(zf-fa)*siom+u**2) + m7*(ua**2+ub**2) + i6 + i7
    for j in range(1, 7):
        for i in range(j):
            m[i,j] = m[j,i]
    xd = sd*coga + sc*siga + xb
    yd = sd*siga - sc*coga + yb
    lang = mp.sqrt((xd-xc)**2 + (yd-yc)**2)
    force = - c0 * (lang - l0)/lang
    fx = force * (xd-xc); fy = force * (yd-yc)
    ff = [mom - m2*da*rr*thp*(thp+2*bep)*sith,
          m2*da*rr*bep**2*sith,
          fx*(sc*coga - sd*siga) + fy*(sd*coga + sc*siga),
          m4*zt*(e-ea)*dep**2*coph,
          - m4*zt*(e-ea)*php*(php+2*dep)*coph,
          - m6*u*(zf-fa)*epp**2*coom,
          m6*u*(zf-fa)*omp*(omp+2*epp)*coom]
    gp = mp.zeros(6, 7)
    gp[0,0] = - rr*sibe + d*sibeth; gp[0,1] = d*sibeth; gp[0,2] = - ss*coga
    gp[1,0] = rr*cobe - d*cobeth; gp[1,1] = - d*cobeth; gp[1,2] = - ss*siga
    gp[2,0] = - rr*sibe + d*sibeth; gp[2,1] = d*sibeth; gp[2,3] = - e*cophde; gp[2,4] = - e*cophde + zt*side
    gp[3,0] = rr*cobe - d*cobeth; gp[3,1] = - d*cobeth; gp[3,3] = - e*siphde; gp[3,4] = - e*siphde - zt*code
    gp[4,0] = - rr*sibe + d*sibeth; gp[4,1] = d*sibeth; gp[4,5] = zf*siomep; gp[4,6] = zf*siomep - u*coep
    gp[5,0] = rr*cobe - d*cobeth; gp[5,1] = - d*cobeth; gp[5,5] = - zf*coomep; gp[5,6] = - zf*coomep - u*siep
    g = [rr*cobe - d*cobeth - ss*siga - xb,
         rr*sibe - d*sibeth + ss*coga - yb,
         rr*cobe - d*cobeth - e*siphde - zt*code - xa,
         rr*sibe - d*sibeth + e*cophde - zt*side - ya,
         rr*cobe - d*cobeth - zf*coomep - u*siep - xa,
         rr*sibe - d*sibeth - zf*siomep + u*coep - ya]
    return m, ff, gp, g

def gp_of(y):
    return parts(y, [0]*7)[2]

def accel(y, yp):
    """q'', lambda from [M G^T; G 0][a; lam] = [f; -(dG/dt) q'] (dG/dt by a
    complex-free high-precision central difference along q')."""
    m, ff, gp, g = parts(y, yp)
    h = mp.mpf('1e-15')
    gpp = gp_of([y[i] + h*yp[i] for i in range(7)]); gpm = gp_of([y[i] - h*yp[i] for i in range(7)])
    Gdot = (gpp - gpm) / (2*h)
    b = Gdot * mp.matrix(yp)
    a, lam = solve(m, ff, gp, b)
    return a, lam, g

def solve(m, ff, gp, b):
    """q'', lambda from [M G^T; G 0][a; lam] = [f; -b]."""
    K = mp.zeros(13, 13); r = mp.zeros(13, 1)
    for i in range(7):
        for j in range(7):
            K[i,j] = m[i,j]
        r[i] = ff[i]
    for i in range(6):
        for j in range(7):
            K[7+i,j] = gp[i,j]; K[j,7+i] = gp[i,j]
        r[7+i] = -b[i]
    x = mp.lu_solve(K, r)
    return [x[i] for i in range(7)], [x[7+i] for i in range(6)]

if __name__ == '__main__':
    names = ['beta', 'theta', 'gamma', 'phi', 'dlt', 'omega', 'epsilon']
    q0 = ['-0.0617138900142764496358948458001', '0', '0.455279819163070380255912382449',
          '0.222668390165885884674473185609', '0.487364979543842550225598953530',
          '-0.222668390165885884674473185609', '1.23054744454982119249735015568']
    random.seed(int(sys.argv[1]) if len(sys.argv) > 1 else 1)
    states = [([float(x) for x in q0], [0.0]*7)]
    for k in range(8):
        q = [float(x) + random.uniform(-1, 1) for x in q0]
        v = [random.uniform(-2000, 2000) if k % 2 else random.uniform(-20, 20) for _ in range(7)]
        states.append((q, v))
    for q, v in states:
        args = [sys.argv[2] if len(sys.argv) > 2 else './andrews', '--accel']
        for i in range(7):
            args += ['--init', '%s=%.17g' % (names[i], q[i]), '--init', "%s'=%.17g" % (names[i], v[i])]
        out = subprocess.run(args, capture_output=True, text=True)
        vals = [float(l.split()[1]) for l in out.stdout.splitlines() if l.strip()]
        a, lam, g = accel([mp.mpf(x) for x in q], [mp.mpf(x) for x in v])
        err_a = max(abs(vals[i] - a[i]) for i in range(7)) / max(abs(x) for x in a)
        err_l = max(abs(vals[7+i] - lam[i]) for i in range(6)) / max(abs(x) for x in lam)
        print('state |v|max %8.3g |g|max %8.2g: rel err q'' %.2g, lambda %.2g (|q''|max %.3g, |lam|max %.3g)%s'
              % (max(abs(x) for x in v), max(abs(x) for x in g), err_a, err_l, max(abs(x) for x in a),
                 max(abs(x) for x in lam), ' STDERR:' + out.stderr.strip()[:200] if out.stderr.strip() else ''))
