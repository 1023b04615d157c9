"""Hysteresis loops: an interface's friction force against its tangential relative
displacement, whose area is the energy friction takes, held to the energy ledger (the
friction power integrated with the steps, not read from samples)."""

import math

import numpy as np
import pytest

import shroudnet as sn
from contact_laws import Coulomb
from shroudnet import scenes

SCENES = {
    "paper group, sticking": scenes.three_blade_paper(gamma1=2.2, friction=Coulomb(mu=0.3)),
    "modal packet": scenes.modal_packet(),
    "block on a belt": scenes.block_on_belt(),
}


@pytest.mark.parametrize("scene", SCENES.values(), ids=SCENES.keys())
def test_the_loops_area_is_the_friction_loss_and_converges_with_the_sampling(scene):
    errors = []
    for samples in (500, 2000):
        sim = sn.simulate(scene, 10, samples_per_period=samples,
                          method=sn.Adaptive(rtol=1e-10))
        area = sum(sn.hysteresis_loop(sim, e, 2).area_per_cycle()
                   for e in range(scene.arrays.n_interfaces))
        reference = sn.friction_loss_per_cycle(sim, 2)  # integrated with the steps
        assert reference > 0.0
        errors.append(abs(area / reference - 1.0))
    # measured: 1.5e-4 → 6.6e-6 (paper), 8.4e-5 → 4.7e-6 (packet), 3.9e-7 → 2.9e-8 (belt):
    # the trapezoidal rule's second order
    assert errors[1] <= 2e-5 and errors[1] <= errors[0] / 10.0


def test_the_slip_displacement_moves_at_the_slip_velocity_of_blades():
    scene = SCENES["paper group, sticking"]
    sim = sn.simulate(scene, 3, samples_per_period=4000)
    cos_alpha = math.cos(math.pi / 3)
    for e, (i, j) in enumerate(((0, 1), (1, 2))):
        slip = sim.slip_displacement(e)
        assert slip == pytest.approx((sim.x[:, i] - sim.x[:, j]) * cos_alpha, abs=1e-18)
        velocity = (sim.v[:, i] - sim.v[:, j]) * cos_alpha
        assert sim.slip_velocity(e) == pytest.approx(velocity, abs=1e-15)
        rate = np.gradient(slip, sim.t)[1:-1]
        assert np.abs(rate - velocity[1:-1]).max() <= 1e-3 * np.abs(velocity).max()


def test_the_slip_displacement_of_substructures_is_along_the_tangent_between_points():
    scene = SCENES["modal packet"]
    sim = sn.simulate(scene, 2, samples_per_period=400)
    tangent = np.array([-math.sin(0.6), math.cos(0.6)])      # scenes.modal_packet's face
    for e in range(5):
        a, b = f"blade{e + 1}", f"blade{e + 2}"
        expected = (sim.displacement(a, "shroud") - sim.displacement(b, "shroud")) @ tangent
        assert sim.slip_displacement(e) == pytest.approx(expected, rel=1e-12, abs=1e-18)


def test_a_belt_counts_its_prescribed_motion():
    """The block on the belt slips against the belt's displacement v_b t: u_t = x − v_b t
    (the interface joins the block to the belt, at α = 0)."""
    scene = SCENES["block on a belt"]
    sim = sn.simulate(scene, 2, samples_per_period=100)
    belt = scene.group.prescribed[0][1]
    assert sim.slip_displacement(0) == pytest.approx(
        sim.x[:, 0] - belt.displacement_at(sim.t), rel=1e-12, abs=1e-15)
    assert sim.slip_velocity(0) == pytest.approx(sim.v[:, 0] - belt.velocity_at(sim.t),
                                                 rel=1e-12, abs=1e-15)


@pytest.mark.parametrize("interface", [-1, 2, 1.5, "first"])
def test_an_interface_that_is_not_there_is_refused_by_name(interface):
    sim = sn.simulate(SCENES["paper group, sticking"], 1, samples_per_period=10)
    for method in (sim.slip_displacement, sim.slip_velocity):
        with pytest.raises((TypeError, ValueError), match="interface"):
            method(interface)
    with pytest.raises((TypeError, ValueError), match="hysteresis_loop.interface"):
        sn.hysteresis_loop(sim, interface, 0)


def test_a_whole_float_skip_reads_the_same_cycles_as_its_int():
    """``skip`` may be a float of integral value (as every reading of a steady response
    takes it): the loop's cycles and the loss per cycle are those of the int."""
    sim = sn.simulate(SCENES["paper group, sticking"], 3, samples_per_period=50)
    for skip in (0, 2):
        loop, same = sn.hysteresis_loop(sim, 0, float(skip)), sn.hysteresis_loop(sim, 0, skip)
        assert type(loop.cycles) is int and loop.cycles == 3 - skip
        assert loop.area_per_cycle() == same.area_per_cycle()
        assert sn.friction_loss_per_cycle(sim, float(skip)) == \
            sn.friction_loss_per_cycle(sim, skip)
