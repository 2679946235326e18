"""The `basin` task: outcome fractions over sampled initial states, or a basin map."""
