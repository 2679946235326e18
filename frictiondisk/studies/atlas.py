"""The atlas of the motions: the pin's motion map with the boundaries traced, and
the braked axisymmetric disk's map.

    python -m frictiondisk.studies.atlas [-o out/atlas] [--figures figures] [--workers 2]

Runs campaigns/map_pin_omega_mu.yaml (the motion of every cell of the (omega_m, mu) plane,
from rest) and the trace campaigns of the boundaries it shows (trace_pin_*.yaml: each
boundary between two motions followed to tol in mu, every point certified) on the engine
into OUT/<name>/, resuming what is there, prints the map's shares and the traced curves,
and writes FIGURES/atlas_pin_map.png: the map with the traced curves on top (what `frictiondisk
plot OUT/map_pin_omega_mu --boundary OUT/trace_pin_...` draws), and FIGURES/atlas_disk_map.png
from campaigns/map_disk_js_omega.yaml.
"""

from __future__ import annotations

import sys
from pathlib import Path

from frictiondisk.studies import campaigns

FIGURES = {  # figure name -> (map campaign, the trace campaigns drawn on it)
    "atlas_pin_map": (
        "map_pin_omega_mu",
        ("trace_pin_selfcentring_stick", "trace_pin_selfcentring_cycle", "trace_pin_cycle_stick"),
    ),
    # the braked axisymmetric disk from one start (x0 0.15 m): its boundaries lie in the
    # hysteresis band of the subcritical torus bifurcation (located: torus_disk_js.yaml)
    "atlas_disk_map": ("map_disk_js_omega", ()),
}


def campaign_names() -> tuple[str, ...]:
    """Every campaign the figures draw on, each once, maps first."""
    return tuple(dict.fromkeys(c for m, ts in FIGURES.values() for c in (m, *ts)))


def draw(name: str, out: Path, figures: Path) -> Path:
    """Print the map's shares and its traced curves, and draw figure `name` from out."""
    import matplotlib

    matplotlib.use("Agg")
    from frictiondisk.figures.plotting import save_figure
    from frictiondisk.tasks.map.figure import plot_map
    from frictiondisk.tasks.map.table import summary_lines
    from frictiondisk.tasks.trace.table import trace_lines

    map_name, traces = FIGURES[name]
    results = campaigns.results(out / map_name)
    print("  " + summary_lines(results)[0])
    drawn = tuple(campaigns.results(out / trace) for trace in traces)
    for trace, data in zip(traces, drawn, strict=True):
        print(f"  {trace}:")
        for line in trace_lines(data):
            print("    " + line)
    return save_figure(plot_map(results, drawn), figures / f"{name}.png")


def main(argv: list[str] | None = None) -> int:
    parser = campaigns.figure_study_parser(
        "python -m frictiondisk.studies.atlas", __doc__.splitlines()[0], "out/atlas"
    )
    args = parser.parse_args(argv)
    campaigns.run_shipped(campaign_names(), args.campaigns, args.out, args.workers)
    for name in FIGURES:
        print(f"{name}: figure {draw(name, args.out, args.figures)}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
