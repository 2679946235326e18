"""What a run means: classification, horizon and stationarity rules, admissibility,
the friction reserve and the result record of one run. Pure numpy over kernel constants."""
