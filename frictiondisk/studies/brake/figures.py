"""The brake study's two figures: mu* against the bounds with the micro-slip, and the
rotation term. Their footer names this code's numerics: the study computes every run it
draws now (its campaigns resume only runs journaled under this numerics version)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from frictiondisk.figures.footer import add_footer, code_footer
from frictiondisk.studies.brake.common import N_POINTS, REV, bounds


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
    _save(fig, path)


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
    _save(fig, path)


def _save(fig, path: Path) -> None:
    """Footer, layout and file (with the footer in its metadata) of a study figure."""
    import matplotlib.pyplot as plt

    from frictiondisk.figures.plotting import save_figure

    add_footer(fig, code_footer("python -m frictiondisk.studies.brake"))
    save_figure(fig, path)
    plt.close(fig)
