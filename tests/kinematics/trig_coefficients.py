#!/usr/bin/env python3
"""Coefficients of the sine and cosine kernels of kinematics/src/trig.h, derived with mpmath.

sin x = x + x^3 P(x^2), cos x = 1 - x^2/2 + x^4 Q(x^2) on |x| <= pi/4: P and Q minimise the
largest relative error of sin and cos there (Lawson's iteratively reweighted least squares on
Chebyshev nodes, which converges to the minimax fit).  Prints the coefficients rounded to the
precision (as C hexadecimal literals, the form trig.h holds them in) and the relative error of the
fit with those rounded coefficients in exact arithmetic.  Not run by the tests (it takes a few
seconds and needs mpmath); test_trig checks the kernels as built against long double."""
import struct

import mpmath as mp

mp.mp.dps = 50
X = mp.pi / 4
NODES = 300

def fit(kind, n):
    xs = [X * (1 + mp.cos(mp.pi * (k + mp.mpf(0.5)) / NODES)) / 2 for k in range(NODES)]
    rows, rhs = [], []
    for x in xs:
        z = x * x
        if kind == "sin":
            f = mp.sin(x)
            base, lead = x, x ** 3   # f = base + lead P(z)
        else:
            f = mp.cos(x)
            base, lead = 1 - z / 2, z * z
        rows.append([lead * z ** j / f for j in range(n)])
        rhs.append((f - base) / f)
    w = [mp.mpf(1)] * NODES
    for _ in range(60):
        A = mp.matrix([[mp.sqrt(w[i]) * a for a in rows[i]] for i in range(NODES)])
        b = mp.matrix([mp.sqrt(w[i]) * rhs[i] for i in range(NODES)])
        c = mp.qr_solve(A, b)[0]
        err = [abs(sum(rows[i][j] * c[j] for j in range(n)) - rhs[i]) for i in range(NODES)]
        s = sum(w[i] * err[i] for i in range(NODES))
        w = [w[i] * err[i] / s for i in range(NODES)]
    return [c[j] for j in range(n)]

def rel_error(kind, c):
    worst = mp.mpf(0)
    for k in range(1, 4001):
        x = X * k / 4000
        z = x * x
        p = mp.polyval(c[::-1], z)
        if kind == "sin":
            approx, f = x + x ** 3 * p, mp.sin(x)
        else:
            approx, f = 1 - z / 2 + z * z * p, mp.cos(x)
        worst = max(worst, abs(approx / f - 1))
    return worst

for prec, n_sin, n_cos in (("double", 6, 6), ("float", 3, 3)):
    for kind, n in (("sin", n_sin), ("cos", n_cos)):
        c = fit(kind, n)
        if prec == "float":
            c = [mp.mpf(struct.unpack("f", struct.pack("f", float(v)))[0]) for v in c]
        else:
            c = [mp.mpf(float(v)) for v in c]
        print(prec, kind, "relative error %.3g" % float(rel_error(kind, c)))
        for v in c:
            print("   ", float(v).hex())

# The Cody-Waite split of pi/2 (trig.h's TRIG_PIO2_*): two parts of few enough bits that k times
# each is exact over the reduction's range of k, then the rest rounded to the precision.
def round_bits(x, bits):
    e = mp.floor(mp.log(abs(x), 2))
    scale = mp.mpf(2) ** (bits - 1 - e)
    return mp.nint(x * scale) / scale

for prec, bits, full in (("double", 33, 53), ("float", 13, 24)):
    p1 = round_bits(mp.pi / 2, bits)
    p2 = round_bits(mp.pi / 2 - p1, bits)
    p3 = round_bits(mp.pi / 2 - p1 - p2, full)
    print(prec, "pi/2 split:", float(p1).hex(), float(p2).hex(), float(p3).hex())
