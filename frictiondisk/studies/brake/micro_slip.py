"""Part 2: micro-slip of co-rotating braked disks, from recorded runs."""

from __future__ import annotations

import numpy as np

from frictiondisk.studies.brake.common import (
    N_POINTS,
    OMEGA,
    REV,
    bounds,
    corotation,
    regular_rows,
    transitions_per_rev,
)

C_I = 2.53e5 / N_POINTS  # contact stiffness of one point [N/m]


def plastic_slip(tr, per: int = 50) -> float:
    """Plastic slip per revolution [m] over the last 3: the change of the body-frame
    contact pattern over c_i."""
    idx = regular_rows(tr, REV / per)
    phi = tr.phi[idx][:, None]
    bx = np.cos(phi) * tr.Zx[idx] + np.sin(phi) * tr.Zy[idx]
    by = -np.sin(phi) * tr.Zx[idx] + np.cos(phi) * tr.Zy[idx]
    a, b = len(idx) - 1 - 3 * per, len(idx) - 1
    return float(np.hypot(bx[b] - bx[a], by[b] - by[a]).max() / 3 / C_I)


def part2(quick: bool) -> list[dict]:
    bb = 0.005
    mus = (
        [0.19, 0.20, 0.22, 0.30, 0.40]
        if quick
        else [0.19, 0.20, 0.21, 0.22, 0.26, 0.30, 0.36, 0.40]
    )
    nrev = 20 if quick else 35  # t_decide = 200 s
    print(f"\n2. micro-slip, beta_b = {bb}, phidot0 = omega_m, {nrev} revolutions, rtol 1e-8")
    print(
        "  mu     outcome      trans/rev(last 3)  slip/rev[m]  drift[m/rev]  lag[rad/rev]  min_stuck"
    )
    out = []
    for mu in mus:
        r = corotation(mu, bb, OMEGA, nrev=nrev, rtol=1e-8)
        tr = r.pop("trajectory")
        slip = plastic_slip(tr)
        r.update(per_rev=transitions_per_rev(tr, nrev), slip_m_per_rev=slip, beta_b=bb)
        print(
            f"  {mu:.2f}   {r['outcome']:11s}  {r['transitions_per_rev']:6.2f}"
            f"            {slip:9.1e}    {r['drift_m_per_rev']:9.1e}    {r['lag_rad_per_rev']:9.1e}"
            f"    {r['min_stuck']}",
            flush=True,
        )
        out.append(r)
    b = bounds(bb, out[-1]["R"])
    print(
        f"  bounds at R = {out[-1]['R']:.4f} m: " + ", ".join(f"{k} {v:.4f}" for k, v in b.items())
    )
    return out
