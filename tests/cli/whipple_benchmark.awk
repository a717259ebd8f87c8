# The Whipple bicycle's lean-and-steer eigenvalue nearest a start s0, at
# forward speed v, from the linearized equations that Meijaard,
# Papadopoulos, Ruina and Schwab published (Proc. R. Soc. A 463 (2007)
# 1955-1982, section 5.3), M q'' + v C1 q' + (g K0 + v^2 K2) q = 0 with
# q = (lean, steer): a root of the quartic det(M s^2 + v C1 s + g K0 +
# v^2 K2), by Newton's method in complex arithmetic.  Independent of eomc:
# the published matrices, not a model eomc derived.
# usage: awk -v v=SPEED -v sr=RE0 -v si=IM0 -f whipple_benchmark.awk
# prints: RE IM
function mul(p, q, r,   i, j) {
    for (i = 0; i <= 4; i++)
        r[i] = 0
    for (i = 0; i <= 2; i++)
        for (j = 0; j <= 2; j++)
            r[i + j] += p[i] * q[j]
}
BEGIN {
    g = 9.81
    M11 = 80.81722; M12 = 2.31941332208709; M21 = M12; M22 = 0.29784188199686
    C11 = 0; C12 = 33.86641391492494; C21 = -0.85035641456978; C22 = 1.68540397397560
    K011 = -80.95; K012 = -2.59951685249872; K021 = K012; K022 = -0.80329488458618
    K211 = 0; K212 = 76.59734589573222; K221 = 0; K222 = 2.65431523794604
    # each entry of M s^2 + v C1 s + K by power of s: [0] .. [2]
    a[0] = g * K011 + v * v * K211; a[1] = v * C11; a[2] = M11
    b[0] = g * K012 + v * v * K212; b[1] = v * C12; b[2] = M12
    c[0] = g * K021 + v * v * K221; c[1] = v * C21; c[2] = M21
    d[0] = g * K022 + v * v * K222; d[1] = v * C22; d[2] = M22
    mul(a, d, ad)
    mul(b, c, bc)
    for (i = 0; i <= 4; i++)
        P[i] = ad[i] - bc[i]
    xr = sr; xi = si
    for (it = 0; it < 60; it++) {
        pr = P[4]; pi = 0; dr = 0; di = 0 # P(x) and P'(x) by Horner
        for (i = 3; i >= 0; i--) {
            t = dr * xr - di * xi + pr; di = dr * xi + di * xr + pi; dr = t
            t = pr * xr - pi * xi + P[i]; pi = pr * xi + pi * xr; pr = t
        }
        den = dr * dr + di * di
        if (den == 0)
            break
        xr -= (pr * dr + pi * di) / den
        xi -= (pi * dr - pr * di) / den
    }
    printf "%.17g %.17g\n", xr, xi
}
