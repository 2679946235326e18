"""The package version (its own module, so that modules can read it without importing the
package's public API)."""

__version__ = "0.1.0"

# The version of the numerics: part of every journal key (store/journal_entry.py
# `kernel_version`, with the numba, numpy and scipy versions). Bump it with any change that
# alters what a run computes (kernel, integrators, classification, result fields, derived
# scene defaults), so that journals never reuse results of older numerics.
NUMERICS_VERSION = 13

# Where a version changed only some scenes, a run of any other scene computes as in the
# version before, and its journal key keeps that one (store/journal_entry.py `key_version`),
# so that journals stay valid where nothing changed. 12 changed every run (the own section's
# rows and the names of not-stick motions); 13 changed Coulomb pins alone (the grazing
# rules, verdict/grazing.py).
UNCHANGED_SINCE = 12
