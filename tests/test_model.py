"""The model layer: blades, interfaces, groups, excitation, scenes, and their validation."""

import math

import networkx as nx
import numpy as np
import pytest

from contact_laws import Coulomb, ExponentialFriction, Hertz, LinearSpring
from shroudnet import (AntiPhase, Blade, BladeGroup, ConstantFrequency, Excitation,
                       FrequencyTable, Interface, Scene, Southwell, TravellingWave, scenes)

BLADE = Blade(mass=0.1, damping=1.0, stiffness=1e5)
SHROUD = Interface(gap=1e-5, angle=0.5, normal=LinearSpring(stiffness=1e5),
                   friction=Coulomb(mu=0.3))
EXCITATION = Excitation(engine_order=2, amplitudes=(0.0, 10.0), phases=AntiPhase())


@pytest.mark.parametrize("make, error, message", [
    (lambda: Blade(mass=-1.0, damping=1.0, stiffness=1.0), ValueError,
     r"Blade\.mass must be in \(0, inf\) kg, got -1"),
    (lambda: Blade(mass=float("nan"), damping=1.0, stiffness=1.0), ValueError,
     r"Blade\.mass must be a number in \(0, inf\) kg, got NaN"),
    (lambda: Blade(mass=1.0, damping=-1.0, stiffness=1.0), ValueError, r"Blade\.damping"),
    (lambda: Blade(mass=1.0, damping=1.0), ValueError, r"exactly one of stiffness"),
    (lambda: Blade(mass=1.0, damping=1.0, stiffness=1.0, frequency=2.0), ValueError,
     r"exactly one of stiffness"),
    (lambda: Interface(gap=0.0, angle=2.0, normal=LinearSpring(stiffness=1.0)), ValueError,
     r"Interface\.angle must be in \[0, 1.5708\] rad, got 2"),
    (lambda: Interface(gap=0.0, angle=-0.1, normal=LinearSpring(stiffness=1.0)), ValueError,
     r"Interface\.angle"),
    (lambda: Interface(gap=float("nan"), angle=0.1, normal=LinearSpring(stiffness=1.0)),
     ValueError, r"Interface\.gap .*NaN"),
    (lambda: Interface(gap=0.0, angle=0.1, normal=Coulomb(mu=0.1)), TypeError,
     r"Interface\.normal must be a contact_laws\.NormalLaw"),
    (lambda: Interface(gap=0.0, angle=0.1, normal=LinearSpring(stiffness=1.0),
                       friction=LinearSpring(stiffness=1.0)), TypeError, r"Interface\.friction"),
    (lambda: BladeGroup().add_blade("a", BLADE).connect("a", "ghost", SHROUD), ValueError,
     r"unknown node 'ghost'"),
    (lambda: BladeGroup().add_blade("a", BLADE).add_blade("a", BLADE), ValueError,
     r"node 'a' is already in the group"),
    (lambda: BladeGroup().add_blade("a", BLADE).connect("a", "a", SHROUD), ValueError,
     r"needs two nodes"),
    (lambda: BladeGroup().add_fixed("d").add_fixed("c").connect("d", "c", SHROUD), ValueError,
     r"neither node is a blade \(both are fixed or prescribed\)"),
    (lambda: BladeGroup.chain(2, BLADE, SHROUD).connect(("blade2", ["x", "x"]), "blade1",
                                                         SHROUD), ValueError,
     r"both ends name as many points \(or one end is a fixed or prescribed node\); got 2 "
     r"and 1"),
    (lambda: BladeGroup.ring(2, BLADE, SHROUD), ValueError, r"ring needs n >= 3"),
    (lambda: BladeGroup.chain(3, [BLADE, BLADE], SHROUD), ValueError, r"2 blades for n = 3"),
    (lambda: Scene(group=BladeGroup().add_fixed("disc"), excitation=EXCITATION,
                   speed_rpm=100.0), ValueError, r"Scene\.group has no blades"),
    (lambda: Scene(group=BladeGroup.chain(3, BLADE, SHROUD), excitation=EXCITATION,
                   speed_rpm=-5.0), ValueError, r"Scene\.speed_rpm must be in \(0, inf\) rpm"),
    (lambda: Scene(group=BladeGroup.chain(3, BLADE, SHROUD),
                   excitation=Excitation(engine_order=1, amplitudes=(0, 1), phases=[0.0, 1.0]),
                   speed_rpm=5.0), ValueError, r"2 phases for 3 blades"),
    (lambda: Excitation(engine_order=0, amplitudes=(0, 1), phases=AntiPhase()), ValueError,
     r"engine_order must be an int >= 1"),
    (lambda: Excitation(engine_order=1, amplitudes=(), phases=AntiPhase()), ValueError,
     r"at least q0"),
    (lambda: FrequencyTable(speeds_rpm=(0, 100, 50), frequencies=(1, 2, 3)), ValueError,
     r"increase strictly"),
    (lambda: Scene(group=BladeGroup().add_blade("a", Blade(
        mass=1.0, damping=0.0, frequency=FrequencyTable(speeds_rpm=(0, 1000),
                                                        frequencies=(100, 110)))),
        excitation=Excitation(engine_order=1, amplitudes=(0,), phases=[0.0]), speed_rpm=2000.0),
     ValueError, r"outside the FrequencyTable range \[0, 1000\] rpm"),
    (lambda: scenes.three_blade_paper(gamma1=2.0, normal=Hertz(stiffness=1e9)), ValueError,
     r"gamma1 .* or normal .* not both"),
    (lambda: scenes.three_blade_paper(gamma1=-1.0), ValueError,
     r"three_blade_paper\.gamma1 must be in \(0, inf\)"),
])
def test_bad_input_fails_early_naming_the_field(make, error, message):
    with pytest.raises(error, match=message):
        make()


def test_frequency_models_and_stiffness():
    assert ConstantFrequency(hz=100.0).at(5000.0) == 100.0
    southwell = Southwell(f0=100.0, coefficient=2.0)
    assert southwell.at(6000.0) == pytest.approx(math.sqrt(100.0**2 + 2.0 * 100.0**2))
    table = FrequencyTable(speeds_rpm=(0, 1000, 2000), frequencies=(100, 110, 130))
    assert table.at(1500.0) == pytest.approx(120.0)
    blade = Blade(mass=0.5, damping=0.0, frequency=table)
    assert blade.stiffness_at(1500.0) == pytest.approx(0.5 * (2 * math.pi * 120.0) ** 2)
    assert blade.frequency_at(1500.0) == pytest.approx(120.0)
    assert Blade(mass=1.0, damping=0.0, frequency=50.0).frequency == ConstantFrequency(hz=50.0)


def test_presets_chain_ring_and_fixed_nodes():
    ring = BladeGroup.ring(5, BLADE, SHROUD)
    assert ring.interfaces[-1][:2] == ("blade5", "blade1")
    assert [(a, b) for a, b, _ in BladeGroup.chain(3, BLADE, SHROUD).interfaces] == [
        ("blade1", "blade2"), ("blade2", "blade3")]
    group = BladeGroup().add_blade("b", BLADE).add_fixed("casing").connect("casing", "b", SHROUD)
    scene = Scene(group=group, excitation=Excitation(engine_order=1, amplitudes=(0, 1),
                                                     phases=[0.0]), speed_rpm=10.0)
    assert scene.arrays.left.tolist() == [-1] and scene.arrays.right.tolist() == [0]
    assert group.fixed == ["casing"] and scene.blades == ["b"]


def test_scene_freezes_a_copy_of_its_group():
    group = BladeGroup.chain(3, BLADE, SHROUD)
    scene = Scene(group=group, excitation=EXCITATION, speed_rpm=3000.0)
    group.add_blade("late", BLADE)
    assert scene.blades == ["blade1", "blade2", "blade3"]
    first, _, last = scene.blades
    with pytest.raises(nx.NetworkXError, match="Frozen graph can't be modified"):
        scene.group.add_blade("later", BLADE)
    with pytest.raises(nx.NetworkXError, match="Frozen graph can't be modified"):
        scene.group.connect(last, first, SHROUD)
    assert scene.blades == ["blade1", "blade2", "blade3"] and len(scene.group.interfaces) == 2


def test_phase_patterns():
    assert np.allclose(AntiPhase().phases(3), [0.0, math.pi, 2 * math.pi])
    assert np.allclose(TravellingWave(2).phases(8), 2 * math.pi * 2 * np.arange(8) / 8)


def test_blade_position_by_name_or_index():
    scene = scenes.three_blade_paper()
    assert scene.blade_position("blade2") == 1 == scene.blade_position(1)
    with pytest.raises(ValueError, match="unknown blade 'blade9'"):
        scene.blade_position("blade9")
    with pytest.raises(ValueError, match="unknown blade 3"):
        scene.blade_position(3)


def test_cos_angle_is_exactly_zero_at_a_right_angle_so_friction_cannot_hold():
    shroud = Interface(gap=0.0, angle=math.pi / 2, normal=LinearSpring(stiffness=1e5),
                       friction=Coulomb(mu=0.3))
    scene = Scene(group=BladeGroup.chain(2, BLADE, shroud), excitation=EXCITATION,
                  speed_rpm=1000.0)
    assert scene.arrays.cos_angle[0] == 0.0 and not scene.arrays.can_stick[0]


class TestPaperScene:
    def test_f0_is_the_cantilever_with_shroud_and_blade_effective_mass(self):
        assert scenes.paper_frequency_model().f0 == pytest.approx(194.6, abs=0.05)

    def test_resonance_at_6487_5_rpm_with_engine_order_2(self):
        scene = scenes.three_blade_paper(speed_rpm=6487.5)
        f_e = scene.excitation.frequency_at(6487.5)
        assert f_e == pytest.approx(216.25)
        assert scenes.paper_frequency_model().at(6487.5) == pytest.approx(f_e, rel=5e-4)

    def test_parameters_from_section_3(self):
        scene = scenes.three_blade_paper(gamma1=3.5, speed_rpm=6000.0, q1=50.0)
        a = scene.arrays
        assert a.mass.tolist() == [0.082] * 3 and a.damping.tolist() == [4.0] * 3
        k = 0.082 * (2 * math.pi * scenes.paper_frequency_model().at(6000.0)) ** 2
        np.testing.assert_allclose(a.stiffness, k)
        assert a.normal_laws[0] == LinearSpring(stiffness=3.5 * k)
        assert a.friction_laws[1] == ExponentialFriction(mu_static=0.5, mu_kinetic=0.3, beta=5.0)
        assert a.gap.tolist() == [2e-5, 2e-5]
        np.testing.assert_allclose(a.sin_angle, math.sin(math.pi / 3))
        np.testing.assert_allclose(a.phases, [0.0, math.pi, 2 * math.pi])
        assert a.excitation_frequency == pytest.approx(2 * 6000.0 * 2 * math.pi / 60.0)
        assert scene.excitation_period == pytest.approx(60.0 / (2 * 6000.0))

    def test_overrides(self):
        scene = scenes.three_blade_paper(gap=(1e-5, 3e-5), alpha=0.3, friction=None,
                                         normal=Hertz(stiffness=1e9), q1=5.0)
        a = scene.arrays
        assert a.gap.tolist() == [1e-5, 3e-5] and a.friction_laws == (None, None)
        assert a.normal_laws[0] == Hertz(stiffness=1e9) and a.amplitudes.tolist() == [0.0, 5.0]
        assert not a.can_stick.any()
