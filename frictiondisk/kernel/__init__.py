"""The numbers of one run: equations of motion, RODAS4 steps, events, energy, the motion's
facts, in named records. numba only: never imports orchestration nor the rest of frictiondisk."""
