"""Properties of the assembled dynamics that hold for any group, laws and state.

The expected values are computed here from the interfaces' own geometry and laws and from
the equation of motion M ẍ = Q − C ẋ − K x − Bᵀ F (DESIGN §2, paper eq. 7); friction limits
use the μ_s each test gave its laws (``tests.laws.static_limit``), never the scene's arrays.
"""

import math

import networkx as nx
import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from contact_laws import Coulomb, LinearSpring, Regularised
from shroudnet import (Blade, BladeGroup, Excitation, ExplicitPhases, FixedStep, Interface, Mode,
                       Scene, assemble, simulate, stick_clusters)
from shroudnet.engine.clusters import cluster_labels
from tests.groups import GAP, blades, external_forces, incidence, scenes, states
from tests.laws import friction_laws, normal_laws, static_limit


def _assembled(data, scene, **kwargs):
    t, x, v, modes = data.draw(states(scene, **kwargs))
    return (t, x, v, modes), assemble(scene, t, x, v, modes)


def _position(scene):
    return {name: i for i, name in enumerate(scene.blades)}


def _kinematics(scene, x, v):
    """δ = (u − Δ) sin α, δ̇ and the slip velocity u̇ cos α of every interface, from the
    interfaces' own gap and angle (u = x_left − x_right, a fixed node at x = 0)."""
    where = _position(scene)
    rows = []
    for left, right, interface in scene.group.interfaces:
        u = (x[where[left]] if left in where else 0.0) - (x[where[right]] if right in where
                                                          else 0.0)
        du = (v[where[left]] if left in where else 0.0) - (v[where[right]] if right in where
                                                           else 0.0)
        sin, cos = math.sin(interface.angle), math.cos(interface.angle)
        rows.append(((u - interface.gap) * sin, du * sin, du * cos))
    return np.array(rows).reshape(-1, 3).T


def _law_forces(scene, x, v, modes):
    """N and sliding f of every interface from its laws (paper eqs. 2–6); 0 friction where
    stuck (there it is the unknown constraint force)."""
    penetration, rate, slip = _kinematics(scene, x, v)
    normal, friction = np.zeros(len(modes)), np.zeros(len(modes))
    for e, (_, _, interface) in enumerate(scene.group.interfaces):
        if modes[e] == Mode.OPEN:
            continue
        normal[e] = interface.normal(penetration[e], rate[e])
        law = interface.friction
        if law is None or modes[e] == Mode.STICK:
            continue
        if isinstance(law, Regularised):
            friction[e] = law(slip[e]) * normal[e] * math.tanh(slip[e] / law.velocity)
        else:
            sign = 1.0 if modes[e] == Mode.SLIP_POSITIVE else -1.0
            friction[e] = sign * law(slip[e]) * normal[e]
    return normal, friction


def _masses(scene):
    return np.array([scene.group.blade(name).mass for name in scene.blades])


def _stuck_solution(scene, external, normal, friction, modes):
    """(ẍ, f) solving M ẍ = R − Bᵀ F with the blades of each stick cluster moving together.

    ``external`` is Q − C ẋ − K x by blade, ``friction`` the sliding friction (stuck
    entries ignored). Unknowns: one acceleration per free stick cluster (0 for a cluster
    held by a fixed node) and the static friction of each stuck interface; solved by
    least squares, which is exact for the tree clusters these tests build.
    """
    names, where = scene.blades, _position(scene)
    edges = scene.group.interfaces
    angles = np.array([interface.angle for _, _, interface in edges])
    stuck = [e for e in range(len(edges)) if modes[e] == Mode.STICK]
    graph = nx.Graph()
    graph.add_nodes_from(list(names) + list(scene.group.fixed))
    graph.add_edges_from((edges[e][0], edges[e][1]) for e in stuck)
    free = [c for c in nx.connected_components(graph) if not c & set(scene.group.fixed)]
    free = [c for c in free if c & set(names)]
    columns = len(free) + len(stuck)
    matrix, rhs = np.zeros((len(names), columns)), np.array(external, dtype=float)
    for c, cluster in enumerate(free):
        for name in cluster:
            matrix[where[name], c] = _masses(scene)[where[name]]
    for e, (left, right, _) in enumerate(edges):
        force = normal[e] * math.sin(angles[e]) + (0.0 if e in stuck
                                                   else friction[e] * math.cos(angles[e]))
        for end, sign in ((left, 1.0), (right, -1.0)):
            if end in where:
                rhs[where[end]] -= sign * force
                if e in stuck:
                    matrix[where[end], len(free) + stuck.index(e)] += sign * math.cos(angles[e])
    solution = np.linalg.lstsq(matrix, rhs, rcond=None)[0]
    acceleration = np.zeros(len(names))
    for c, cluster in enumerate(free):
        for name in cluster:
            acceleration[where[name]] = solution[c]
    static = np.array(friction, dtype=float)
    static[stuck] = solution[len(free):]
    return acceleration, static


@given(st.data())
def test_accelerations_obey_the_equation_of_motion_with_the_laws_forces(data):
    """N and the sliding f are each interface's laws at its δ, δ̇ and v computed here; with
    the returned static friction, M ẍ = Q − C ẋ − K x − Bᵀ F holds blade by blade, and the
    blades joined by a stuck interface accelerate together (a held cluster not at all)."""
    scene = data.draw(scenes())
    (t, x, v, modes), r = _assembled(data, scene)
    normal, friction = _law_forces(scene, x, v, modes)
    stuck = modes == Mode.STICK
    scale = np.abs(normal).max() + np.abs(external_forces(scene, t, x, v)).max() + 1.0
    np.testing.assert_allclose(r.normal_force, normal, rtol=1e-12, atol=1e-12 * scale)
    np.testing.assert_allclose(r.friction_force[~stuck], friction[~stuck], rtol=1e-12,
                               atol=1e-12 * scale)
    friction[stuck] = r.friction_force[stuck]
    angles = np.array([interface.angle for _, _, interface in scene.group.interfaces])
    force = normal * np.sin(angles) + friction * np.cos(angles)
    expected = (external_forces(scene, t, x, v) - incidence(scene).T @ force) / _masses(scene)
    accel_scale = (scale + np.abs(force).max()) / _masses(scene).min()
    np.testing.assert_allclose(r.acceleration, expected, rtol=1e-9, atol=1e-9 * accel_scale)
    np.testing.assert_allclose((incidence(scene) @ expected)[stuck], 0.0,
                               atol=1e-9 * accel_scale)


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
    amplitudes = tuple(-q for q in scene.excitation.amplitudes)
    phases = ExplicitPhases(tuple(scene.arrays.phases[::-1]))
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
def test_sliding_friction_stays_within_mu_s_n_and_the_stuck_margin_is_measured_against_it(data):
    """With μ_s the coefficient the law was given: a sliding interface carries at most
    μ_s N, and a stuck one reports its breakaway margin μ_s N − |f| (negative when its
    static friction is beyond the limit)."""
    scene = data.draw(scenes())
    (t, x, v, modes), r = _assembled(data, scene)
    normal, _ = _law_forces(scene, x, v, modes)
    mu_s = np.array([0.0 if interface.friction is None else static_limit(interface.friction)
                     for _, _, interface in scene.group.interfaces])
    limit = mu_s * normal
    sliding = modes != Mode.STICK
    assert np.all(np.abs(r.friction_force[sliding]) <= limit[sliding] * (1 + 1e-12) + 1e-300)
    stuck = modes == Mode.STICK
    margin = limit[stuck] - np.abs(r.friction_force[stuck])
    np.testing.assert_allclose(r.motion_guard[stuck], margin, rtol=1e-12,
                               atol=1e-12 * (np.abs(limit).max() + 1.0))


@st.composite
def all_stuck_chains(draw, n=st.integers(3, 6)):
    """A free chain of 3–6 blades with exact friction on every interface and a state in
    which every contact is closed and stuck: one stick cluster, one velocity."""
    count = draw(n)
    names = [f"b{i}" for i in range(count)]
    group = BladeGroup()
    for name in names:
        group.add_blade(name, draw(blades()))
    x = [draw(st.floats(-4 * GAP, 4 * GAP))]
    for left, right in zip(names, names[1:]):
        interface = Interface(gap=draw(st.floats(-GAP, GAP)), angle=draw(st.floats(0.05, 1.5)),
                              normal=draw(normal_laws()),
                              friction=draw(friction_laws(regularised=False)))
        group.connect(left, right, interface)
        x.append(x[-1] - interface.gap - draw(st.floats(1e-8, 2 * GAP)))  # u − Δ > 0
    excitation = Excitation(engine_order=draw(st.integers(1, 4)),
                            amplitudes=(draw(st.floats(-20.0, 20.0)), draw(st.floats(0.0, 50.0))),
                            phases=draw(st.lists(st.floats(0.0, 2 * math.pi), min_size=count,
                                                 max_size=count)))
    scene = Scene(group=group, excitation=excitation, speed_rpm=draw(st.floats(1000.0, 9000.0)))
    t = draw(st.floats(0.0, 1.0)) * scene.excitation_period
    v = np.full(count, draw(st.floats(-1.0, 1.0)))
    return scene, t, np.array(x), v


@given(all_stuck_chains())
def test_all_stuck_chain_moves_as_one_body(sample):
    """One cluster: ẍ = (Σ Q − Σ c ẋ − Σ k x)/Σ m, the single body with summed m, c and k,
    and each static friction balances its blades: m_i ẍ = R_i − (Bᵀ F)_i blade by blade."""
    scene, t, x, v = sample
    modes = np.full(len(scene.blades) - 1, Mode.STICK)
    penetration, _, _ = _kinematics(scene, x, v)
    assert np.all(penetration > 0.0)
    r = assemble(scene, t, x, v, modes)
    external = external_forces(scene, t, x, v)
    body = external.sum() / _masses(scene).sum()
    np.testing.assert_allclose(r.acceleration, body, rtol=1e-9, atol=1e-9 * abs(body) + 1e-9)
    assert len(r.grounded) == 1 and not r.grounded[0]
    normal, friction = _law_forces(scene, x, v, modes)
    _, static = _stuck_solution(scene, external, normal, friction, modes)
    scale = np.abs(external).max() + np.abs(normal).max() + 1.0
    np.testing.assert_allclose(r.friction_force, static, rtol=1e-9, atol=1e-9 * scale)


def test_regularised_friction_is_mu_n_tanh_v_over_v_epsilon():
    """Regularised's docstring: f = μ(|v|) N tanh(v/v_ε), by hand on one interface.

    k_c = 1e5 N/m, α = π/6, overlap 2 µm: N = 1e5 · 2e-6 · sin(π/6) = 0.1 N; with μ = 0.3
    and a slip velocity v = v_ε = 1 mm/s, f = 0.3 · 0.1 · tanh(1) = 0.03 · 0.76159415595576.
    At v = −v_ε it is the opposite, and at v = 0 it is zero: a regularised law never holds.
    """
    blade = Blade(mass=0.1, damping=0.0, stiffness=1e5)
    shroud = Interface(gap=0.0, angle=math.pi / 6, normal=LinearSpring(stiffness=1e5),
                       friction=Regularised(law=Coulomb(mu=0.3), velocity=1e-3))
    scene = Scene(group=BladeGroup.chain(2, blade, shroud),
                  excitation=Excitation(engine_order=1, amplitudes=(0.0,), phases=[0.0, 0.0]),
                  speed_rpm=1000.0)
    x = np.array([2e-6, 0.0])
    relative = 1e-3 / math.cos(math.pi / 6)  # u̇ that slips at v_ε
    for u_dot, expected in [(relative, 0.03 * 0.76159415595576489),
                            (-relative, -0.03 * 0.76159415595576489), (0.0, 0.0)]:
        r = assemble(scene, 0.0, x, np.array([u_dot, 0.0]), [Mode.SLIP_POSITIVE])
        assert r.normal_force[0] == pytest.approx(0.1, rel=1e-14)
        assert r.friction_force[0] == pytest.approx(expected, rel=1e-12, abs=0.0)


@st.composite
def resting_chains(draw):
    """A chain at rest with every contact closed (linear springs, Coulomb friction): one
    blade held by a fixed node, or 2–4 free blades. Each interface's μ is set so that holding
    the whole chain stuck needs r_e μ_e N_e, with the ratio r_e drawn around 1.

    Returns (scene, x, the needed friction, the ratios r_e).
    """
    grounded = draw(st.booleans())
    count = draw(st.integers(1 if grounded else 2, 4))
    names = [f"b{i}" for i in range(count)]
    ends = (["disc"] if grounded else []) + names
    parts = [dict(gap=draw(st.floats(-GAP, GAP)), angle=draw(st.floats(0.1, 1.4)),
                  normal=LinearSpring(stiffness=draw(st.floats(1e4, 1e7))),
                  overlap=draw(st.floats(1e-7, 2 * GAP))) for _ in ends[1:]]
    chain_blades = [draw(blades()) for _ in names]
    x = [] if grounded else [draw(st.floats(-4 * GAP, 4 * GAP))]
    for part in parts:
        x.append((x[-1] if x else 0.0) - part["gap"] - part["overlap"])
    x = np.array(x)
    excitation = Excitation(engine_order=1,
                            amplitudes=(draw(st.floats(-20.0, 20.0)), draw(st.floats(0.0, 50.0))),
                            phases=draw(st.lists(st.floats(0.0, 2 * math.pi), min_size=count,
                                                 max_size=count)))

    def scene_with(mus):
        group = BladeGroup()
        if grounded:
            group.add_fixed("disc")
        for name, blade in zip(names, chain_blades):
            group.add_blade(name, blade)
        for left, right, part, mu in zip(ends, ends[1:], parts, mus):
            group.connect(left, right, Interface(gap=part["gap"], angle=part["angle"],
                                                 normal=part["normal"], friction=Coulomb(mu=mu)))
        return Scene(group=group, excitation=excitation, speed_rpm=6e5)  # T_e = 0.1 ms

    # With every interface stuck and every blade at rest the needed friction does not
    # depend on μ: find it with μ = 1, then choose each μ_e from its ratio.
    probe = scene_with([1.0] * len(parts))
    modes = np.full(len(parts), Mode.STICK)
    q = np.array([excitation.amplitudes[0] + excitation.amplitudes[1] * math.sin(phase)
                  for phase in excitation.phases.values])  # Q_i(0)
    stiffness = np.array([blade.stiffness for blade in chain_blades])
    normal, friction = _law_forces(probe, x, np.zeros(count), modes)
    _, needed = _stuck_solution(probe, q - stiffness * x, normal, friction, modes)
    assume(np.all(np.abs(needed) > 1e-6 * normal))
    # The largest ratio, from either side of 1 and close to it; the others below it.
    worst = draw(st.sampled_from([1.15, 0.9, 1.05, 0.6, 1.001, 0.999, 1.3, 1.6]))
    ratios = np.array([worst * draw(st.floats(0.3, 1.0)) for _ in parts])
    ratios[draw(st.integers(0, len(parts) - 1))] = worst
    return scene_with(np.abs(needed) / (ratios * normal)), x, needed, ratios


@given(resting_chains())
def test_mode_selection_sticks_exactly_where_the_static_friction_is_within_mu_s_n(sample):
    """At rest every closed interface is a candidate for stick; the run's first sample is
    the mode rule's choice. The whole chain stays stuck exactly when every needed static
    friction, computed here from the blades' equilibrium, is within μ_s N with the μ_s
    given to the law; otherwise something slips, and a lone interface slips the way its
    needed friction pushes. Whatever is chosen, each stuck interface holds
    |f| ≤ μ_s N with f the static friction of the chosen modes (computed here), and each
    sliding one carries ±μ N by its direction."""
    scene, x, needed, ratios = sample
    sim = simulate(scene, 1, method=FixedStep(steps_per_period=8), samples_per_period=1,
                   initial=(x, np.zeros(len(x))))
    modes, friction = sim.modes[0], sim.friction_force[0]
    assert np.all(modes != Mode.OPEN)
    stuck = modes == Mode.STICK
    assert stuck.all() == bool(np.all(ratios <= 1.0))
    if len(modes) == 1 and not stuck[0]:
        assert modes[0] == (Mode.SLIP_POSITIVE if needed[0] > 0 else Mode.SLIP_NEGATIVE)
    mu = np.array([static_limit(interface.friction) for _, _, interface in scene.group.interfaces])
    q = np.array([scene.excitation.amplitudes[0] + scene.excitation.amplitudes[1] * math.sin(p)
                  for p in scene.excitation.phases.values])
    stiffness = np.array([scene.group.blade(name).stiffness for name in scene.blades])
    normal, sliding = _law_forces(scene, x, np.zeros(len(x)), modes)
    _, static = _stuck_solution(scene, q - stiffness * x, normal, sliding, modes)
    scale = np.abs(normal).max() + np.abs(q).max() + np.abs(stiffness * x).max()
    np.testing.assert_allclose(sim.normal_force[0], normal, rtol=1e-12, atol=1e-12 * scale)
    np.testing.assert_allclose(friction, static, rtol=1e-9, atol=1e-9 * scale)
    assert np.all(np.abs(friction[stuck]) <= mu[stuck] * normal[stuck] * (1 + 1e-9))
    np.testing.assert_allclose(np.abs(friction[~stuck]), mu[~stuck] * normal[~stuck], rtol=1e-12)


def test_mode_rule_lets_a_re_held_interface_slip_the_other_way():
    """Disc – a – b pressed together (gap 0, α = 1 rad, k_c = 1e5 N/m, μ_s = 1), unforced,
    at rest at x = (−3.64, −3.76) µm. By hand: N0 = 1e5 · 3.64e-6 · sin 1 and
    N1 = 1e5 · 0.12e-6 · sin 1. Held together, (a, b) would need about 70 μ_s N1. With both
    interfaces slipping, f = ±μ N, the relative accelerations computed below have the signs
    of the slips: (disc, a) slips negatively and (a, b) positively, the one consistent
    choice. The rule releases (a, b) negatively first, finds that slip reversing once
    (disc, a) slips too and holds it again; it must then let it slip positively, not keep
    it stuck with |f| ≈ 6 μ_s N1."""
    mu, sin, cos = 1.0, math.sin(1.0), math.cos(1.0)
    blade = Blade(mass=0.125, damping=0.0, stiffness=1e5)
    shroud = Interface(gap=0.0, angle=1.0, normal=LinearSpring(stiffness=1e5),
                       friction=Coulomb(mu=mu))
    group = BladeGroup().add_fixed("disc").add_blade("a", blade).add_blade("b", blade)
    group.connect("disc", "a", shroud).connect("a", "b", shroud)
    scene = Scene(group=group, excitation=Excitation(engine_order=1, amplitudes=(0.0,),
                                                     phases=[0.0, 0.0]), speed_rpm=6e5)
    x = np.array([-3.64e-6, -3.76e-6])
    normal = np.array([1e5 * 3.64e-6 * sin, 1e5 * 0.12e-6 * sin])
    friction = np.array([-mu * normal[0], mu * normal[1]])
    force = normal * sin + friction * cos          # F of (disc, a) and of (a, b)
    accel = np.array([-1e5 * x[0] + force[0] - force[1], -1e5 * x[1] + force[1]]) / 0.125
    assert (0.0 - accel[0]) * cos < 0.0 and (accel[0] - accel[1]) * cos > 0.0

    sim = simulate(scene, 1, method=FixedStep(steps_per_period=8), samples_per_period=1,
                   initial=(x, np.zeros(2)))
    stuck = sim.modes[0] == Mode.STICK
    assert np.all(np.abs(sim.friction_force[0][stuck]) <= mu * normal[stuck] * (1 + 1e-9))
    assert sim.modes[0].tolist() == [Mode.SLIP_NEGATIVE, Mode.SLIP_POSITIVE]
    np.testing.assert_allclose(sim.friction_force[0], friction, rtol=1e-12)


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

    labels, grounded, _ = cluster_labels(a.n_blades, a.n_blades, a.left, a.right, stuck)
    found = {frozenset(names[i] for i in np.flatnonzero(labels == c)) for c in range(len(grounded))}
    assert found == expected
    assert {frozenset(names[i] for i in np.flatnonzero(labels == c))
            for c in np.flatnonzero(grounded)} == ({frozenset(ground)} if ground else set())


def test_stick_clusters_of_a_chain_with_one_stuck_interface():
    blade = Blade(mass=0.1, damping=1.0, stiffness=1e5)
    shroud = Interface(gap=0.0, angle=0.5, normal=LinearSpring(stiffness=1e5),
                       friction=Coulomb(mu=0.5))
    group = BladeGroup.chain(4, blade, shroud)
    clusters = stick_clusters(group.graph, [("blade2", "blade3")])
    assert sorted(map(sorted, clusters)) == [["blade1"], ["blade2", "blade3"], ["blade4"]]
    with pytest.raises(ValueError, match="not an edge"):
        stick_clusters(group.graph, [("blade1", "blade4")])
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
