"""The five outcomes a run can have (docs/model.md section 6), in the order tables and
figures list them. Dependency-free, so that planning, storage and figures can name them
without loading the kernel; what decides among them is verdict/label.py.

* stick: the slave co-rotates with the master for good (stick_rule corotation) or every
  contact stuck for a whole master revolution (contacts);
* creep: it ratchets on its small orbit, slipping a little every revolution for ever;
* stick_slip: sticking and sliding alternate (a cycle reached, or approached);
* slide: it never sticks as a whole;
* undetermined: the run could not tell (a budget, a failure, or no evidence in time).
"""

OUTCOMES = ("stick", "creep", "stick_slip", "slide", "undetermined")
