"""Continuation through the kinks of a nonsmooth branch.

Where an orbit's switch sequence changes (a contact grazes, a stick phase appears or
goes), the branch has a kink: the stroboscopic map's Jacobian jumps, and a pseudo-
arclength corrector whose linear model was taken on one side may not reach the other
however short its step. There the branch is crossed at a fixed parameter
(``continuation.KINK_JUMPS``) from the secant through its last two points, the kink is
located by bisection on the parameter and reported with it, and the branch goes on from
there in the parameter's direction, its steps never below the jumps.

The scene: the six-blade, three-mode packet (``scenes.modal_packet``) of the example
``fe_packet.py``, with its two shroud designs, swept up in speed from 2600 rpm with steps of
at most 5 % of the range.
"""

import numpy as np

import shroudnet as sn
from shroudnet.scenes import modal_packet


def upward(gap, max_points):
    """The branch of the packet with ``gap`` from 2600 rpm towards 3400."""
    return sn.continuation(lambda speed: modal_packet(gap=gap, speed_rpm=speed),
                           2600.0, 3400.0, max_step=0.05, max_points=max_points,
                           parameter="speed_rpm")


def test_a_branch_crosses_the_kinks_where_its_orbits_change_their_switches_and_names_them():
    """The preloaded packet: at 2634.3 rpm a stick phase appears (before kinks were
    crossed, the branch ended there; then, it crawled on to 2638.5 rpm in 40 points);
    the kink is reported there, located to a fraction of an rpm, every other change of
    the switches too, and the branch goes on, its parameter rising and every orbit
    converged (measured: 2669.7 rpm after 40 points, twelve kinks)."""
    branch = upward(-2e-6, 40)
    kinks = [b for b in branch.bifurcations if b.kink]
    assert all(b.kind in ("grazing", "stick-slip") for b in kinks)
    stick = [b for b in kinks if 2634.0 < b.parameter < 2635.0]
    assert [b.kind for b in stick] == ["stick-slip"]
    low, high = stick[0].bracket
    assert low <= stick[0].parameter <= high and high - low < 1.0
    assert branch.parameter[-1] > 2660.0
    assert np.all(np.diff(branch.parameter) > 0.0)
    assert all(orbit.residual <= 10 * 1e-10 for orbit in branch.orbits)
    for kink in kinks:  # each between the points whose switches differ
        i = kink.index
        assert branch.orbits[i].switches != branch.orbits[i + 1].switches


def test_a_branch_goes_on_past_a_kink_where_the_orbit_jumps_aside():
    """The packet with a gap, near 2920.78 rpm: across the kink the orbit's change points
    back along the branch, and so did the branch's tangent there, oriented by that
    change: the branch once went back down over the orbits it came along (to 2600 rpm).
    Going on in the parameter's direction, it passes the kink with its speed still
    rising, as the branch followed down from 3400 rpm passes it too (the example's
    figure), and reports the stick phases that change there."""
    branch = upward(2e-6, 135)
    p = branch.parameter
    assert p[-1] > 2921.0 and np.all(np.diff(p) > 0.0), p[-10:]
    assert any(b.kind == "stick-slip" and 2918.0 < b.parameter < 2923.0
               for b in branch.bifurcations)
