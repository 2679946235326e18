"""Locating switching events inside a step on the step's dense output (numba).

Each contact has a directed event function w = sigma * s (sigma = +1 in stick, -1 in
slide); an event is w crossing 0 from below. Within an accepted step [t0, t0 + h] the
step loop knows w and dw/dt at both ends. Two cases are found:

* a sign change between the ends: bracketed at once;
* a graze: both ends negative, but the cubic Hermite model of w has an interior
  maximum close to zero. Then the true w on the dense output is maximised (golden
  section) and, if that maximum is >= 0, the crossing is bracketed before it. A
  stick->slide crossing near mu* can last well under a step and shows up only here.

The root is then refined by Brent's method on w(y(t)) to a time tolerance.

Event functions come in three kinds. KIND_SWITCH: w = sigma s_i with the switching
function of the contact's mode (model.switch_value). For a contact inside the hysteresis
band of its mode (kernel/switching.py) a rate is watched instead: KIND_REENTRY, a sliding
contact whose ds/dt under stick dynamics falls through 0 (it may stick again), w = -rate;
KIND_RISE, a stuck contact above the friction limit whose |k| starts to grow (it must
slide), w = +rate.
"""

import math

from .jit import kernel_jit
from .model import n_coords, stick_rate, switch_value
from .rosenbrock import dense_eval, dense_eval_contact

GOLDEN = 0.3819660112501051  # (3 - sqrt(5)) / 2
GRAZE_SCAN = 24  # golden-section iterations when a graze is suspected
BRENT_MAXITER = 100
KIND_SWITCH = 0
KIND_REENTRY = 1
KIND_RISE = 2
SAME_TIME = 1e-12  # [s] events closer than this count as one instant (Zeno guard)
SIMULTANEOUS = 1e-9  # [s] crossings this close are switched together
T_TOL_ABS = 1e-11  # [s] time tolerance of the event root finder


@kernel_jit
def directed_value(p, pts, modes, y0, y1, wk, s, i, sigma, kind, ybuf, fbuf):
    """Event function w_i of the given kind at fraction s of the last step (dense output).

    A switching function reads only the rigid-body coordinates and Z_i, so only those are
    interpolated (O(1)); a stick rate needs the whole state rate (O(N))."""
    if kind == KIND_SWITCH:
        dense_eval_contact(y0, y1, wk, s, ybuf, n_coords(p), i)
        return sigma * switch_value(p, pts, ybuf, i, modes[i])
    dense_eval(y0, y1, wk, s, ybuf)
    if kind == KIND_REENTRY:
        return -stick_rate(p, pts, modes, ybuf, i, fbuf)
    return stick_rate(p, pts, modes, ybuf, i, fbuf)


@kernel_jit
def hermite_max(w0, w1, d0, d1):
    """Largest value and its position of the cubic Hermite on [0, 1] with end values w0, w1
    and end slopes d0, d1 (slopes per unit of s). Only interior maxima are returned;
    (-inf, -1) if there is none."""
    # H(s) = w0 h00 + d0 h10 + w1 h01 + d1 h11; H'(s) = a s^2 + b s + c
    a = 6.0 * w0 + 3.0 * d0 - 6.0 * w1 + 3.0 * d1
    b = -6.0 * w0 - 4.0 * d0 + 6.0 * w1 - 2.0 * d1
    c = d0
    best = -math.inf
    best_s = -1.0
    roots = (0.0, 0.0)
    nroot = 0
    if abs(a) < 1e-300:
        if b != 0.0:
            roots = (-c / b, 0.0)
            nroot = 1
    else:
        disc = b * b - 4.0 * a * c
        if disc >= 0.0:
            sq = math.sqrt(disc)
            q = -0.5 * (b + math.copysign(sq, b))
            r1 = q / a
            r2 = c / q if q != 0.0 else r1
            roots = (r1, r2)
            nroot = 2
    for k in range(nroot):
        s = roots[k]
        if 0.0 < s < 1.0:
            h00 = 2 * s**3 - 3 * s**2 + 1
            h10 = s**3 - 2 * s**2 + s
            h01 = -2 * s**3 + 3 * s**2
            h11 = s**3 - s**2
            val = w0 * h00 + d0 * h10 + w1 * h01 + d1 * h11
            # a maximum has H'' = 2 a s + b < 0
            if 2.0 * a * s + b < 0.0 and val > best:
                best = val
                best_s = s
    return best, best_s


@kernel_jit
def find_graze(p, pts, modes, y0, y1, wk, i, sigma, w0, w1, d0, d1, ybuf, fbuf):
    """Fraction s in (0, 1] where w >= 0 inside a step whose ends are both negative,
    or -1 if the step holds no crossing. d0, d1 are dw/ds at the ends."""
    hmax, hs = hermite_max(w0, w1, d0, d1)
    if hs < 0.0:
        return -1.0
    # Suspect a graze only when the model rises at least halfway to zero from the higher end.
    if hmax < 0.5 * max(w0, w1):
        return -1.0
    # Golden-section maximisation of the true w around the Hermite maximum.
    lo = 0.0
    hi = 1.0
    x1 = lo + GOLDEN * (hi - lo)
    x2 = hi - GOLDEN * (hi - lo)
    f1 = directed_value(p, pts, modes, y0, y1, wk, x1, i, sigma, KIND_SWITCH, ybuf, fbuf)
    f2 = directed_value(p, pts, modes, y0, y1, wk, x2, i, sigma, KIND_SWITCH, ybuf, fbuf)
    fh = directed_value(p, pts, modes, y0, y1, wk, hs, i, sigma, KIND_SWITCH, ybuf, fbuf)
    if fh >= 0.0:
        return hs
    for _ in range(GRAZE_SCAN):
        if f1 >= 0.0:
            return x1
        if f2 >= 0.0:
            return x2
        if f1 > f2:
            hi = x2
            x2 = x1
            f2 = f1
            x1 = lo + GOLDEN * (hi - lo)
            f1 = directed_value(p, pts, modes, y0, y1, wk, x1, i, sigma, KIND_SWITCH, ybuf, fbuf)
        else:
            lo = x1
            x1 = x2
            f1 = f2
            x2 = hi - GOLDEN * (hi - lo)
            f2 = directed_value(p, pts, modes, y0, y1, wk, x2, i, sigma, KIND_SWITCH, ybuf, fbuf)
    if f1 >= 0.0:
        return x1
    if f2 >= 0.0:
        return x2
    return -1.0


@kernel_jit
def brent_root(p, pts, modes, y0, y1, wk, i, sigma, kind, a, fa, b, fb, stol, ybuf, fbuf):
    """Brent's method for w(s) = 0 on [a, b] with fa < 0 <= fb; returns the upper end of the
    final bracket (w >= 0 there), so the event is never placed before the crossing."""
    c = a
    fc = fa
    d = b - a
    e = d
    for _ in range(BRENT_MAXITER):
        if (fb >= 0.0) == (fc >= 0.0):
            c = a
            fc = fa
            d = b - a
            e = d
        if abs(fc) < abs(fb):
            a = b
            b = c
            c = a
            fa = fb
            fb = fc
            fc = fa
        tol1 = 2.0 * 2.2e-16 * abs(b) + 0.5 * stol
        xm = 0.5 * (c - b)
        if abs(xm) <= tol1 or fb == 0.0:
            break
        if abs(e) >= tol1 and abs(fa) > abs(fb):
            s = fb / fa
            if a == c:
                pp = 2.0 * xm * s
                q = 1.0 - s
            else:
                q = fa / fc
                r = fb / fc
                pp = s * (2.0 * xm * q * (q - r) - (b - a) * (r - 1.0))
                q = (q - 1.0) * (r - 1.0) * (s - 1.0)
            if pp > 0.0:
                q = -q
            pp = abs(pp)
            if 2.0 * pp < min(3.0 * xm * q - abs(tol1 * q), abs(e * q)):
                e = d
                d = pp / q
            else:
                d = xm
                e = d
        else:
            d = xm
            e = d
        a = b
        fa = fb
        if abs(d) > tol1:
            b += d
        else:
            b += math.copysign(tol1, xm)
        fb = directed_value(p, pts, modes, y0, y1, wk, b, i, sigma, kind, ybuf, fbuf)
    # b and c bracket the root; return the end on the crossed side
    if fb >= 0.0:
        return b
    return c
