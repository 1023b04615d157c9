"""Properties of the assembled dynamics that hold for any group, laws and state."""

import math

import networkx as nx
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from contact_laws import Coulomb, LinearSpring
from shroudnet import (Blade, BladeGroup, Excitation, ExplicitPhases, Interface, Mode, Scene,
                       assemble, stick_clusters)
from shroudnet.clusters import cluster_labels
from tests.groups import GAP, external_forces, incidence, scenes, states


def _assembled(data, scene, **kwargs):
    t, x, v, modes = data.draw(states(scene, **kwargs))
    return (t, x, v, modes), assemble(scene, t, x, v, modes)


@given(st.data())
def test_equation_of_motion_holds_with_the_returned_interface_forces(data):
    """M ẍ = Q − C ẋ − K x − Bᵀ F (paper eq. 7, DESIGN §2), static friction included."""
    scene = data.draw(scenes())
    (t, x, v, modes), r = _assembled(data, scene)
    a = scene.arrays
    rhs = external_forces(scene, t, x, v) - incidence(scene).T @ r.interface_force
    scale = np.abs(external_forces(scene, t, x, v)).max() + np.abs(r.interface_force).max() + 1
    np.testing.assert_allclose(a.mass * r.acceleration, rhs, atol=1e-9 * scale)
    np.testing.assert_allclose(r.interface_force,
                               r.normal_force * a.sin_angle + r.friction_force * a.cos_angle)
    stuck = modes == Mode.STICK
    np.testing.assert_allclose((incidence(scene) @ r.acceleration)[stuck], 0.0,
                               atol=1e-12 * (np.abs(r.acceleration).max() + 1))


@given(st.data())
def test_interface_forces_cancel_in_pairs(data):
    """Without fixed nodes the interfaces only move momentum between blades."""
    scene = data.draw(scenes(shapes=("chain", "ring")))
    (t, x, v, _), r = _assembled(data, scene)
    external = external_forces(scene, t, x, v)
    total = scene.arrays.mass @ r.acceleration
    assert total == pytest.approx(external.sum(), abs=1e-9 * (np.abs(external).sum()
                                                              + np.abs(r.interface_force).sum()))


def _mirror(scene):
    """The chain seen in a mirror: blades in reverse order, x → −x, Q → −Q."""
    group, n = scene.group, len(scene.blades)
    names = scene.blades
    mirrored = BladeGroup()
    for name in reversed(names):
        mirrored.add_blade(name, group.blade(name))
    for left, right, interface in reversed(group.interfaces):
        mirrored.connect(right, left, interface)
    amplitudes = (-scene.excitation.amplitudes[0],) + scene.excitation.amplitudes[1:]
    phases = ExplicitPhases(tuple(scene.arrays.phases[::-1] + math.pi))
    excitation = Excitation(engine_order=scene.excitation.engine_order, amplitudes=amplitudes,
                            phases=phases)
    assert n == len(mirrored.blades)
    return Scene(group=mirrored, excitation=excitation, speed_rpm=scene.speed_rpm)


@given(st.data())
def test_mirror_image_groups_give_mirror_image_forces(data):
    scene = data.draw(scenes(shapes=("chain",)))
    (t, x, v, modes), r = _assembled(data, scene)
    mirror = assemble(_mirror(scene), t, -x[::-1], -v[::-1], modes[::-1])
    scale = np.abs(r.acceleration).max() + 1
    np.testing.assert_allclose(mirror.acceleration, -r.acceleration[::-1], atol=1e-9 * scale)
    force_scale = np.abs(r.interface_force).max() + 1
    np.testing.assert_allclose(mirror.normal_force, r.normal_force[::-1], atol=1e-9 * force_scale)
    np.testing.assert_allclose(mirror.friction_force, r.friction_force[::-1],
                               atol=1e-9 * force_scale)


@given(st.data())
def test_friction_never_exceeds_the_static_limit_unless_flagged(data):
    """Sliding friction stays within μ_s N; static friction beyond it shows as a negative guard."""
    scene = data.draw(scenes())
    (_, _, _, modes), r = _assembled(data, scene)
    a = scene.arrays
    limit = a.static_mu * r.normal_force
    sliding = modes != Mode.STICK
    assert np.all(np.abs(r.friction_force[sliding]) <= limit[sliding] * (1 + 1e-12) + 1e-300)
    stuck = modes == Mode.STICK
    np.testing.assert_allclose(r.motion_guard[stuck],
                               limit[stuck] - np.abs(r.friction_force[stuck]))


@given(st.data())
def test_all_stuck_chain_moves_as_one_body(data):
    """One cluster: ẍ = (Σ Q − Σc ẋ − Σ k x)/Σ m, the single body with summed m, c and k."""
    scene = data.draw(scenes(shapes=("chain",)))
    a = scene.arrays
    t, x, v, modes = data.draw(states(scene, stick=st.just(True)))
    if not np.all(modes == Mode.STICK):
        return  # some contact is open or cannot stick: not this property's case
    r = assemble(scene, t, x, v, modes)
    body = external_forces(scene, t, x, v).sum() / a.mass.sum()
    np.testing.assert_allclose(r.acceleration, body, rtol=1e-9, atol=1e-9 * abs(body) + 1e-9)
    assert len(r.grounded) == 1


@given(st.data())
def test_blades_decouple_when_every_contact_is_open(data):
    scene = data.draw(scenes())
    a = scene.arrays
    t, x, v, _ = data.draw(states(scene))
    modes = np.full(a.n_interfaces, Mode.OPEN)
    r = assemble(scene, t, x, v, modes)
    np.testing.assert_allclose(r.acceleration, external_forces(scene, t, x, v) / a.mass,
                               rtol=1e-12, atol=1e-9)
    assert not r.normal_force.any() and not r.friction_force.any()


@given(st.data())
def test_compiled_cluster_labels_are_the_graphs_stick_clusters(data):
    """Same partition of the blades, with all fixed nodes taken as one ground."""
    scene = data.draw(scenes())
    a = scene.arrays
    stuck = np.array(data.draw(st.lists(st.booleans(), min_size=a.n_interfaces,
                                        max_size=a.n_interfaces)), dtype=bool)
    edges = [(left, right) for (left, right, _), s in zip(scene.group.interfaces, stuck) if s]
    names, fixed = scene.blades, set(scene.group.fixed)
    free, ground = [], set()
    for cluster in stick_clusters(scene.group.graph, edges):
        if cluster & fixed:
            ground |= cluster - fixed
        else:
            free.append(frozenset(cluster))
    expected = set(free) | ({frozenset(ground)} if ground else set())

    labels, grounded = cluster_labels(a.n_blades, a.left, a.right, stuck)
    found = {frozenset(names[i] for i in np.flatnonzero(labels == c)) for c in range(len(grounded))}
    assert found == expected
    assert {frozenset(names[i] for i in np.flatnonzero(labels == c))
            for c in np.flatnonzero(grounded)} == ({frozenset(ground)} if ground else set())


def test_stick_clusters_of_a_chain_with_one_stuck_interface():
    blade = Blade(mass=0.1, damping=1.0, stiffness=1e5)
    shroud = Interface(gap=0.0, angle=0.5, normal=LinearSpring(stiffness=1e5),
                       friction=Coulomb(mu=0.5))
    group = BladeGroup.chain(4, blade, shroud)
    clusters = stick_clusters(group.graph, [("blade1", "blade2")])
    assert sorted(map(sorted, clusters)) == [["blade0"], ["blade1", "blade2"], ["blade3"]]
    with pytest.raises(ValueError, match="not an edge"):
        stick_clusters(group.graph, [("blade0", "blade3")])
    assert nx.is_frozen(Scene(group=group, excitation=Excitation(
        engine_order=1, amplitudes=(0.0,), phases=[0.0] * 4), speed_rpm=1.0).group.graph)


def test_all_stuck_ring_takes_the_minimum_norm_friction():
    """A stuck ring is indeterminate up to a force circulating round it; we take none."""
    n = 8
    blade = Blade(mass=0.1, damping=2.0, stiffness=1e5)
    shroud = Interface(gap=-GAP, angle=0.4, normal=LinearSpring(stiffness=1e6),
                       friction=Coulomb(mu=0.9))
    group = BladeGroup.ring(n, blade, shroud)
    excitation = Excitation(engine_order=3, amplitudes=(0.0, 10.0),
                            phases=np.linspace(0, 2, n).tolist())
    scene = Scene(group=group, excitation=excitation, speed_rpm=5000.0)
    x = np.linspace(-1e-6, 1e-6, n)
    r = assemble(scene, 1e-3, x, np.full(n, 0.05), np.full(n, Mode.STICK))
    assert len(r.grounded) == 1
    assert abs(r.friction_force.sum()) < 1e-12 * np.abs(r.friction_force).max()
    rhs = external_forces(scene, 1e-3, x, np.full(n, 0.05)) - incidence(scene).T @ r.interface_force
    np.testing.assert_allclose(scene.arrays.mass * r.acceleration, rhs, atol=1e-9)


def test_a_cluster_held_by_a_fixed_node_is_at_rest():
    blade = Blade(mass=0.1, damping=2.0, stiffness=1e5)
    shroud = Interface(gap=-GAP, angle=0.4, normal=LinearSpring(stiffness=1e6),
                       friction=Coulomb(mu=5.0))
    group = BladeGroup().add_fixed("disc").add_blade("a", blade).add_blade("b", blade)
    group.connect("disc", "a", shroud).connect("a", "b", shroud)
    scene = Scene(group=group, excitation=Excitation(engine_order=1, amplitudes=(1.0, 3.0),
                                                     phases=[0.0, 1.0]), speed_rpm=3000.0)
    x = np.array([-2e-6, 1e-6])
    r = assemble(scene, 0.01, x, np.zeros(2), [Mode.STICK, Mode.STICK])
    assert np.all(r.acceleration == 0.0) and r.grounded.tolist() == [True]
    rhs = external_forces(scene, 0.01, x, np.zeros(2)) - incidence(scene).T @ r.interface_force
    np.testing.assert_allclose(rhs, 0.0, atol=1e-9)
