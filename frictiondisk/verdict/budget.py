"""The horizon budget (numba): may a run's horizon still move on, and is a departure still
followed? machine.at_horizon extends the horizon a revolution at a time within the budget,
and a followed departure decides only at the last horizon before numerics.
follow_departures_until (section_evidence)."""

from frictiondisk.kernel.jit import kernel_jit


@kernel_jit
def may_extend(rules, t_stop, t_eps):
    """Whether the horizon t_stop [s] may move one revolution T on within the budget (up to
    t_eps [s] of rounding)."""
    return t_stop + rules.hold <= rules.budget + t_eps


@kernel_jit
def still_following(rules, t_stop, t_eps):
    """Whether a departure seen at the horizon t_stop [s] is still followed: the next
    horizon, one revolution on, lies within numerics.follow_departures_until (up to t_eps
    [s] of rounding; never where that is 0)."""
    return t_stop + rules.hold <= rules.follow_until + t_eps
