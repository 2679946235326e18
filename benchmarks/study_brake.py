"""Braked disk (issue 4 item 5, paper Fig. 11): mu*(beta_b) against the admissibility bounds,
persistent micro-slip of a co-rotating disk, and the rotation term of the contact rate.

    .venv/bin/python benchmarks/study_brake.py --out out/brake [--quick] [--no-radau]

Prints every number it finds and writes
  figures/brake_admissibility.png   mu*(beta_b) of the `stick` rule (both initial spins), the
                                    mu* of a co-rotation rule, and the four bounds of
                                    frictiondisk/verdict/admissibility.py; micro-slip per revolution
  figures/brake_rotation_term.png   a stuck braked disk integrated with and without the
                                    rotation term of docs/model.md section 3 (scipy-radau)
  OUT/brake_study.json              the numbers

Scene: disk, default layout (12 points on rho = 0.05 m), x_ms = 0.1 m, all other defaults.
Cost (2 cores): about 3 min, of which 2 min scipy-radau (--no-radau skips the radau mu*).
"""

from __future__ import annotations

import argparse
import json
import math
import pathlib
import time

import numpy as np

from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.numpy_model import NumpyModel
from frictiondisk.simulation.radau import simulate_radau
from frictiondisk.simulation.simulate import simulate
from frictiondisk.verdict import admissibility as ad

OMEGA = 1.1  # [rad/s]
REV = 2 * math.pi / OMEGA  # [s]
N_POINTS, RHO = 12, 0.05  # default layout [1], [m]
POINTS = ad.ring_points(N_POINTS, RHO)
BETA_B = np.linspace(0.0, 0.03, 13)  # as campaigns/fig11_betab_mu.yaml [N m s/rad]
# co-rotation rule: the centre in the master frame and the spin phase phi - omega_m t
# repeat every revolution to within these (integration error at rtol 1e-8: < 2e-9 m,
# < 1e-12 rad; at rtol 1e-6 up to 7e-8 m, hence rtol 1e-8 here)
DRIFT_TOL = 1e-8  # [m/rev]
LAG_TOL = 1e-7  # [rad/rev]
ROOT = pathlib.Path(__file__).resolve().parents[1]


def scene(mu, beta_b, phidot0, **numerics):
    return scene_from_dict(
        {
            "scene": "disk",
            "params": {"mu": float(mu), "beta_b": float(beta_b), "phidot0": float(phidot0)},
            "numerics": numerics,
        }
    )


def bisect(is_stick, lo, hi, tol):
    """Bracket [lo, hi] with is_stick(lo) False and is_stick(hi) True, to width tol."""
    s_lo, s_hi = is_stick(lo), is_stick(hi)
    if s_lo or not s_hi:
        return math.nan, math.nan
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        if is_stick(mid):
            hi = mid
        else:
            lo = mid
    return lo, hi


# --- 1. mu* of the `stick` rule and of a co-rotation rule -----------------------------------


def stick_run(mu, beta_b, phidot0):
    return simulate(scene(mu, beta_b, phidot0))


def regular_rows(tr, dt):
    """Indices of the samples at multiples of dt (drops the extra rows at switches)."""
    k = np.round(tr.t / dt)
    reg = np.abs(tr.t - k * dt) < 1e-9
    _, first = np.unique(k[reg], return_index=True)
    return np.flatnonzero(reg)[first]


def corotation(mu, beta_b, phidot0, nrev=12, per=50, rtol=1e-8):
    """Run nrev revolutions without stopping at stick and measure, over the last 3:
    drift of the centre in the master frame [m/rev], of the spin phase [rad/rev],
    mode transitions per revolution, fewest contacts stuck at once."""
    dt = REV / per
    cfg = scene(
        mu, beta_b, phidot0, stop_on_stick=False, t_decide=nrev * REV, rtol=rtol, atol=rtol * 1e-3
    )
    res = simulate(cfg, record=True, dt_out=dt)
    tr = res.trajectory
    idx = regular_rows(tr, dt)
    i1, i0 = idx[-1], idx[-1 - 3 * per]

    def in_master_frame(i):
        c, s = math.cos(-OMEGA * tr.t[i]), math.sin(-OMEGA * tr.t[i])
        return np.array([c * tr.x[i] - s * tr.y[i], s * tr.x[i] + c * tr.y[i]])

    drift = float(np.linalg.norm(in_master_frame(i1) - in_master_frame(i0)) / 3)
    lag = float(abs((tr.phi[i1] - OMEGA * tr.t[i1]) - (tr.phi[i0] - OMEGA * tr.t[i0])) / 3)
    late = tr.t > tr.t[-1] - 3 * REV
    trans = np.abs(np.diff(tr.mode.astype(int), axis=0)).sum(axis=1)[late[1:]].sum() / 3
    return {
        "mu": float(mu),
        "outcome": res.outcome,
        "R": float(math.hypot(tr.x[-1], tr.y[-1])),
        "drift_m_per_rev": drift,
        "lag_rad_per_rev": lag,
        "transitions_per_rev": float(trans),
        "min_stuck": int(tr.mode[late].sum(axis=1).min()),
        "corotates": drift < DRIFT_TOL and lag < LAG_TOL,
        "trajectory": tr,
    }


def bounds(beta_b, radius):
    """The four demands of admissibility.py as friction coefficients (F_n = 1 N)."""
    d = ad.demands(ad.LoadCase(R=radius, beta_b=beta_b), POINTS, RHO)
    return {
        "collapse": d.collapse,
        "shakedown": d.shakedown,
        "elastic": d.elastic,
        "additive": d.additive,
    }


def part1(quick):
    betas = BETA_B[::3] if quick else BETA_B
    rows = []
    print("\n1. mu*(beta_b): `stick` rule (both spins), co-rotation rule, bounds at R1(mu_hi)")
    print(
        "  beta_b  mu*_stick(w) mu*_stick(0)  mu*_corot  R1[m]    collapse shakedown"
        "  elastic additive  mu*/additive"
    )
    for bb in betas:
        row = {"beta_b": float(bb)}
        for key, spin in (("stick_corot_start", OMEGA), ("stick_rest_start", 0.0)):
            lo, hi = bisect(
                lambda m, s=spin, b=bb: stick_run(m, b, s).outcome == "stick", 0.1, 1.2, 1e-4
            )
            row[key] = 0.5 * (lo + hi)
            if spin == OMEGA:
                row["R1"] = stick_run(hi, bb, spin).R1
        lo, hi = bisect(lambda m, b=bb: corotation(m, b, OMEGA)["corotates"], 0.1, 1.2, 2e-3)
        row["corotation_rule"] = 0.5 * (lo + hi)
        row["R_corot"] = corotation(hi, bb, OMEGA)["R"]
        row["bounds"] = bounds(bb, row["R1"])
        row["bounds_at_corot"] = bounds(bb, row["R_corot"])
        b = row["bounds"]
        print(
            f"  {bb:.4f}  {row['stick_corot_start']:.4f}       {row['stick_rest_start']:.4f}"
            f"       {row['corotation_rule']:.4f}     {row['R1']:.4f}   {b['collapse']:.4f}"
            f"   {b['shakedown']:.4f}    {b['elastic']:.4f}   {b['additive']:.4f}"
            f"   {row['stick_corot_start'] / b['additive']:.2f}",
            flush=True,
        )
        rows.append(row)
    return rows


# --- 2. micro-slip of co-rotating braked disks ------------------------------------------------


def part2(quick):
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
        per_rev = [
            int(
                np.abs(
                    np.diff(tr.mode[(tr.t >= k * REV) & (tr.t < (k + 1) * REV)].astype(int), axis=0)
                ).sum()
            )
            for k in range(nrev)
        ]
        # plastic slip per revolution: change of the body-frame contact pattern / c_i
        dt = REV / 50
        idx = regular_rows(tr, dt)
        phi = tr.phi[idx][:, None]
        bx = np.cos(phi) * tr.Zx[idx] + np.sin(phi) * tr.Zy[idx]
        by = -np.sin(phi) * tr.Zx[idx] + np.cos(phi) * tr.Zy[idx]
        a, b = len(idx) - 1 - 3 * 50, len(idx) - 1
        c_i = 2.53e5 / N_POINTS
        slip = float(np.hypot(bx[b] - bx[a], by[b] - by[a]).max() / 3 / c_i)
        r.update(per_rev=per_rev, slip_m_per_rev=slip, beta_b=bb)
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


# --- 3. the rotation term ------------------------------------------------------------------


def self_stress(model, tr):
    """Largest contact force [N] not explained by the elastic sharing of the resultants
    (force and torque) of the pattern: the self-equilibrated part, in every sample."""
    out = np.empty(len(tr.t))
    for j in range(len(tr.t)):
        ang = tr.phi[j]
        a = POINTS @ np.array([[math.cos(ang), math.sin(ang)], [-math.sin(ang), math.cos(ang)]])
        z = np.column_stack((tr.Zx[j], tr.Zy[j]))
        torque = float((a[:, 0] * z[:, 1] - a[:, 1] * z[:, 0]).sum())
        elastic = ad.elastic_pattern(z.sum(axis=0), torque, a)
        out[j] = np.linalg.norm(z - elastic, axis=1).max()
    return out


def part3(no_radau, quick):
    mu, bb = 0.5, 0.002
    nrev = 6 if quick else 10
    print(
        f"\n3. rotation term: stuck disk mu = {mu}, beta_b = {bb}, phidot0 = omega_m, {nrev} revolutions (scipy-radau)"
    )
    runs = {}
    for label, obj in (("with rotation term (ours)", True), ("without (u = v)", False)):
        cfg = scene(mu, bb, OMEGA, method="scipy-radau", stop_on_stick=False, t_decide=nrev * REV)
        t0 = time.perf_counter()
        res = simulate_radau(cfg, record=True, dt_out=REV / 50, objective_rate=obj)
        tr = res.trajectory
        per_rev = [
            int(
                np.abs(
                    np.diff(tr.mode[(tr.t >= k * REV) & (tr.t < (k + 1) * REV)].astype(int), axis=0)
                ).sum()
            )
            for k in range(nrev)
        ]
        lag = tr.phi - OMEGA * tr.t
        k1 = tr.t > (nrev - 3) * REV
        lag_rate = float(np.polyfit(tr.t[k1], lag[k1], 1)[0] * REV)
        model = NumpyModel.from_config(cfg, objective_rate=obj)
        ss = self_stress(model, tr)
        runs[label] = {"trajectory": tr, "per_rev": per_rev, "lag": lag, "self_stress": ss}
        print(
            f"  {label:26s}: {res.outcome}, transitions per revolution {per_rev}, spin creep"
            f" {lag_rate:+.2e} rad/rev, self-stress last rev {ss[k1].max():.2e} N"
            f" (limit mu F_n/N = {mu / N_POINTS:.4f} N), wall {time.perf_counter() - t0:.1f} s",
            flush=True,
        )
        runs[label].update(lag_rate=lag_rate, outcome=res.outcome)
    mustar = {}
    if not no_radau:
        for label, obj in (("ours", True), ("without", False)):
            t0 = time.perf_counter()

            def sticks(m, obj=obj):
                cfg = scene(m, bb, OMEGA, method="scipy-radau")
                return simulate_radau(cfg, objective_rate=obj).outcome == "stick"

            lo, hi = bisect(sticks, 0.15, 1.35 if obj else 2.55, 0.02)
            mustar[label] = (lo, hi)
            print(
                f"  mu* (`stick` rule, scipy-radau, tol 0.02), {label}: [{lo:.3f}, {hi:.3f}]"
                f" ({time.perf_counter() - t0:.0f} s)",
                flush=True,
            )
    return runs, mustar


# --- figures -------------------------------------------------------------------------------


def figure_admissibility(rows, micro, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(13, 5.2))
    bb = np.array([r["beta_b"] for r in rows])
    fine = np.linspace(0.0, bb.max(), 31)
    radius = np.interp(fine, bb, [r["R1"] for r in rows])
    curves = {k: [] for k in ("collapse", "shakedown", "elastic", "additive")}
    for b, rr in zip(fine, radius, strict=True):
        for k, v in bounds(b, rr).items():
            curves[k].append(v)
    style = {"collapse": ":", "shakedown": "-.", "elastic": "-", "additive": "--"}
    names = {
        "collapse": "collapse: max_t Λ(F(t), T)",
        "shakedown": "shakedown (Melan): c_s x_ms + Λ(C, T)",
        "elastic": "elastic sharing (worst layout)",
        "additive": "additive: c_s x_ms + gR + β_b ω_m/ρ",
    }
    for k, v in curves.items():
        ax.plot(fine, v, style[k], color="0.35", label=names[k])
    ax.plot(
        bb,
        [r["stick_corot_start"] for r in rows],
        "o-",
        color="C3",
        label="μ*, `stick` rule, φ̇0 = ω_m",
    )
    ax.plot(
        bb,
        [r["stick_rest_start"] for r in rows],
        "s",
        mfc="none",
        color="C1",
        label="μ*, `stick` rule, φ̇0 = 0",
    )
    ax.plot(
        bb,
        [r["corotation_rule"] for r in rows],
        "^-",
        color="C0",
        label="μ*, co-rotation rule (no creep), φ̇0 = ω_m",
    )
    ax.set_xlabel("brake damping β_b [N m s/rad]")
    ax.set_ylabel("friction coefficient μ [1]")
    ax.set_title("Disk, 12 points on ρ = 0.05 m, x_ms = 0.1 m: jump μ* vs bounds (R = R1)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    for r in micro:
        bx.plot(np.arange(len(r["per_rev"])), r["per_rev"], ".-", label=f"μ = {r['mu']:.2f}")
    bx.set_yscale("symlog", linthresh=1)
    bx.set_xlabel("master revolution [1]")
    bx.set_ylabel("stick/slide transitions in the revolution, all contacts [1]")
    bx.set_title(f"β_b = {micro[0]['beta_b']}, φ̇0 = ω_m: micro-slip per revolution")
    bx.legend(fontsize=8, ncol=2)
    bx.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def figure_rotation(runs, mustar, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 2, figsize=(13, 8))
    colors = {"with rotation term (ours)": "C0", "without (u = v)": "C3"}
    for label, r in runs.items():
        tr = r["trajectory"]
        c = colors[label]
        zmax = np.hypot(tr.Zx, tr.Zy).max(axis=1)
        axes[0, 0].plot(tr.t / REV, zmax, color=c, label=label)
        axes[0, 1].plot(tr.t / REV, r["self_stress"], color=c, label=label)
        slides = (tr.mode == 0).sum(axis=1)
        axes[1, 0].step(tr.t / REV, slides, where="post", color=c, label=label, lw=0.8)
        axes[1, 1].plot(
            tr.t / REV,
            r["lag"] - r["lag"][0],
            color=c,
            label=f"{label}: {r['lag_rate']:+.1e} rad/rev",
        )
    limit = 0.5 / N_POINTS
    axes[0, 0].axhline(limit, color="k", ls="--", lw=0.8, label="limit μF_n/N")
    axes[0, 0].set_ylabel("largest contact force |Z_i| [N]")
    axes[0, 1].set_ylabel("self-stress: largest |Z_i − elastic share| [N]")
    axes[1, 0].set_ylabel("contacts sliding [1]")
    axes[1, 1].set_ylabel("spin phase φ − ω_m t, change [rad]")
    title = "Stuck braked disk μ = 0.5, β_b = 0.002 N m s/rad, φ̇0 = ω_m (scipy-radau)"
    if mustar:
        title += "; μ* (`stick` rule): " + ", ".join(
            f"{k} [{lo:.2f}, {hi:.2f}]" for k, (lo, hi) in mustar.items()
        )
    fig.suptitle(title)
    for a in axes.flat:
        a.set_xlabel("time [master revolutions]")
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="out/brake", help="folder for brake_study.json")
    ap.add_argument("--quick", action="store_true", help="fewer points and revolutions")
    ap.add_argument("--no-radau", action="store_true", help="skip the scipy-radau mu* bisections")
    args = ap.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    figs = ROOT / "figures"
    figs.mkdir(exist_ok=True)
    t0 = time.perf_counter()
    rows = part1(args.quick)
    micro = part2(args.quick)
    runs, mustar = part3(args.no_radau, args.quick)
    figure_admissibility(rows, micro, figs / "brake_admissibility.png")
    figure_rotation(runs, mustar, figs / "brake_rotation_term.png")
    summary = {
        "mu_star": rows,
        "micro_slip": micro,
        "rotation_term": {
            k: {
                "per_rev": v["per_rev"],
                "lag_rate_rad_per_rev": v["lag_rate"],
                "outcome": v["outcome"],
            }
            for k, v in runs.items()
        },
        "radau_mu_star": {k: list(v) for k, v in mustar.items()},
    }
    (out / "brake_study.json").write_text(json.dumps(summary, indent=1))
    print(f"\nfigures: {figs / 'brake_admissibility.png'}, {figs / 'brake_rotation_term.png'}")
    print(f"numbers: {out / 'brake_study.json'}  ({time.perf_counter() - t0:.0f} s)")


if __name__ == "__main__":
    main()
