"""Figures from stored results: one style module, one module per figure family.
Nothing here simulates."""
