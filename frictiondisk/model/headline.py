"""The scene name, mu and x_ms of a configuration, for titles and one-line summaries.

Its own light module (yaml only), so that `simulate`'s report needs neither xarray nor
matplotlib.
"""

from __future__ import annotations

from typing import Any

import yaml


def scene_headline(config: Any) -> dict[str, Any]:
    """The scene name, mu and x_ms of a configuration (for titles, summaries and reports)."""
    try:
        scene = getattr(config.scene, "value", config.scene)
        params = config.params
        mu, x_ms = params.mu, params.x_ms
    except AttributeError:  # any other layout: read the canonical YAML
        data = yaml.safe_load(config.to_yaml())
        scene = data["scene"]
        mu, x_ms = data["params"]["mu"], data["params"]["x_ms"]
    return {"scene": str(scene), "mu": float(mu), "x_ms": float(x_ms)}
