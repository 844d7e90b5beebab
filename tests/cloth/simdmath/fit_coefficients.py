#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Refits the float coefficients of runtime/src/cloth/cloth_simd_math.h and prints them.

Not run by the build or the tests (which check the header's accuracy against libm directly);
kept so that a function's domain or degree can be changed and refitted. Needs numpy and mpmath
(Debian: python3-numpy python3-mpmath). Each fit is a weighted minimax fit on Chebyshev nodes by
Lawson's iteration (iteratively reweighted least squares); polynomial coefficients are rounded to
float one at a time, lowest power first, the others refitted after each rounding. The rational
tail of the normal quantile is linearised (Loeb) around the previous denominator.
"""
import math

import mpmath as mp
import numpy as np

mp.mp.dps = 40


def f32(v):
    return float(np.float32(v))


def nodes(a, b, n=3000):
    k = np.arange(n)
    return 0.5 * (a + b) + 0.5 * (b - a) * np.cos(np.pi * (k + 0.5) / n)


def exact(fn, xs):
    return np.array([float(fn(mp.mpf(float(x)))) for x in xs])


def lawson(a, f, w, iters):
    u = np.ones(a.shape[0]) / a.shape[0]
    best = None
    for _ in range(iters):
        s = np.sqrt(u) * w
        c, *_ = np.linalg.lstsq(a * s[:, None], f * s, rcond=None)
        e = np.abs(w * (a @ c - f))
        if best is None or e.max() < best[0]:
            best = (e.max(), c.copy())
        u = u * e
        u /= u.sum()
    return best[1]


def polynomial(v, f, w, degree, iters=400):
    """Float coefficients c_0..c_degree of sum c_k v^k ~ f, minimising max |w (approx - f)|."""
    a = np.stack([v**k for k in range(degree + 1)], axis=1)
    coeffs = []
    for k in range(degree + 1):
        resid = f - (a[:, :k] @ np.array(coeffs) if k else 0)
        coeffs.append(f32(lawson(a[:, k:], resid, w, iters)[0]))
    return coeffs, np.abs(w * (a @ np.array(coeffs) - f)).max()


def rational(v, f, w, n, m, outer=30, iters=200):
    """P (degree n) / Q (degree m, Q(0) = 1) ~ f, minimising max |w (P / Q - f)|."""
    q_old = np.ones_like(v)
    best = None
    for _ in range(outer):
        a = np.concatenate([np.stack([v**k for k in range(n + 1)], 1),
                            np.stack([-f * v**k for k in range(1, m + 1)], 1)], 1)
        c = lawson(a, f, w / np.abs(q_old), iters)
        p = sum(c[k] * v**k for k in range(n + 1))
        q = 1 + sum(c[n + k] * v**k for k in range(1, m + 1))
        err = np.abs(w * (p / q - f)).max()
        if best is None or err < best[0]:
            best = (err, c)
        q_old = q
    return [f32(x) for x in best[1][:n + 1]], [1.0] + [f32(x) for x in best[1][n + 1:]], best[0]


def show(name, coeffs, err):
    print(f"{name}: weighted max error {err:.3e}; coefficients from the highest power down:")
    print("   " + ", ".join(f"{c:.9e}" for c in reversed(coeffs)))


def main():
    # exp: e^r = 1 + r + r^2 P(r), |r| <= ln2 / 2; relative error.
    xs = nodes(-math.log(2) / 2 * 1.0001, math.log(2) / 2 * 1.0001)
    xs = xs[xs != 0]
    show("exp P", *polynomial(xs, exact(lambda r: (mp.exp(r) - 1 - r) / r**2, xs),
                              xs**2 / np.exp(xs), 4))
    # log: ln(1 + f) = f - f^2 / 2 + f^3 P(f), f in [sqrt(1/2) - 1, sqrt(2) - 1]; relative.
    xs = nodes((math.sqrt(0.5) - 1) * 1.0001, (math.sqrt(2) - 1) * 1.0001)
    xs = xs[xs != 0]
    show("log P", *polynomial(xs, exact(lambda f: (mp.log1p(f) - f + f**2 / 2) / f**3, xs),
                              np.abs(xs**3 / np.log1p(xs)), 7))
    # sin r = r + r^3 S(r^2), cos r = 1 - r^2 / 2 + r^4 C(r^2), |r| <= pi/4; absolute.
    xs = nodes(0, math.pi / 4 * 1.0001)
    show("sin S", *polynomial(xs * xs, exact(lambda r: (mp.sin(r) - r) / r**3, xs), xs**3, 2))
    show("cos C", *polynomial(xs * xs, exact(lambda r: (mp.cos(r) - 1 + r**2 / 2) / r**4, xs),
                              xs**4, 2))
    # atan a = a + a^3 T(a^2), a in [0, 1]; absolute.
    xs = nodes(0, 1, 4000)
    show("atan T", *polynomial(xs * xs, exact(lambda a: (mp.atan(a) - a) / a**3, xs), xs**3, 8))
    # asin s = s + s^3 A(s^2), s in [0, 1/2]; relative.
    xs = nodes(0, 0.5 * 1.0001)
    show("asin A", *polynomial(xs * xs, exact(lambda s: (mp.asin(s) - s) / s**3, xs),
                               xs**3 / np.arcsin(xs), 4))
    # erfc a = e^-a^2 P(t), t = 2 / (2 + a), a in [0, 10.5]; relative.
    ts = nodes(2 / 12.5, 1, 4000)
    r = exact(lambda t: mp.erfc(2 / t - 2) * mp.exp((2 / t - 2)**2), ts)
    show("erfc P", *polynomial(ts, r, 1 / r, 9))

    # Normal quantile: Phi^-1(p) = x G(w), x = 2p - 1, w = -ln(1 - x^2); absolute error in z.
    def g(w):
        x = mp.sqrt(-mp.expm1(-w))
        return mp.sqrt(2) * mp.erfinv(x) / x

    def weight(ws):
        return np.array([float(mp.sqrt(-mp.expm1(-mp.mpf(float(w))))) for w in ws])

    ws = nodes(1e-6, 5.0001)
    show("quantile central G(w - 2.5)",
         *polynomial(ws - 2.5, exact(g, ws), weight(ws), 8, iters=300))
    ws = nodes(4.9999, 39.5, 2000)
    num, den, err = rational(np.sqrt(ws) - 3, exact(g, ws), weight(ws), 5, 4)
    show("quantile tail numerator (sqrt(w) - 3)", num, err)
    show("quantile tail denominator", den, err)


if __name__ == "__main__":
    main()
