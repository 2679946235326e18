"""The braked disk (paper Fig. 11): mu*(beta_b) against the admissibility
bounds, persistent micro-slip of a co-rotating disk, and the rotation term of the contact
rate (docs/brake.md).

    python -m frictiondisk.studies.brake [-o out/brake] [--figures figures] [--quick] [--no-radau]

Prints every number it finds and writes
  FIGURES/brake_admissibility.png   mu*(beta_b) of the `stick` rule (both initial spins), the
                                    mu* of a co-rotation rule, and the four bounds of
                                    frictiondisk/verdict/admissibility.py; micro-slip per
                                    revolution
  FIGURES/brake_rotation_term.png   a stuck braked disk integrated with and without the
                                    rotation term of docs/model.md section 3 (scipy-radau)
  OUT/brake_study.json              the numbers

Scene: disk, default layout (12 points on rho = 0.05 m), x_ms = 0.1 m, all other defaults.
The `stick` rule's mu*(beta_b) are two find_jump campaigns along beta_b run on the engine
into OUT/<name>/ (mu_star.py). The rest reads what the engine does not keep, each from
single runs of `simulate`: the co-rotation rule and the micro-slip from recorded
trajectories (the drift of the centre in the master frame, the spin phase, the contact
pattern), and the rotation term from scipy-radau runs of a model variant that no scene
file can ask for (`objective_rate=False`, rotation_term.py).
"""
