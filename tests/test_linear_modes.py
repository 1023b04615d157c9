"""The group's linear modes in the open and stuck limits, by nodal diameter, and its
Campbell diagram; checked against closed forms of spring–mass chains and rings."""

import math

import numpy as np
import pytest

from contact_laws import Coulomb, LinearSpring
from shroudnet import (
    AntiPhase,
    Blade,
    BladeGroup,
    Coupling,
    Excitation,
    Interface,
    Scene,
    Southwell,
    group_campbell,
    linear_modes,
)
from shroudnet.linear.modes import excited_diameter

MASS, GROUND, LINK = 0.1, 1e5, 2e4
EXCITATION = Excitation(engine_order=1, amplitudes=(0.0, 1.0), phases=AntiPhase())


def scene_of(group, speed_rpm=6000.0):
    return Scene(group=group, excitation=EXCITATION, speed_rpm=speed_rpm)


def hz(stiffness, mass):
    return math.sqrt(stiffness / mass) / (2.0 * math.pi)


@pytest.mark.parametrize("n", [3, 7, 24])
def test_a_tuned_ring_of_coupled_masses_has_the_cyclic_chains_closed_form(n):
    """ω_ND² = (k + 4 k_c sin²(π ND / N)) / m, one mode at ND = 0 (and N/2), two at the
    others."""
    ring = BladeGroup.ring(n, Blade(mass=MASS, damping=0.0, stiffness=GROUND),
                           Coupling(stiffness=LINK))
    modes = linear_modes(scene_of(ring))
    for nd in range(n // 2 + 1):
        expected = hz(GROUND + 4 * LINK * math.sin(math.pi * nd / n) ** 2, MASS)
        found = modes.of_diameter(nd)
        assert len(found) == (1 if nd == 0 or 2 * nd == n else 2)
        assert found == pytest.approx(expected, rel=1e-12)
    assert np.all(np.diff(modes.frequencies) >= 0.0)
    assert np.allclose(modes.shapes.T @ np.diag(ring_masses(n)) @ modes.shapes, np.eye(n))
    assert modes.families()[:, 0] == pytest.approx(
        [hz(GROUND + 4 * LINK * math.sin(math.pi * nd / n) ** 2, MASS)
         for nd in range(n // 2 + 1)], rel=1e-12)


def ring_masses(n):
    return np.full(n, MASS)


def test_a_mode_shape_of_diameter_nd_varies_round_the_ring_as_cos():
    n = 12
    ring = BladeGroup.ring(n, Blade(mass=MASS, damping=0.0, stiffness=GROUND),
                           Coupling(stiffness=LINK))
    modes = linear_modes(scene_of(ring))
    shape = modes.shapes[:, np.flatnonzero(modes.nodal_diameters == 3)[0]]
    s = np.arange(n)
    basis = np.column_stack([np.cos(2 * np.pi * 3 * s / n), np.sin(2 * np.pi * 3 * s / n)])
    fitted = basis @ np.linalg.lstsq(basis, shape, rcond=None)[0]
    assert np.abs(fitted - shape).max() < 1e-12 * np.abs(shape).max()


def pair(interface):
    group = BladeGroup().add_blade("a", Blade(mass=0.1, damping=0.0, stiffness=1e5))
    group.add_blade("b", Blade(mass=0.3, damping=0.0, stiffness=2e5))
    return scene_of(group.connect("a", "b", interface))


def test_stuck_interfaces_move_their_blades_as_one_body():
    scene = pair(Interface(gap=1e-5, angle=0.4, normal=LinearSpring(stiffness=1e6),
                           friction=Coulomb(mu=0.3)))
    assert linear_modes(scene, "stuck").frequencies == pytest.approx([hz(3e5, 0.4)])
    assert linear_modes(scene, "open").frequencies == pytest.approx(
        sorted([hz(1e5, 0.1), hz(2e5, 0.3)]))


def test_a_closed_frictionless_contact_is_a_spring_of_its_stiffness_along_x():
    angle, contact = 0.7, 1e6
    scene = pair(Interface(gap=-1e-5, angle=angle, normal=LinearSpring(stiffness=contact)))
    spring = contact * math.sin(angle) ** 2
    stiffness = np.array([[1e5 + spring, -spring], [-spring, 2e5 + spring]])
    expected = np.sqrt(np.linalg.eigvals(np.linalg.solve(np.diag([0.1, 0.3]), stiffness)))
    assert linear_modes(scene, "stuck").frequencies == pytest.approx(
        np.sort(expected) / (2 * math.pi), rel=1e-12)
    gapped = pair(Interface(gap=1e-5, angle=angle, normal=LinearSpring(stiffness=contact)))
    assert linear_modes(gapped, "stuck").frequencies == pytest.approx(
        linear_modes(gapped, "open").frequencies)  # open at rest: no spring


def test_a_blade_stuck_to_a_fixed_node_does_not_move():
    group = BladeGroup().add_fixed("disc").add_blade("a", Blade(mass=0.1, damping=0.0,
                                                                stiffness=1e5))
    group.add_blade("b", Blade(mass=0.2, damping=0.0, stiffness=1e5))
    shroud = Interface(gap=0.0, angle=0.3, normal=LinearSpring(stiffness=1e6),
                       friction=Coulomb(mu=0.5))
    group.connect("disc", "a", shroud).connect("a", "b", Coupling(stiffness=5e4))
    modes = linear_modes(scene_of(group), "stuck")
    assert modes.frequencies == pytest.approx([hz(1.5e5, 0.2)])
    assert modes.shapes[0, 0] == 0.0


def test_a_bladed_disc_stiffens_when_its_shrouds_stick():
    blade = Blade(mass=0.05, damping=0.0, stiffness=0.0)
    disc = BladeGroup.bladed_disc(
        8, disc=Blade(mass=0.5, damping=0.0, stiffness=4e6), disc_coupling=Coupling(
            stiffness=2e6), blade=[blade, blade],
        blade_couplings=[Coupling(stiffness=8e5), Coupling(stiffness=4e5)],
        shroud=Interface(gap=0.0, angle=0.5, normal=LinearSpring(stiffness=1e6),
                         friction=Coulomb(mu=0.4)))
    open_, stuck = (linear_modes(scene_of(disc), c) for c in ("open", "stuck"))
    assert open_.sectors == stuck.sectors == 8 and len(open_.frequencies) == 24
    # Stuck shrouds tie every tip to its neighbours: 8 tips become one body.
    assert len(stuck.frequencies) == 24 - 7
    for nd in range(1, 5):  # the tips are held: the first blade family rises
        assert stuck.of_diameter(nd)[0] > open_.of_diameter(nd)[0]
    assert np.isnan(stuck.families()[1:, 2]).all() and not np.isnan(open_.families()).any()


def test_engine_orders_excite_one_diameter_and_the_campbell_diagram_finds_crossings():
    orders = (1, 12, 23, 25, 36, 48)
    assert [excited_diameter(order, 24) for order in orders] == [1, 12, 1, 1, 12, 0]
    blade = Blade(mass=MASS, damping=0.0, frequency=Southwell(f0=150.0, coefficient=4.0))
    ring = BladeGroup.ring(6, blade, Coupling(stiffness=LINK))
    campbell = group_campbell(scene_of(ring), np.linspace(1000.0, 12000.0, 23),
                              engine_orders=(2, 3, 4, 6))
    assert campbell.frequencies.shape == (23, 6)
    for order, mode, speed, frequency in campbell.crossings:
        nd = excited_diameter(order, 6)
        k = blade.stiffness_at(speed)
        assert frequency == pytest.approx(
            hz(k + 4 * LINK * math.sin(math.pi * nd / 6) ** 2, MASS), rel=1e-8)
        assert frequency == pytest.approx(order * speed / 60.0)
    # l = 2 never catches the stiffening blade (f² = f0² + 4 (Ω/60)²); ND 3 and ND 0 do.
    assert {order for order, *_ in campbell.crossings} == {3, 4, 6}
    from shroudnet.front.figures import group_campbell_diagram
    axes = group_campbell_diagram(campbell, modes=4).axes[0]
    assert len(axes.lines) >= 4 + 1 + 4  # modes, legend entry, four engine orders


def test_bad_arguments_are_refused():
    ring = scene_of(BladeGroup.ring(6, Blade(mass=MASS, damping=0.0, stiffness=GROUND),
                                    Coupling(stiffness=LINK)))
    with pytest.raises(ValueError, match="contacts must be one of"):
        linear_modes(ring, "closed")
    with pytest.raises(ValueError, match="sectors = 4 does not divide the 6 blades"):
        linear_modes(ring, sectors=4)
    chain = scene_of(BladeGroup.chain(3, Blade(mass=MASS, damping=0.0, stiffness=GROUND),
                                      Coupling(stiffness=LINK)))
    with pytest.raises(ValueError, match="not sorted by nodal diameter"):
        linear_modes(chain).of_diameter(0)
