"""The numerics presets (`numerics.preset`): named sets of method, tolerances and steps."""

from __future__ import annotations

from typing import Any

# Numerics presets: each sets every key it names unless the scene gives that key
# explicitly (explicit keys win). `default` is the field defaults, so a scene without a preset
# is unchanged. Chosen from the accuracy study (`frictiondisk accuracy` on
# campaigns/accuracy_pin.yaml and accuracy_disk.yaml, bisection tol 1e-9): |mu* - mu*_ref|
# against rodas4 at rtol 1e-9 on the default pin / co-rotating disk, and kernel steps of the
# whole bisection relative to `default`:
#   fast       rtol 1e-4, atol 1e-7   9.0e-6 / Zeno     0.64x / 0.49x
#   default    rtol 1e-6, atol 1e-9   5.8e-7 / 6.5e-9   1
#   reference  rtol 1e-9, atol 1e-12  the reference     6.5x / 6.5x
# All well below the campaigns' bisection tol 1e-4. atol = 1e-3 rtol throughout (states are
# O(0.1) m, m/s, N). t_decide is not part of a preset: a horizon that is too short misses a
# late permanent stick unless the run extends until its verdict is shown stationary
# (docs/model.md section 6; before that rule, t_decide = 2 s misplaced mu* by 1e-2).
NUMERICS_PRESETS: dict[str, dict[str, Any]] = {
    "fast": {"method": "rodas4", "rtol": 1.0e-4, "atol": 1.0e-7, "dt": 1.0e-2, "h_max": 0.1},
    "default": {"method": "rodas4", "rtol": 1.0e-6, "atol": 1.0e-9, "dt": 1.0e-2, "h_max": 0.1},
    "reference": {
        "method": "rodas4",
        "rtol": 1.0e-9,
        "atol": 1.0e-12,
        "dt": 1.0e-2,
        "h_max": 0.1,
    },
}
