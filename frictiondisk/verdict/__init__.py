"""What a run is: the state machine the step loop calls, every threshold in one record
(VerdictParams), the evidence it weighs, the bounds, and the label after the run."""
