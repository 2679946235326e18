"""The package version (its own module, so that modules can read it without importing the
package's public API)."""

__version__ = "0.1.0"

# The version of the numerics: part of every journal key (store/journal_entry.py
# `kernel_version`, with the numba, numpy and scipy versions). Bump it with any change that
# alters what a run computes (kernel, integrators, classification, result fields, derived
# scene defaults), so that journals never reuse results of older numerics.
NUMERICS_VERSION = 10
