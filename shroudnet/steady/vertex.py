"""The vertex of the parabola through three evenly spaced samples: where a sampled
maximum lies between the samples, and its value."""


def parabola_vertex(before: float, at: float, after: float) -> tuple[float, float]:
    """(shift, top) of the parabola through (−1, ``before``), (0, ``at``) and (1, ``after``):
    its vertex's abscissa, in sample spacings from the middle one, and its value,

        shift = (before − after) / (2 c),   top = at − (before − after) shift / 4,

    c = before − 2 at + after; (0, ``at``) where the parabola does not open downward
    (c ≥ 0). Where ``at`` is the largest of the three, |shift| ≤ ½."""
    curvature = before - 2.0 * at + after
    if curvature >= 0.0:
        return 0.0, at
    shift = 0.5 * (before - after) / curvature
    return shift, at - 0.25 * (before - after) * shift
