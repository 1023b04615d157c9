"""Cyclic symmetry for rings of FE sectors (DESIGN §7–8): substructures of four modes in
sector frames of their own (``scenes.faced_group``), joined face to face by 1-D and 3-D
contacts, rigid and elastic, single pairs and patches. The symmetric orbit, a fixed point of
S⁻ᵏ φ_τ over a fraction of the period (its state carrying the elastic contacts'
stretches, each moved to its twin's one sector on), against the full shooting over T_e
started on it; and over random small rings, a property.

Kernels: the faces' laws (LinearSpring, Coulomb) with rigid and with elastic stick, with
their tangent flows: those of ``scenes.modal_packet`` and ``scenes.beam_pair``, which the
suite compiles anyway.
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import shroudnet as sn
from shroudnet import scenes
from shroudnet.steady.cyclic import cyclic_symmetry, whole_tangent
from tests.test_cyclic import _multiset_gap

#: Both solvers with this map, their switches located to this fraction of a period, and
#: to this residual: an elastic contact's stretch changes its rate where it breaks away,
#: so the map is as good as the switches are located (at the default 1e-10 periods, the
#: symmetric and the full orbits part by 1e-9 of the scale).
SETTINGS = dict(method=sn.Adaptive(rtol=1e-11), tolerance=1e-11, event_tolerance=3e-13)


def ring(speed_rpm=3000.0, **options):
    return scenes.faced_group(shape="ring", speed_rpm=speed_rpm, **options)


def agreement(scene, transient=30, settings=SETTINGS):
    """(state gap over the scale, largest multiplier gap, the symmetric orbit): the
    symmetric orbit against the full shooting started on it, the stretches counted as
    displacements."""
    symmetric = sn.periodic_orbit(scene, symmetry="cyclic", transient=transient, **settings)
    full = sn.periodic_orbit(scene, symmetry="none", guess=symmetric.initial, **settings)
    n = scene.arrays.n_blades
    gap = np.abs(full.state - symmetric.state)
    state = max(gap[:n].max(), gap[n:2 * n].max() / scene.arrays.excitation_frequency,
                gap[2 * n:].max(initial=0.0))
    for name in ("maximum", "minimum"):  # every sector's, the first one's moved round
        # located on runs shorter than τ: measured up to 1.1e-8 of the scale
        assert np.abs(getattr(full, name) - getattr(symmetric, name)).max() \
            <= 1e-7 * full.scale, name
    return state / full.scale, _multiset_gap(full.multipliers, symmetric.multipliers), \
        symmetric


CASES = {
    "1-D rigid, l = 1": dict(blades=3, components=1, face_points=1,
                             tangential_stiffness=None, engine_order=1),
    "1-D rigid, l = 2 on 4 (g = 2)": dict(blades=4, components=1, face_points=1,
                                          tangential_stiffness=None, engine_order=2),
    "3-D elastic, l = 1": dict(blades=3, components=3, face_points=1, engine_order=1),
}


@pytest.mark.parametrize("options", CASES.values(), ids=CASES.keys())
def test_the_symmetric_orbit_of_a_ring_of_fe_sectors_is_the_full_shootings(options):
    state, multipliers, orbit = agreement(ring(**options))
    # Measured: states 0, 0 and 3.4e-11 of the scale (the rigid rings' symmetric orbits
    # are fixed points of the full map to its tolerance), multipliers 1.2e-14, 2.9e-12
    # and 1.0e-11. (l = 2 on 4: sectors two apart switch together, so the orbit is
    # singular to either solver; their multipliers agree here all the same.)
    assert state <= 1e-10
    assert multipliers <= 1e-8
    assert orbit.events.counts["closing"] > 0 and orbit.events.counts["breakaway"] > 0


@pytest.mark.slow  # a 3-D elastic patch: a sector's tangent carries 24 stretches
def test_the_symmetric_orbit_of_a_ring_with_3d_elastic_patches_is_the_full_shootings():
    state, multipliers, _ = agreement(ring(blades=3, components=3, face_points=4,
                                           engine_order=1))
    # Measured: 1.9e-11 of the scale, multipliers 2.9e-12; 42 s.
    assert state <= 1e-10
    assert multipliers <= 1e-8


@pytest.mark.slow  # 20 s: two orbits at the default switch location, parting slowly
def test_the_symmetric_orbit_of_a_ring_with_1d_elastic_contacts_is_the_full_shootings():
    """1-D elastic contacts (the angle form with a tangential stiffness) at the default
    switch location: located more tightly (1e-12 periods), a run of theirs stops with
    steps below 1e-14 periods; at 1e-10 the two orbits part by what the location leaves."""
    state, multipliers, _ = agreement(ring(blades=3, components=1, face_points=1,
                                           engine_order=2),
                                      settings=dict(method=sn.Adaptive(rtol=1e-11),
                                                    tolerance=1e-11))
    # Measured: 3.2e-9 of the scale, multipliers 4.4e-10.
    assert state <= 1e-8
    assert multipliers <= 1e-8


def test_the_stretches_move_round_with_their_contacts():
    """On a ring of four sectors of 3-D elastic patches whose forcing comes round every
    two (l = 2, g = 2): the shift moves each contact's stretches to its twin's (a face of
    four contacts on), and four shifts are none; the repeating states keep the first two
    sectors' coordinates and their contacts' stretches; and a tangent that commutes with
    the shift by two sectors is rebuilt whole from its columns along those
    (``whole_tangent``)."""
    scene = ring(blades=4, components=3, face_points=4, engine_order=2)
    symmetry = cyclic_symmetry(scene)
    a = scene.arrays
    assert (symmetry.share, symmetry.repeating) == (2, a.n_blades // 2)
    assert len(symmetry.stretch_image) == a.n_stretches == 2 * 4 * 4
    y = np.arange(symmetry.size, dtype=float)
    assert np.array_equal(symmetry.shifted(y, 4), y)
    moved = symmetry.shifted(y, 1)
    first = 2 * a.n_blades
    assert np.array_equal(moved[first:first + 2], y[first + 8:first + 10])
    assert np.array_equal(moved[:a.n_blades], np.roll(y[:a.n_blades], -4))
    z = np.random.default_rng(0).normal(size=len(symmetry.restricted(y)))
    repeating = symmetry.tiled(z)
    assert np.array_equal(symmetry.restricted(repeating), z)
    assert np.array_equal(symmetry.shifted(repeating, symmetry.repeats), repeating)
    # Φ = A + R⁻¹ A R commutes with R (R² = I), whatever A.
    matrix = np.random.default_rng(1).normal(size=(symmetry.size, symmetry.size))
    index = symmetry.permutation(symmetry.repeats)
    inverse = np.argsort(index)
    commuting = matrix + matrix[inverse][:, inverse]
    assert np.array_equal(commuting[index][:, index], commuting)
    columns = symmetry.restricted(np.arange(symmetry.size))
    assert np.array_equal(whole_tangent(symmetry, commuting[:, columns]), commuting)


def test_a_symmetric_orbit_moves_each_sectors_dofs_to_the_next_one_a_sector_on():
    """The symmetry read from a plain run, not from the solver's shift: the symmetric
    orbit's state in the nodes' own degrees of freedom q (each sector in its own frame),
    simulated over Δ = l T_e / N, is the state of t = 0 with each sector's q taken from
    the next sector's, y(t + Δ) = S y(t), the modal coordinates of one sector the next
    one's unchanged (identical sectors: one Φ for all)."""
    scene = ring(**CASES["1-D rigid, l = 1"])
    orbit = sn.periodic_orbit(scene, symmetry="cyclic", transient=30, **SETTINGS)
    sectors = 3
    run = sn.simulate(scene, 1, samples_per_period=sectors, initial=orbit.initial,
                      method=SETTINGS["method"], event_tolerance=SETTINGS["event_tolerance"])
    bases = scene.arrays.layout.bases
    assert all(np.array_equal(basis, bases[0]) for basis in bases)
    for part, now in ((run.x, 0), (run.v, 0)):
        start = part[now].reshape(sectors, -1)
        later = part[now + 1].reshape(sectors, -1)  # t = T_e/N = Δ (l = 1)
        scale = np.abs(start).max()
        # Measured: 5.9e-14 (q) and 6.7e-13 (q̇) of the largest entry; the other way
        # round (sector s from s − 1) they part by 1.95 and 1.55.
        assert np.abs(later - np.roll(start, -1, axis=0)).max() <= 1e-9 * scale
        assert np.abs(later - start).max() > 1e-2 * scale  # the sectors do differ


@pytest.mark.slow  # random rings: a minute or two
@settings(max_examples=12, deadline=None)
@given(blades=st.integers(3, 5), order=st.integers(1, 10), speed=st.floats(2800.0, 3200.0),
       gap=st.sampled_from([5e-7, 1e-6, 2e-6]))
def test_for_small_rings_of_fe_sectors_the_symmetric_and_the_full_solver_agree(
        blades, order, speed, gap):
    """Rings of three to five FE sectors with 1-D rigid faces, open at rest, in any engine
    order up to 10 (g = gcd(l, N) > 1 among them: the repeating states). Where the
    sectors N/g apart switch at one instant the orbit is ``singular``, to either solver:
    independent contacts of substructures that switch together are not told apart, and
    the multipliers are not to be trusted; the orbit is. Elastic faces are the cases
    above: where a 3-D face slips into its separation, its stretch turning at the rate
    λ/|u| as the limit μN shrinks to nothing makes the tangent flow stiff, and some rings'
    orbits cannot be shot at all, symmetric or not. Preloaded rigid faces stuck all round
    a ring are nearly redundant constraints, whose least-norm static friction some rings
    cannot hold."""
    options = dict(blades=blades, engine_order=order, components=1, face_points=1,
                   tangential_stiffness=None)
    state, multipliers, orbit = agreement(ring(speed_rpm=speed, gap=gap, **options))
    assert state <= 1e-10
    assert multipliers <= 1e-8 or orbit.singular


def test_continuation_follows_a_ring_of_fe_sectors_on_its_symmetric_orbits():
    """A branch over speed of the 1-D rigid ring's travelling waves (continuation with
    symmetry="cyclic", the stretches of none): each of its orbits is the full shooting's
    at its speed."""
    def scene_at(speed_rpm):
        return ring(speed_rpm=speed_rpm, **CASES["1-D rigid, l = 1"])

    branch = sn.continuation(scene_at, 3000.0, 3030.0, symmetry="cyclic", max_points=4,
                             transient=30)
    assert len(branch) >= 3
    for orbit, speed in zip(branch.orbits[1:], branch.parameter[1:]):
        full = sn.periodic_orbit(scene_at(speed), symmetry="none", guess=orbit.initial)
        n = orbit.scene.arrays.n_blades
        gap = np.abs(full.state - orbit.state)
        # Measured: 0 (each is a fixed point of the full map to the branch's tolerance).
        assert max(gap[:n].max(), gap[n:].max() / orbit.scene.arrays.excitation_frequency) \
            <= 1e-8 * full.scale


def test_what_breaks_the_symmetry_of_fe_sectors_is_named():
    packet = scenes.faced_group(blades=3, face_points=1)  # a chain: no sectors
    with pytest.raises(ValueError, match="needs a ring or a disc of sectors"):
        sn.periodic_orbit(packet, symmetry="cyclic")
    scene = ring(blades=3, face_points=1)
    group = scene.group
    tuned = sn.BladeGroup()
    for name in group.blades:
        tuned.add_blade(name, group.blade(name), frame=group.frame(name))
    (left, right, face), *rest = group.interfaces
    points = group.edge_points("interface")
    faster = sn.Interface(gap=face.gap, normal=face.normal, friction=face.friction,
                          normal_direction=face.normal_direction,
                          tangent_directions=face.tangent_directions,
                          tangential_stiffness=2.0 * face.tangential_stiffness)
    tuned.connect((left, points[0][0]), (right, points[0][1]), faster)
    for (one, other, interface), ends in zip(rest, points[1:]):
        tuned.connect((one, ends[0]), (other, ends[1]), interface)
    tuned.declare_sectors(3)
    mistuned = sn.Scene(group=tuned, excitation=scene.excitation, speed_rpm=3000.0)
    with pytest.raises(ValueError, match=r"not tuned: contact 0 differs from its twin"):
        sn.periodic_orbit(mistuned, symmetry="cyclic")
