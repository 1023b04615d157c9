"""Continuation through the kinks of a nonsmooth branch.

Where an orbit's switch sequence changes (a contact grazes, a stick phase appears or
goes), the branch has a kink: the stroboscopic map's Jacobian jumps, and a pseudo-
arclength corrector whose linear model was taken on one side may not reach the other
however short its step. There the branch is crossed at a fixed parameter
(``continuation.KINK_JUMPS``), and the branch goes on from there in the parameter's
direction.

The scene: the six-blade, three-mode packet (``scenes.modal_packet``) of the example
``fe_packet.py``, with its two shroud designs, swept up in speed from 2600 rpm with steps of
at most 5 % of the range.
"""

import importlib

import numpy as np
import pytest

import shroudnet as sn
from shroudnet.scenes import modal_packet

# the module, which the package's function of the same name hides
continuation_module = importlib.import_module("shroudnet.steady.continuation")

def upward(gap, max_points, crossings):
    """The branch of the packet with ``gap`` from 2600 rpm towards 3400, recording each
    fixed-parameter crossing in ``crossings`` as (parameter, found)."""
    original = continuation_module.Solver.across

    def across(self, point):
        found = original(self, point)
        crossings.append((point.parameter, found is not None))
        return found

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(continuation_module.Solver, "across", across)
        return sn.continuation(lambda speed: modal_packet(gap=gap, speed_rpm=speed),
                               2600.0, 3400.0, max_step=0.05, max_points=max_points,
                               parameter="speed_rpm")


def test_a_branch_crosses_the_kinks_where_its_orbits_change_their_switches():
    """The preloaded packet: arclength steps stall at 2634.32 rpm, where a stick phase
    appears (before kinks were crossed, the branch ended there); fixed-parameter steps
    of 1e-5 of the range cross it, and the branch goes on, its parameter rising and
    every orbit converged."""
    crossings = []
    branch = upward(-2e-6, 40, crossings)
    assert branch.ended == "reached max_points = 40"
    assert any(found and 2634.0 < p < 2635.0 for p, found in crossings), crossings
    assert branch.parameter[-1] > 2636.0   # measured 2638.5
    assert np.all(np.diff(branch.parameter) > 0.0)
    assert all(orbit.residual <= 10 * 1e-10 for orbit in branch.orbits)


def test_a_branch_goes_on_past_a_kink_where_the_orbit_jumps_aside():
    """The packet with a gap, near 2920.78 rpm: the fixed-parameter step across the kink
    lands on an orbit whose change from the last one points back along the branch, and
    so did the branch's tangent there, oriented by that change: the branch then went
    back down over the orbits it came along (to 2600 rpm). Going on in the parameter's
    direction, it passes the kink with its speed still rising, as the branch followed
    down from 3400 rpm passes it too (the example's figure). On the way, correctors
    whose residual stalls at the map's own noise, a few times the tolerance (4.6e-10
    against 1e-10), count as converged (``continuation.NOISE_FLOOR``)."""
    crossings = []
    branch = upward(2e-6, 135, crossings)
    assert any(found and 2920.7 < p < 2920.8 for p, found in crossings), crossings
    p = branch.parameter
    assert p[-1] > 2921.0 and np.all(np.diff(p) > 0.0), p[-10:]
