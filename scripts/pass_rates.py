"""The factor per pass by which an iterative loop's residual falls, fitted to one step's residuals.

scripts/make-lab-report fits it for its rates table and states it on its convergence figures; both
use fit_rate, so a figure's curve and the table's rows are the same fit.
"""
import math

# Residuals at or below this are rounding (a resting contact's exact zero), not convergence.
RATE_FLOOR = 1e-13


def fit_rate(residuals, floor=RATE_FLOOR):
    """A least-squares line through log(residual) against the pass (0 for the first), over the
    passes whose residual is above floor: (factor per pass, fitted residual at pass 0, passes
    fitted), or None when fewer than three passes are above floor."""
    points = [(k, math.log(r)) for k, r in enumerate(residuals) if r > floor]
    if len(points) < 3:
        return None
    n = len(points)
    mk, ml = sum(k for k, _ in points) / n, sum(v for _, v in points) / n
    slope = sum((k - mk) * (v - ml) for k, v in points) / sum((k - mk) ** 2 for k, _ in points)
    return math.exp(slope), math.exp(ml - slope * mk), n


def fitted_rate(residuals, floor=RATE_FLOOR):
    """The factor per pass alone (see fit_rate); None when it cannot be fitted."""
    fit = fit_rate(residuals, floor)
    return fit[0] if fit else None
