"""The well-posedness study: is a certified headline mu* true? (docs/wellposed.md)

Draws seeded random scenes (scenes.py: pins and disks, half of them with a Stribeck
curve) and locates every jump of each under three settings (settings.py: `default`, the
campaign defaults; `uncertified`, the same without certification; `reference`, a dense
prescan with horizon x 8 and rtol and atol / 100), each as a find_jump campaign run on the
engine into one output folder (study.py; found.py reads back what each found and what its
answer stands on). Every disagreement between the default and the reference is settled
run by run by long watches that count only what a run shows, a Coulomb pin's by the exact
Coulomb integrator too (judge.py), and the report (report.py) says who was right, how
often the default was silently wrong, how many points failed and what certification costs.

    python -m frictiondisk.studies.wellposed -o out/wellposed            # all 500 scenes
    python -m frictiondisk.studies.wellposed.longer out/wellposed --longer 8
"""
