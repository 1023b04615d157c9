"""Contact patches and several edges between two nodes (DESIGN §8): an interface that joins k
point pairs is k contacts, each with the interface's laws, so a patch of k coincident pairs
is exactly one pair with k times the stiffnesses; a patch of four pairs on two beams against
the independent event-driven reference (``references.structures``, solve_ivp); the group's
multigraph, the readers by (interface, contact), files and the patch's contact-state map.

Kernels: the paper's group, the packet's rigid and elastic faces (``scenes.beam_pair``,
``scenes.modal_packet``): all compiled by the suite anyway.
"""

import dataclasses

import networkx as nx
import numpy as np
import scipy.linalg
import pytest

import shroudnet as sn
from contact_laws import Coulomb, LinearSpring
from shroudnet import scenes
from shroudnet.io import results, scenefile
from shroudnet.model.substructure import Substructure
from shroudnet.references import structures as reference
from tests.test_structures import TIGHT, stuck_ring
from tests.test_tangent import EXACT

PAPER = scenes.three_blade_paper()
BLADE = PAPER.group.blade("blade1")
SHROUD = PAPER.group.interfaces[0][2]
SPRING = sn.Coupling(stiffness=1e4, damping=0.5)


def scaled(interface, factor):
    """``interface`` with its normal (and tangential) stiffness times ``factor``."""
    stiffness = interface.tangential_stiffness
    return dataclasses.replace(
        interface, normal=LinearSpring(stiffness=interface.normal.stiffness * factor),
        tangential_stiffness=None if stiffness is None else stiffness * factor)


def rebuilt(scene, pairs, factor):
    """``scene`` with each interface a patch of ``pairs`` coincident point pairs (its own
    points, ``pairs`` times over), each with ``factor`` times its stiffnesses."""
    old = scene.group
    group = sn.BladeGroup()
    for name in old.blades:
        group.add_blade(name, old.blade(name))
    for (left, right, interface), (a, b) in zip(old.interfaces, old.edge_points("interface")):
        group.connect((left, [a] * pairs), (right, [b] * pairs), scaled(interface, factor))
    return sn.Scene(group=group, excitation=scene.excitation, speed_rpm=scene.speed_rpm)


# ---- the group: a multigraph, and patches ----------------------------------------------------

def test_two_nodes_may_be_joined_by_an_interface_and_a_coupling_or_by_two_interfaces():
    group = sn.BladeGroup().add_blade("a", BLADE).add_blade("b", BLADE).add_fixed("disc")
    group.connect("a", "b", SHROUD).connect("a", "b", SPRING).connect("b", "a", SHROUD)
    group.connect("disc", "a", SPRING)
    assert group.interfaces == [("a", "b", SHROUD), ("b", "a", SHROUD)]
    assert group.couplings == [("a", "b", SPRING), ("disc", "a", SPRING)]
    assert isinstance(group.graph, nx.MultiGraph)
    assert group.graph.edges["disc", "a"]["index"] == 1  # one edge: read as a Graph's
    with pytest.raises(ValueError, match=r"joined by 3 edges; name one as edges\['a', 'b', key\]"):
        group.graph.edges["a", "b"]  # noqa: B018
    scene = sn.Scene(group=group, excitation=PAPER.excitation, speed_rpm=6000.0)
    a = scene.arrays
    assert (a.n_interfaces, a.n_couplings) == (2, 2) and not a.is_structure
    assert list(a.left) == [0, 1] and list(a.right) == [1, 0]
    # the coupling between a and b and the one to the disc add up in K
    k = SPRING.stiffness
    assert np.array_equal(a.stiffness_matrix(),
                          np.diag(a.stiffness) + [[2 * k, -k], [-k, k]])


def test_a_graph_of_networkx_that_holds_one_edge_between_two_nodes_says_so():
    graph = nx.Graph()
    graph.add_node("a", blade=BLADE, motion=None)
    graph.add_node("b", blade=BLADE, motion=None)
    graph.add_edge("a", "b", interface=SHROUD, left="a", index=0)
    group = sn.BladeGroup()
    group.graph = graph
    with pytest.raises(ValueError, match=r"already connected, and this group's graph is a "
                                         r"networkx.Graph.*networkx.MultiGraph"):
        group.connect("a", "b", SPRING)
    group.graph = nx.MultiGraph(graph)
    group.connect("a", "b", SPRING)
    assert group.couplings == [("a", "b", SPRING)]


def face_blade():
    """A blade of two coordinates whose face has the points "R0" … "R2" and "L0" …
    "L2" (two components each)."""
    points = {f"{side}{k}": [[1.0, 0.1 * k], [0.0, 1.0]] for side in "LR" for k in range(3)}
    return Substructure(np.diag([0.1, 0.05]), np.diag([1e5, 3e5]), points=points,
                        load=np.array([1.0, 0.0]))


#: A face whose contacts stick elastically: the points of ``face_blade`` slide alike (their
#: tangent rows are one), so rigid stick would tie them into one redundant constraint.
FACE = sn.Interface(gap=1e-6, normal=LinearSpring(stiffness=1e5), friction=Coulomb(mu=0.3),
                    normal_direction=(1.0, 0.0), tangent_direction=(0.0, 1.0),
                    tangential_stiffness=3e4)


def test_a_patch_is_a_contact_per_point_pair_with_the_interfaces_laws():
    blade = face_blade()
    group = sn.BladeGroup().add_blade("a", blade).add_blade("b", blade).add_fixed("disc")
    group.connect(("a", ["R0", "R1", "R2"]), ("b", ["L0", "L1", "L2"]), FACE)
    group.connect(("b", "R0"), ("a", "L0"), FACE)
    group.connect(("a", ("L1", "L2")), "disc", FACE)
    assert group.edge_points("interface") == [(("R0", "R1", "R2"), ("L0", "L1", "L2")),
                                              ("R0", "L0"), (("L1", "L2"), None)]
    assert group.point_pairs("interface")[2] == (("L1", None), ("L2", None))
    scene = sn.Scene(group=group, excitation=sn.Excitation(
        engine_order=1, amplitudes=(0.0, 1.0), phases=[0.0, 0.0]), speed_rpm=3000.0)
    assert [(c.interface, c.contact, c.pairs) for c in scene.contacts] == [
        (0, 0, 3), (0, 1, 3), (0, 2, 3), (1, 0, 1), (2, 0, 2), (2, 1, 2)]
    assert str(scene.contacts[1]) == "interface 0, contact 1 ('a', 'b')"
    assert str(scene.contacts[3]) == "interface 1 ('b', 'a')"
    a = scene.arrays
    assert a.n_interfaces == 6 and len(a.normal_laws) == 6
    # contact k of the first patch: n·(Φ_a,Rk − Φ_b,Lk) over the degrees of freedom q,
    # which the engine's rows read through q = Φ η, node by node
    to_q = scipy.linalg.block_diag(*a.layout.bases)
    rows = [scene.point_rows("a", f"R{k}") - scene.point_rows("b", f"L{k}") for k in range(3)]
    for k in range(3):
        assert np.allclose(a.normal_rows[k, :4], rows[k][0] @ to_q, rtol=1e-14, atol=0.0)
        assert np.allclose(a.tangent_rows[k, :4], rows[k][1] @ to_q, rtol=1e-14, atol=0.0)
    assert np.allclose(a.normal_rows[5, :4], scene.point_rows("a", "L2")[0] @ to_q,
                       rtol=1e-14, atol=0)
    assert [scene.contact_position(which) for which in (1, (0, 2), (2, 1))] == [3, 2, 5]
    with pytest.raises(ValueError, match=r"interface 0 is a patch of 3 contacts; name one as "
                                         r"\(0, k\), k in 0..2"):
        scene.contact_position(0)
    with pytest.raises(ValueError, match=r"Scene.contact_position.contact must be an int >= 0 "
                                         r"and <= 2, got 3"):
        scene.contact_position((0, 3))
    with pytest.raises(TypeError, match=r"Scene.contact_position.interface must be an int"):
        scene.contact_position("0")


@pytest.mark.parametrize("left, right, message", [
    (("a", ["R0", "R1"]), ("b", ["L0"]), r"both ends name as many points .* got 2 and 1"),
    (("a", ["R0", "R1"]), ("b", "L0"), r"both ends name as many points .* got 2 and 1"),
    (("a", []), ("b", []), r"the patch at node 'a' names no points"),
    (("a", ["R0", "nowhere"]), ("b", ["L0", "L1"]), r"node 'a' has no point 'nowhere'"),
])
def test_a_patch_whose_points_do_not_pair_up_is_refused_by_name(left, right, message):
    blade = face_blade()
    group = sn.BladeGroup().add_blade("a", blade).add_blade("b", blade)
    with pytest.raises(ValueError, match=message):
        group.connect(left, right, FACE)


def test_parallel_interfaces_of_half_the_stiffness_move_a_ring_as_one():
    """Each shroud of a preloaded ring of four blades that stick, break away and separate
    (``tests.test_structures.stuck_ring``) split into two interfaces of half its contact
    stiffness between the same blades: the two stick, slip and open together (a cycle of
    two edges in a stick cluster, its static friction shared by least norm), and the ring
    moves as with one."""
    ring = stuck_ring()
    group = sn.BladeGroup()
    for name in ring.blades:
        group.add_blade(name, ring.group.blade(name))
    for left, right, interface in ring.group.interfaces:
        half = scaled(interface, 0.5)
        group.connect(left, right, half).connect(left, right, half)
    split = sn.Scene(group=group, excitation=ring.excitation, speed_rpm=ring.speed_rpm)
    one = sn.simulate(ring, 30, method=TIGHT)
    two = sn.simulate(split, 30, method=TIGHT)
    assert one.events.counts["sticking"] > 0 and one.events.counts["breakaway"] > 0
    assert {k: 2 * v for k, v in one.events.counts.items()} == two.events.counts
    # Measured: 3.3e-13 of the amplitude, the forces 4.2e-13 of their largest.
    assert np.abs(two.x - one.x).max() <= 1e-9 * np.abs(one.x).max()
    for name in ("normal_force", "friction_force"):
        ours, theirs = getattr(two, name), getattr(one, name)
        assert np.abs(ours[:, ::2] + ours[:, 1::2] - theirs).max() \
            <= 1e-9 * np.abs(theirs).max()
        assert np.array_equal(ours[:, ::2], ours[:, 1::2])


# ---- a patch of k coincident pairs is one pair of k times the stiffnesses ----------------------

def pair_on_a_disc():
    """Two blades of the packet with 2-D elastic faces that close, stick, break away,
    stick again and open every period (as ``tests.test_elastic_tangent``)."""
    return scenes.modal_packet(blades=2, tangential_stiffness=3e4, gap=-1e-6, q1=3.0,
                               speed_rpm=3100.0, blades_on_disc=8)


def nearest_gap(some, others):
    """The largest distance from a multiplier of ``some`` to the nearest of ``others``."""
    return np.abs(some[:, None] - others[None, :]).min(axis=1).max()


@pytest.mark.slow  # 20-30 s each on two busy cores: two orbits with their monodromies
@pytest.mark.parametrize("stick", ["rigid", "elastic"])
def test_a_patch_of_coincident_pairs_is_one_pair_of_k_times_the_stiffnesses(stick):
    """Three coincident pairs of a third of the stiffnesses each against one pair: the
    patch's orbit, solved by its own Newton from a start 1e-3 off, is the pair's, and so
    are its multipliers (the elastic patch has two more per extra slider: the pair's are
    among them); the contacts share the load, stick and slip as one, and their friction
    losses add up to the pair's."""
    pairs = 3
    one = scenes.beam_pair() if stick == "rigid" else pair_on_a_disc()
    patch = rebuilt(one, pairs, 1.0 / pairs)
    assert patch.arrays.n_interfaces == pairs * one.arrays.n_interfaces
    settings = dict(method=EXACT, tolerance=1e-12, event_tolerance=1e-13)
    alone = sn.periodic_orbit(one, **settings)
    kinds = alone.events.counts
    assert kinds["sticking"] > 0 and kinds["breakaway"] > 0 and kinds["separation"] > 0
    x0, v0, *u0 = alone.initial
    off = 1e-3 * alone.scale
    guess = (x0 + off, v0) + ((np.tile(u0[0], pairs) + off,) if u0 else ())
    orbit = sn.periodic_orbit(patch, guess=guess, **settings)
    assert orbit.iterations > 0
    # Rigid, the pairs' guards are one surface on the stuck constraints, and switch as
    # one; elastic, each pair's slider is a state of its own, and their switches at one
    # instant are several (``singular``): the map is smooth along the orbit's own
    # perturbations, where the sliders stay together, not across them.
    assert bool(orbit.singular) == (stick == "elastic")
    n = patch.arrays.n_blades
    weights = np.repeat([1.0, 1.0 / one.arrays.excitation_frequency], n)
    gap = np.abs(orbit.state[:2 * n] - alone.state[:2 * n]) * weights
    # Measured: 2.1e-13 (rigid) and 1.1e-13 (elastic) of the scale; multipliers 8.8e-14
    # and 3.9e-14; the normal forces 2.4e-14 and 5.1e-11 of their largest, the losses
    # (from the samples' loops) 9.0e-10 apart.
    assert gap.max() <= 1e-10 * alone.scale
    if u0:
        stretches = orbit.state[2 * n:].reshape(pairs, -1)
        assert np.abs(stretches - alone.state[2 * n:]).max() <= 1e-10 * alone.scale
        assert len(orbit.multipliers) == len(alone.multipliers) + 2 * (pairs - 1)
    else:
        assert len(orbit.multipliers) == len(alone.multipliers)
    assert nearest_gap(alone.multipliers, orbit.multipliers) <= 1e-8
    run = orbit.simulation()
    single = alone.simulation()
    assert np.array_equal(run.modes[:, 0], run.modes[:, pairs - 1])
    assert np.allclose(pairs * run.normal_force[:, 1], single.normal_force[:, 0], rtol=0.0,
                       atol=1e-9 * np.abs(single.normal_force).max())
    losses = orbit.friction_losses()
    assert losses.shape == (pairs,)
    assert abs(losses.sum() - alone.friction_losses()[0]) <= 1e-8 * alone.friction_losses()[0]
    # the last pair's loops, along each direction it slides in, are a k-th of the one's
    directions = (1, 2) if np.any(patch.arrays.slip_rows(2) != 0.0) else (1,)
    last = sum(sn.hysteresis_loop(run, (0, pairs - 1), 0, d).area_per_cycle()
               for d in directions)
    assert abs(pairs * last - alone.friction_losses()[0]) <= 1e-8 * alone.friction_losses()[0]


# ---- a patch of four pairs on two beams, against the independent reference ----------------------

#: The axial offsets [m] of the four points of each beam's shroud face from its tip.
OFFSETS = (-4.5e-3, -1.5e-3, 1.5e-3, 4.5e-3)


def faced_beam():
    """``scenes.beam_pair``'s beam whose shroud is a face of four points, each at an axial
    offset a from the tip: r = (v + a θ_z, w − a θ_y) (a rigid shroud on the tip)."""
    beam = sn.cantilever_beam(length=0.08, width=0.02, thickness=0.003, youngs_modulus=2.1e11,
                              density=7800.0, elements=2, tip_mass=0.02, damping_ratios=0.01)
    shroud = np.asarray(beam.point("shroud"))
    n = beam.n_dofs
    turn = np.zeros((2, n))
    turn[0, n - 3], turn[1, n - 1] = 1.0, -1.0  # the tip's θ_z and θ_y
    points = dict(beam.points) | {f"p{k}": shroud + a * turn for k, a in enumerate(OFFSETS)}
    return Substructure(beam.mass, beam.stiffness, damping_ratios=beam.damping_ratios,
                        points=points, load="load")


@pytest.mark.slow  # 20-30 s on two busy cores: the solve_ivp reference at rtol 1e-12
def test_a_patch_of_four_pairs_on_two_beams_matches_the_independent_reference():
    """Two unreduced beams whose shroud faces meet at four point pairs across a gap, a
    quarter of the contact stiffness each: over one period of the orbit, every switch of
    the engine (each pair closes, slips, reverses and opens at instants of its own) is one
    of the reference's (solve_ivp, event by event, its own contact code), at its
    instant, and the motion agrees. (Rigid stick of more pairs than the face has
    tangential freedoms, two here, is statically indeterminate: the friction is low
    enough that they slip.)"""
    blade = faced_beam()
    base = scenes.beam_pair(blade=blade, gap=1e-6, friction=Coulomb(mu=0.1))
    face = scaled(base.group.interfaces[0][2], 0.25)
    points = [f"p{k}" for k in range(len(OFFSETS))]
    group = sn.BladeGroup().add_blade("blade1", blade).add_blade("blade2", blade)
    group.connect(("blade1", points), ("blade2", points), face)
    scene = sn.Scene(group=group, excitation=base.excitation, speed_rpm=base.speed_rpm)
    orbit = sn.periodic_orbit(scene, history=True)
    history = orbit.history
    assert len(set(history.events.interface)) == len(OFFSETS)  # every pair switches
    dofs = scene.dof_matrix()
    q0, v0 = dofs @ orbit.initial[0], dofs @ orbit.initial[1]
    run = reference.run_structure(reference.structure_from_substructures(scene), q0, v0,
                                  history.t[-1], rtol=1e-12, atol=1e-16, t_eval=history.t)
    engine_q = history.x @ dofs.T
    amplitude = np.abs(engine_q).max()
    # Measured: 5.0e-11 of the amplitude, the twelve switches to 7.5e-11 periods.
    assert np.abs(run.q - engine_q).max() <= 1e-8 * amplitude
    period = scene.excitation_period
    engine = sorted(zip(history.events.time, history.events.interface))
    theirs = sorted(zip(run.switch_times, run.switch_contacts))
    assert len(engine) == len(theirs)
    for (t, e), (s, c) in zip(engine, theirs):
        assert e == c and abs(t - s) <= 1e-8 * period


# ---- files, readers and the map --------------------------------------------------------------

def test_scene_and_results_files_carry_patches_and_parallel_edges(tmp_path):
    blade = face_blade()
    group = sn.BladeGroup().add_blade("a", blade).add_blade("b", blade).add_fixed("disc")
    group.connect(("a", ["R0", "R1"]), ("b", ["L0", "L1"]), FACE)
    group.connect(("a", "R2"), ("b", "L2"), FACE).connect(("a", "R2"), ("b", "L2"), SPRING)
    group.connect(("a", ["L1", "L2"]), "disc", SPRING)
    scene = sn.Scene(group=group, excitation=sn.Excitation(
        engine_order=1, amplitudes=(0.0, 1.0), phases=[0.0, 0.0]), speed_rpm=3000.0)
    path = scenefile.save(tmp_path / "patch.toml", scene)
    text = path.read_text()
    assert 'left = ["a", ["R0", "R1"]]' in text
    again = scenefile.load(path).scene
    assert again.group.edge_points("interface") == scene.group.edge_points("interface")
    assert again.group.edge_points("coupling") == scene.group.edge_points("coupling")
    for field in ("normal_rows", "tangent_rows", "normal_gap", "structure_stiffness",
                  "structure_damping"):
        assert np.array_equal(getattr(again.arrays, field), getattr(scene.arrays, field))
    sim = sn.simulate(scene, 2, samples_per_period=20)
    loaded = results.load_simulation(results.save_simulation(tmp_path / "run.npz", sim))
    assert np.array_equal(loaded.normal_force, sim.normal_force)
    assert len(loaded.scene.contacts) == 3


def test_a_patchs_history_gives_its_contact_state_map_and_load_distribution():
    blade = face_blade()
    group = sn.BladeGroup().add_blade("a", blade).add_fixed("disc")
    group.connect(("a", ["R0", "R1", "R2"]), "disc", dataclasses.replace(FACE, gap=-1e-6))
    scene = sn.Scene(group=group, excitation=sn.Excitation(
        engine_order=1, amplitudes=(0.0, 2.0), phases=[0.0]), speed_rpm=3000.0)
    sim = sn.simulate(scene, 4, samples_per_period=50)
    patch = sn.patch_history(sim, 0, skip=2)
    assert patch.contacts == 3 and patch.interface == 0
    assert len(patch.time) == 2 * 50 + 1
    shares = patch.fractions()
    assert np.allclose(sum(shares.values()), 1.0, rtol=0.0, atol=1e-15)
    loads = patch.load_shares()
    assert abs(loads.sum() - 1.0) <= 1e-12 and np.all(loads >= 0.0)
    # the far point (R2: the face turns with the second coordinate) carries the most
    expected = np.trapezoid(sim.normal_force[100:], sim.t[100:], axis=0)
    assert np.allclose(loads, expected / expected.sum(), rtol=1e-12)
    from shroudnet.front.figures import patch_map
    figure = patch_map(patch)
    assert figure.axes[0].get_ylabel() == "contact"
    assert patch_map(patch, quantity="normal", ax=figure.axes[0]) is figure.axes[0]
    with pytest.raises(ValueError, match=r"patch_map.quantity"):
        patch_map(patch, quantity="pressure")
