"""One run: a validated scene in, a classified SimulationResult out, by the RODAS4 kernel,
scipy's Radau (cross-check) or the exact-Coulomb pin, chosen in one registry (simulate.py)."""
