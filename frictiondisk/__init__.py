"""frictiondisk: bifurcation tracking for the radial dynamics of friction disks."""

__version__ = "0.1.0"
