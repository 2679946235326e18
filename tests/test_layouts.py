"""Contact layouts (ring, annulus, points): geometry, weights, validation, canonical form,
and the physics of unequal contacts."""

from __future__ import annotations

import math

import numpy as np
import pytest

from frictiondisk.model import layouts
from frictiondisk.model.scene import ConfigError, scene_from_dict
from frictiondisk.model.yamlio import load_yaml_text
from frictiondisk.simulation.pack import pack_parameters
from frictiondisk.simulation.simulate import simulate

CLUTCH = {"layout": "annulus", "inner_radius": 0.063, "outer_radius": 0.087}


def _disk(contact, **params):
    return scene_from_dict({"scene": "disk", "contact": contact, "params": params})


def _problems(contact, scene="disk"):
    with pytest.raises(ConfigError) as info:
        scene_from_dict({"scene": scene, "contact": contact})
    return info.value.problems


def test_ring_is_the_old_layout_with_weights_exactly_one():
    config = _disk({"points": 12})
    p, pts = pack_parameters(config)
    angles = 2.0 * np.pi * np.arange(12) / 12
    old = 0.05 * np.column_stack((np.cos(angles), np.sin(angles)))
    assert np.array_equal(pts[:, :2], old)
    assert np.all(pts[:, 2] == 1.0)  # so c_i = c/N, beta_i, F_n,i bit for bit as before


@pytest.mark.parametrize(("inner", "outer"), [(0.063, 0.087), (0.0, 0.1)])
@pytest.mark.parametrize("n", [1, 12, 192, 768])
def test_annulus_has_uniform_pressure_and_the_exact_slip_torque(n, inner, outer):
    positions, shares = layouts.annulus(n, inner, outer)
    assert positions.shape == (n, 2)
    radii = np.hypot(positions[:, 0], positions[:, 1])
    assert np.all((radii >= inner) & (radii <= outer))
    # uniform pressure: each band's share of the total is its share of the area
    counts = layouts.annulus_bands(n, inner, outer)
    edges = np.linspace(inner, outer, len(counts) + 1)
    start = np.cumsum([0, *counts])
    for j in range(len(counts)):
        band = shares[start[j] : start[j + 1]].sum() / shares.sum()
        area = (edges[j + 1] ** 2 - edges[j] ** 2) / (outer**2 - inner**2)
        assert band == pytest.approx(area, rel=1e-12)
    # sliding as a whole, the points carry the facing's torque mu F_n r_f exactly
    r_f = 2.0 / 3.0 * (outer**3 - inner**3) / (outer**2 - inner**2)
    weights = layouts.relative_weights(shares) / n
    assert float(weights @ radii) == pytest.approx(r_f, rel=1e-12)
    # cells about square: every band's count within one of its ideal share
    ideal = n * np.diff(edges**2) / (outer**2 - inner**2)
    assert np.all(np.abs(np.array(counts) - ideal) <= 1.0)


def test_annulus_bands_grow_like_sqrt_n():
    assert layouts.annulus_bands(12, 0.063, 0.087) == [12]
    for n in (48, 192, 768):
        bands = len(layouts.annulus_bands(n, 0.063, 0.087))
        # cells as long as wide: n / bands points on a band of mean circumference 2 pi 0.075
        cell_length = 2.0 * math.pi * 0.075 * bands / n
        cell_width = 0.024 / bands
        assert 0.5 < cell_length / cell_width < 2.0, (n, bands)


def test_points_layout_normalizes_its_weights():
    contact = {"layout": "points", "positions": [[0.05, 0.0], [0.0, 0.05], [-0.05, 0.0]]}
    config = _disk({**contact, "weights": [1.0, 2.0, 1.0]})
    assert config.n_contacts == 3
    assert np.allclose(config.contact_weights(), [0.75, 1.5, 0.75])
    same = _disk({**contact, "weights": [2.0, 4.0, 2.0]})
    assert np.array_equal(same.contact_weights(), config.contact_weights())
    equal = _disk(contact)
    assert np.all(equal.contact_weights() == 1.0)
    # null weights are equal weights: one canonical form, one key
    assert equal.content_hash() == _disk({**contact, "weights": [1.0, 1.0, 1.0]}).content_hash()


@pytest.mark.parametrize(
    ("contact", "expected"),
    [
        ({"layout": "annulus"}, "contact.inner_radius: null is not allowed: layout 'annulus'"),
        ({**CLUTCH, "outer_radius": 0.05}, "contact.outer_radius: 0.05 is not allowed: must be >"),
        ({**CLUTCH, "inner_radius": -0.01}, "contact.inner_radius: -0.01 is out of range: must"),
        ({"inner_radius": 0.01}, "contact.inner_radius: 0.01 is not allowed: only used by"),
        ({"positions": [[0.0, 0.1]]}, "contact.positions: [[0.0, 0.1]] is not allowed: only"),
        ({"layout": "points"}, "contact.positions: null is not allowed: layout 'points' needs"),
        ({"layout": "points", "positions": []}, "contact.positions: [] is not allowed: must hold"),
        (
            {"layout": "points", "positions": [[0.1, 0.0], [0.1]]},
            "contact.positions.1: [0.1] is not allowed: must be a pair",
        ),
        (
            {"layout": "points", "positions": [[0.1, 0.0]], "weights": [1.0, 1.0]},
            "contact.weights: [1.0, 1.0] is not allowed: must have one weight per position",
        ),
        (
            {"layout": "points", "positions": [[0.1, 0.0]], "weights": [0.0]},
            "contact.weights.0: 0.0 is not allowed: must be > 0",
        ),
        (
            {"layout": "points", "positions": [[0.1, 0.0]], "points": 2},
            "contact.points: 2 is not allowed: must be null or len(positions) = 1",
        ),
        ({"layout": "ring", "weights": [1.0]}, "contact.weights: [1.0] is not allowed: only"),
        ({"layout": "disc"}, "contact.layout: 'disc' is not allowed: must be one of 'ring'"),
        ({**CLUTCH, "points": 1001}, "contact.points: 1001 is out of range: must be >= 1 and"),
    ],
)
def test_bad_layouts_name_the_field_and_the_rule(contact, expected):
    found = _problems(contact)
    assert len(found) == 1 and found[0].startswith(expected), found


def test_a_pin_keeps_its_one_contact():
    found = _problems(CLUTCH, scene="pin")
    assert found[0].startswith("contact.layout: 'annulus' is not allowed for scene 'pin'")


def test_canonical_form_keeps_only_the_chosen_layout_and_round_trips():
    ring = _disk({})
    assert ring.canonical()["contact"]["layout"] == "ring"
    assert "inner_radius" not in ring.canonical()["contact"]
    annulus = _disk({**CLUTCH, "points": 192})
    contact = annulus.canonical()["contact"]
    assert (contact["inner_radius"], contact["outer_radius"], contact["points"]) == (
        0.063,
        0.087,
        192,
    )
    assert "ring_radius" not in contact and "positions" not in contact
    hashes = {ring.content_hash(), annulus.content_hash(), _disk({**CLUTCH}).content_hash()}
    assert len(hashes) == 3  # the layout is part of the content hash, hence the journal key
    for config in (ring, annulus):
        again = scene_from_dict(load_yaml_text(config.to_yaml()))
        assert again.canonical() == config.canonical()


@pytest.mark.parametrize("copies", [2, 16])
def test_split_contacts_behave_like_the_merged_ones(copies):
    """Contacts at one point with weights 1, 2, 3, ... are one contact of their total
    weight: the contact law is homogeneous of degree one in (c_i, beta_i, F_n,i, Z_i). A
    ring of 12 against 12 * copies points, every ring point split unequally, so that with
    16 copies 192 contacts switch in groups of 16 at nearly the same instant (their
    switching functions differ by the weight factor, their located roots by round-off)."""
    params = {"beta_b": 0.005, "phidot0": 1.1, "mu": 0.2}
    # the kernel's rules only: the shakedown bound reads equal weights alone (its scope),
    # so it would judge the ring and not the split points
    numerics = {"t_decide": 10.0, "evidence": "observe"}
    ring = scene_from_dict(
        {"scene": "disk", "params": params, "numerics": numerics, "contact": {"points": 12}}
    )
    positions = np.repeat(ring.contact_positions(), copies, axis=0).tolist()
    weights = [float(1 + (k + i) % copies) for i in range(12) for k in range(copies)]
    split = scene_from_dict(
        {
            "scene": "disk",
            "params": params,
            "numerics": numerics,
            "contact": {"layout": "points", "positions": positions, "weights": weights},
        }
    )
    assert len(set(split.contact_weights())) == copies  # unequal contacts in the kernel
    a, b = simulate(ring), simulate(split)
    assert a.n_transitions > 10  # a run with real switching
    assert (a.outcome, copies * a.n_transitions) == (b.outcome, b.n_transitions)
    rtol = ring.numerics.rtol
    assert abs(a.R1 - b.R1) <= rtol * a.R1
    assert abs(a.t_end - b.t_end) <= rtol * a.t_end
