"""One run end to end: a scene in, the step loop (kernel steps + verdict machine), a labelled
SimulationResult out; the integrator chosen from one registry (simulate.py METHODS)."""
