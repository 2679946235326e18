"""Figures from stored results: one style module and the layers every figure shares (each
task draws its own figure from them). Nothing here simulates."""
