"""The horizon budget (numba): may a run's horizon still move on, and is a departure still
followed? machine.at_horizon extends the horizon a revolution at a time within the budget,
and a followed departure decides only at the last horizon before numerics.
follow_departures_until (section_evidence)."""

from frictiondisk.kernel.jit import kernel_jit


@kernel_jit
def next_horizon_within(rules, t_stop, limit, t_eps):
    """Whether the horizon after t_stop [s], one revolution T on, lies within `limit` [s]
    (up to t_eps [s] of rounding)."""
    return t_stop + rules.hold <= limit + t_eps


@kernel_jit
def may_extend(rules, t_stop, t_eps):
    """Whether the horizon t_stop [s] may move one revolution on within the budget."""
    return next_horizon_within(rules, t_stop, rules.budget, t_eps)


@kernel_jit
def still_following(rules, t_stop, t_eps):
    """Whether a departure seen at the horizon t_stop [s] is still followed: the next
    horizon lies within numerics.follow_departures_until (never where that is 0)."""
    return next_horizon_within(rules, t_stop, rules.follow_until, t_eps)
