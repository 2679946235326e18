"""The reason a jump search's point gives (jump_result.compose_result): why it fails, or
what it found, where it refined between motions, what its prescan skipped. Pure Python."""

from __future__ import annotations

import math

from frictiondisk.verdict.outcomes import UNDETERMINED


def problems_of(state, jumps, scan, vanished: int, unresolved) -> tuple[list[str], str]:
    """Why the point fails (empty: it does not), and the note on prescan values left
    undetermined."""
    # an undetermined prescan value inside a converged jump's bracket is that jump's
    # slow approach (straddle.Straddle.undecided), not a gap in the scan
    undetermined = [
        r.request.mu
        for r in scan
        if state.between.side(r.outcome) is None
        and not any(j.status == "converged" and j.mu_lo < r.request.mu < j.mu_hi for j in jumps)
    ]
    problems = [state.failure] if state.failure else []
    if state.never_ran:
        problems.append(f"{len(state.never_ran)} prescan value(s) never ran")
    # an undetermined value between decided neighbours is a gap in the grid, not a failure:
    # the changes are bisected between decided values, and a gap below the headline leaves
    # its grid less than wholly decided (uncertain); without any jump it is a failure
    undecided_note = ""
    if undetermined:
        mus = ", ".join(f"{mu:.6g}" for mu in sorted(undetermined))
        what = UNDETERMINED if state.between.is_default else "on neither side"
        undecided_note = f"prescan {what} at mu = {mus} after every retry"
        if not jumps:
            problems.append(undecided_note)
    problems += [
        j.reason if math.isnan(j.mu_lo) else f"jump in [{j.mu_lo:.6g}, {j.mu_hi:.6g}]: {j.reason}"
        for j in jumps
        if j.status != "converged" and j not in unresolved
    ]
    if not jumps and vanished and not problems:
        problems.append(
            f"no jump: the {vanished} jump(s) of the prescan vanished at stricter numerics"
        )
    return problems, undecided_note


def converged_reason(state, jumps, unresolved, windows, grid, scan, vanished: int) -> str:
    """The reason of a converged point: its jumps, the failed changes above its headline,
    its windows and the grid below it."""
    resolved = [j for j in jumps if j not in unresolved]
    kinds = ", ".join(
        f"{'rising' if j.rising else 'falling'} at {j.mu_star:.6g}"
        + ("" if j.certification == "off" else f" ({j.certification})")
        for j in resolved
    )
    reason = f"{len(resolved)} jump(s) to tol {state.tol:.3g}: {kinds}"
    for j in unresolved:
        reason += f"; above mu*, a change in [{j.mu_lo:.6g}, {j.mu_hi:.6g}] failed: {j.reason}"
    if windows:
        sticking = "sticking" if state.between.is_default else state.between.high
        reason += f"; {sticking} windows " + ", ".join(
            f"[{w.lo:.6g}, {w.hi:.6g}]" + (" (narrow)" if w.narrow else "") for w in windows
        )
    if grid is not None:
        reason += (
            f"; {grid.decided} of {grid.total} prescan values below mu* decided "
            f"(resolution {grid.resolution:.3g})"
        )
        reason += motion_note(state, grid)
        if state.persists_nowhere:
            reason += (
                f"; no rising jump persists over {state.persist:g} tol (every sticking "
                "set found is that narrow): the lowest one is taken, uncertain"
            )
        elif not state.headline_judged:
            reason += "; the persistence run above mu* stayed undetermined"
    return reason


def motion_note(state, grid) -> str:
    """What the refinement at motion boundaries below mu* did, where it ran."""
    if not grid.motion_runs and not grid.unrefined:
        return ""
    width = state.persist * state.tol
    note = f"; {grid.motion_runs} run(s) between neighbours naming different motions"
    if grid.unrefined:
        note += (
            f", {grid.unrefined} interval(s) between them left wider than the persistence "
            f"width {width:.3g} (refinement budget spent)"
        )
    else:
        note += f", every interval between them refined to the persistence width {width:.3g}"
    if grid.unrefined_at:
        mus = ", ".join(f"{mu:.6g}" for mu in grid.unrefined_at)
        note += f" (undetermined after every retry at mu = {mus}: refined around)"
    return note


def tail_notes(state, scan, vanished: int) -> str:
    """What a converged reason ends with: an adaptive prescan's count, vanished jumps."""
    notes = ""
    if len(scan) < len(state.mus):
        notes += f"; adaptive prescan ran {len(scan)} of {len(state.mus)} values"
    if vanished:
        notes += f"; {vanished} more vanished at stricter numerics"
    return notes
