"""The horizon budget (numba): may a run's horizon still move on? machine.at_horizon extends
it a revolution at a time, and a followed departure decides only where it cannot
(section_evidence)."""

from frictiondisk.kernel.jit import kernel_jit


@kernel_jit
def may_extend(rules, t_stop, t_eps):
    """Whether the horizon t_stop [s] may move one revolution T on within the budget (up to
    t_eps [s] of rounding)."""
    return t_stop + rules.hold <= rules.budget + t_eps
