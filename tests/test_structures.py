"""Substructures in the engine: nodes of many degrees of freedom, interfaces between their
points, stick as constraints (DESIGN §7).

A scene of one-mass blades, each rebuilt as a ``Substructure`` of one degree of freedom,
runs through the other half of the engine (``records.StructureScene``: modal coordinates,
rows for the interfaces, constraints for stick), which shares none of the clusters' code
with the first: the two must give the same events, trajectories and Floquet multipliers.
"""


import numpy as np
import pytest

import shroudnet as sn
from contact_laws import Coulomb, LinearSpring
from shroudnet import scenes
from shroudnet.substructure import Substructure


def as_substructures(scene: sn.Scene) -> sn.Scene:
    """``scene`` with every Blade a one-degree-of-freedom Substructure whose point "x" is
    its displacement: the same physics, in the coordinates η = √m x."""
    old = scene.group
    group = sn.BladeGroup()
    for name, data in old.graph.nodes(data=True):
        body, motion = data["blade"], data.get("motion")
        if body is not None:
            group.add_blade(name, Substructure(
                [[body.mass]], [[body.stiffness_at(scene.speed_rpm)]], [[body.damping]],
                points={"x": [[1.0]]}, load="x", excitation_scale=body.excitation_scale))
        elif motion is not None:
            group.add_prescribed(name, motion)
        else:
            group.add_fixed(name)

    def end(node):
        return (node, "x") if old.graph.nodes[node]["blade"] is not None else node

    for left, right, interface in old.interfaces:
        group.connect(end(left), end(right), interface)
    for left, right, coupling in old.couplings:
        group.connect(end(left), end(right), coupling)
    group.graph.graph.update(old.graph.graph)
    return sn.Scene(group=group, excitation=scene.excitation, speed_rpm=scene.speed_rpm)


def stuck_ring():
    """Four blades in a preloaded ring that stick, break away, reverse and separate."""
    interface = sn.Interface(gap=-1e-5, angle=0.4, normal=LinearSpring(stiffness=3e5),
                             friction=Coulomb(mu=0.6))
    return sn.Scene(group=sn.BladeGroup.ring(
        4, sn.Blade(mass=0.08, damping=4.0, stiffness=1.5e5), interface),
        excitation=sn.Excitation(engine_order=1, amplitudes=(0.0, 30.0),
                                 phases=sn.EngineOrderWave()), speed_rpm=3000.0)


def switches(log, period):
    """(time in periods, interface, kind) of every logged switch, ordered by time to
    1e-6 periods, then interface and kind."""
    order = np.lexsort((log.kind, log.interface, np.round(log.time / period, 6)))
    return log.time[order] / period, log.interface[order], log.kind[order]


#: The two halves round differently (η = √m x; the couplings as a matrix), so their
#: trajectories part by the integrator's error: run both close to exact.
TIGHT = sn.Adaptive(rtol=1e-10)

CASES = {
    "paper group": (scenes.three_blade_paper, 40),
    "stuck ring (redundant constraints)": (stuck_ring, 30),
    "bladed disc (couplings)": (scenes.bladed_disc_24, 4),
    "block on a belt (prescribed motion)": (scenes.block_on_belt, 20),
}


@pytest.mark.parametrize("name", CASES)
def test_one_dof_substructures_reproduce_the_blades(name):
    make, periods = CASES[name]
    scene = make()
    blades, structures = (sn.simulate(one, periods, method=TIGHT)
                          for one in (scene, as_substructures(scene)))
    assert structures.scene.arrays.is_structure and not scene.arrays.is_structure
    assert structures.events.counts == blades.events.counts
    # the same switches, at the same times (where several fall together, as round a
    # symmetric disc, rounding may log them in another order)
    period = scene.excitation_period
    for expected, got in zip(switches(blades.events, period),
                             switches(structures.events, period)):
        np.testing.assert_allclose(got, expected, rtol=0, atol=1e-8)
    x = structures.x / np.sqrt(scene.arrays.mass)  # η = √m x
    amplitude = np.abs(blades.x).max()
    assert np.abs(x - blades.x).max() <= 1e-8 * amplitude
    assert np.allclose(structures.energy.excitation_work, blades.energy.excitation_work,
                       rtol=1e-8)
    assert abs(structures.energy.residual) <= 1e-6 * abs(structures.energy.excitation_work)
