"""The `trace` task: every jump curve of a (key, mu) plane, folds located (docs/trace.md)."""
