"""Studies: the evidence behind the tool (well-posedness, error model, identical results),
run on the engine and the journal; apart from the performance benchmarks."""
