"""The group's linear modes in the open, stuck and closed limits, by nodal diameter, and
its Campbell diagram; checked against closed forms of spring–mass chains and rings."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from contact_laws import ConstantLoad, Coulomb, Hertz, KelvinVoigt, LinearSpring
from shroudnet import (
    AntiPhase,
    Blade,
    BladeGroup,
    Coupling,
    EngineOrderWave,
    Excitation,
    Interface,
    Scene,
    Southwell,
    frequency_response,
    group_campbell,
    linear_modes,
    scenes,
)
from shroudnet.linear.modes import excited_diameter
from shroudnet.model.substructure import Substructure

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
        linear_modes(ring, "slipping")
    with pytest.raises(ValueError, match="sectors = 4 does not divide the 6 blades"):
        linear_modes(ring, sectors=4)
    chain = scene_of(BladeGroup.chain(3, Blade(mass=MASS, damping=0.0, stiffness=GROUND),
                                      Coupling(stiffness=LINK)))
    with pytest.raises(ValueError, match="not sorted by nodal diameter"):
        linear_modes(chain).of_diameter(0)


# ---- the closed limit: every interface closed, normal springs included ---------------------

def eigen_hz(stiffness, mass):
    """The natural frequencies [Hz] of K φ = ω² M φ, ascending."""
    return np.sqrt(np.sort(np.linalg.eigvals(np.linalg.solve(mass, stiffness)).real)) \
        / (2 * math.pi)


def gapped_trio(*, ground_law=KelvinVoigt(stiffness=7e5, damping=3.0), gap=2e-5):
    """Three blades and a disc, every interface open at rest (``gap``):

        disc ──(γ, frictionless, ground_law)── c ──(β, Coulomb)── b ──(α, elastic)── a

    a–b an elastic contact (k_n, k_t), b–c a rigid Coulomb contact, c–disc a frictionless
    contact."""
    group = BladeGroup().add_fixed("disc")
    for name, mass, stiffness in (("a", 0.1, 1e5), ("b", 0.3, 2e5), ("c", 0.2, 1.5e5)):
        group.add_blade(name, Blade(mass=mass, damping=1.0, stiffness=stiffness))
    group.connect("a", "b", Interface(gap=gap, angle=0.4, normal=LinearSpring(stiffness=6e5),
                                      friction=Coulomb(mu=0.3), tangential_stiffness=4e5))
    group.connect("b", "c", Interface(gap=gap, angle=0.9, normal=LinearSpring(stiffness=2e6),
                                      friction=Coulomb(mu=0.5)))
    group.connect("c", "disc", Interface(gap=gap, angle=1.2, normal=ground_law))
    return scene_of(group)


def test_closed_blades_add_the_normal_springs_that_stuck_leaves_out_of_a_gap_design():
    """DESIGN §2: δ = (u − Δ) sin α, so a normal spring k_n is k_n sin²α along x and a
    tangential one k_t cos²α. Stuck, b and c are one body (x_bc) and only the elastic
    contact's k_t acts; closed, k_n sin²α of a–b and k_g sin²γ of c–disc join it, and the
    Kelvin–Voigt dashpot c_g sin²γ. Written here by hand in (x_a, x_bc)."""
    scene = gapped_trio()
    mass = np.diag([0.1, 0.5])
    tangential = 4e5 * math.cos(0.4) ** 2
    normal, ground = 6e5 * math.sin(0.4) ** 2, 7e5 * math.sin(1.2) ** 2

    def stiffness(edge, disc):
        return np.array([[1e5 + edge, -edge], [-edge, 3.5e5 + edge + disc]])

    assert linear_modes(scene, "stuck").frequencies == pytest.approx(
        eigen_hz(stiffness(tangential, 0.0), mass), rel=1e-12)
    closed = linear_modes(scene, "closed")
    assert closed.frequencies == pytest.approx(
        eigen_hz(stiffness(tangential + normal, ground), mass), rel=1e-12)
    assert np.allclose(closed.shapes[1], closed.shapes[2])  # b and c one body
    # The response: X = T (Tᵀ(K − ω²M + iωC)T)⁻¹ Tᵀ F with T taking x_bc to x_b and x_c.
    frequencies = np.array([120.0, 190.0, 260.0])
    found = frequency_response(scene, frequencies, "closed").response
    a = scene.arrays
    forcing = a.harmonic_amplitudes[1] * np.exp(1j * a.harmonic_phases[1])
    basis = np.array([[1.0, 0.0], [0.0, 1.0], [0.0, 1.0]])
    damping = np.diag([1.0, 2.0]) + np.diag([0.0, 3.0 * math.sin(1.2) ** 2])
    for f, row in zip(frequencies, found):
        omega = 2 * math.pi * f
        dynamic = stiffness(tangential + normal, ground) - omega ** 2 * mass \
            + 1j * omega * damping
        expected = basis @ np.linalg.solve(dynamic, basis.T @ forcing)
        assert row == pytest.approx(expected, rel=1e-10)


def test_a_law_stiff_only_under_load_has_no_closed_limit_open_and_one_when_preloaded():
    """Hertz N = k δ^{3/2}: ∂N/∂δ = 0 at first touch, so a gap design is refused by name;
    preloaded (δ₀ = −Δ sin γ), it is the spring 1.5 k √δ₀ sin²γ along x. A constant load
    never depends on δ: closed is stuck."""
    with pytest.raises(ValueError, match=r"interface 2 \('c', 'disc'\).*Hertz law"):
        linear_modes(gapped_trio(ground_law=Hertz(stiffness=1e9)), "closed")
    with pytest.raises(ValueError, match="frequency_response: contacts='closed'"):
        frequency_response(gapped_trio(ground_law=Hertz(stiffness=1e9)), [100.0], "closed")
    preloaded = gapped_trio(ground_law=Hertz(stiffness=1e9), gap=-2e-5)
    ground = 1.5e9 * math.sqrt(2e-5 * math.sin(1.2)) * math.sin(1.2) ** 2
    edge = 4e5 * math.cos(0.4) ** 2 + 6e5 * math.sin(0.4) ** 2
    expected = eigen_hz(np.array([[1e5 + edge, -edge], [-edge, 3.5e5 + edge + ground]]),
                        np.diag([0.1, 0.5]))
    assert linear_modes(preloaded, "closed").frequencies == pytest.approx(expected, rel=1e-12)
    constant = gapped_trio(ground_law=ConstantLoad(force=5.0))
    assert linear_modes(constant, "closed").frequencies == pytest.approx(
        eigen_hz(np.array([[1e5 + edge, -edge], [-edge, 3.5e5 + edge]]), np.diag([0.1, 0.5])),
        rel=1e-12)


def point_mass(mass, stiffnesses):
    """A point mass moving in the plane on springs ``stiffnesses`` along x and y."""
    return Substructure(mass * np.eye(2), np.diag(stiffnesses), points={"tip": np.eye(2)},
                        load=np.array([1.0, 0.0]))


def test_a_stuck_gap_between_substructures_is_free_across_its_face_and_closed_is_not():
    """Two point masses in the plane, their tips in contact across a face of normal
    n = (cos φ, sin φ), with a gap: stuck holds t·(r_a − r_b) = 0 only, so r_b = r_a − s n
    with (r_a, s) free; closed adds k_n s². Assembled by hand in (r_a, s)."""
    phi, k_n = 0.6, 8e5
    n = np.array([math.cos(phi), math.sin(phi)])
    group = BladeGroup().add_blade("a", point_mass(0.2, (3e5, 5e5)))
    group.add_blade("b", point_mass(0.1, (2e5, 9e5)))
    group.connect(("a", "tip"), ("b", "tip"), Interface(
        gap=1e-5, normal=LinearSpring(stiffness=k_n), friction=Coulomb(mu=0.3),
        normal_direction=tuple(n), tangent_direction=(-n[1], n[0])))
    scene = scene_of(group)
    basis = np.zeros((4, 3))
    basis[:2, :2] = basis[2:, :2] = np.eye(2)
    basis[2:, 2] = -n
    mass = basis.T @ np.diag([0.2, 0.2, 0.1, 0.1]) @ basis
    stiffness = basis.T @ np.diag([3e5, 5e5, 2e5, 9e5]) @ basis
    assert linear_modes(scene, "stuck").frequencies == pytest.approx(
        eigen_hz(stiffness, mass), rel=1e-12)
    stiffness[2, 2] += k_n
    assert linear_modes(scene, "closed").frequencies == pytest.approx(
        eigen_hz(stiffness, mass), rel=1e-12)


def test_the_packet_with_a_gap_closed_is_the_preloaded_packet_stuck():
    """A linear contact spring has one stiffness at every penetration, so the gap design
    closed is the preloaded design stuck, while stuck with its gap leaves the springs out
    (measured: 197.3, 280.4 × 5, 453.6 Hz against 197.3, 307.3, 370.1, 439.7 Hz)."""
    gapped, preloaded = scenes.modal_packet(gap=2e-6), scenes.modal_packet(gap=-2e-6)
    closed = linear_modes(gapped, "closed").frequencies
    assert closed == pytest.approx(linear_modes(preloaded, "stuck").frequencies, rel=1e-12)
    assert linear_modes(gapped, "stuck").frequencies[1] < 0.95 * closed[1]


@settings(max_examples=25, deadline=None)
@given(st.lists(st.tuples(st.floats(-3e-5, 3e-5), st.floats(0.0, math.pi / 2),
                          st.sampled_from(["rigid", "elastic", "frictionless"]),
                          st.floats(1e4, 1e7)), min_size=2, max_size=5),
       st.booleans())
def test_closed_frequencies_are_at_least_stuck_ones_and_those_at_least_open_ones(edges, ring):
    """Each limit adds springs ∂N/∂δ ≥ 0 or constraints to the one before, so the k-th
    eigenvalue never falls (Courant–Fischer), whatever the gaps, angles and laws."""
    ring = ring and len(edges) >= 3
    n = len(edges) if ring else len(edges) + 1
    group = BladeGroup()
    for i in range(n):
        group.add_blade(f"b{i}", Blade(mass=0.1 + 0.05 * i, damping=0.0,
                                       stiffness=1e5 * (1 + i % 3)))
    for i, (gap, angle, kind, stiffness) in enumerate(edges):
        interface = Interface(
            gap=gap, angle=angle, normal=LinearSpring(stiffness=stiffness),
            friction=None if kind == "frictionless" else Coulomb(mu=0.3),
            tangential_stiffness=2.0 * stiffness if kind == "elastic" else None)
        group.connect(f"b{i}", f"b{(i + 1) % n}", interface)
    scene = scene_of(group)
    open_, stuck, closed = (linear_modes(scene, c).frequencies
                            for c in ("open", "stuck", "closed"))
    assert len(closed) == len(stuck) <= len(open_)
    assert np.all(closed >= stuck * (1 - 1e-12))
    assert np.all(stuck >= open_[:len(stuck)] * (1 - 1e-12))


# ---- nodal diameters from the cyclic projection of each eigenspace -------------------------

def diameter_shares(dofs, sectors):
    """For each column of ``dofs`` (rows sector-major), the share of its square in each
    nodal diameter 0 … N//2 (harmonics k and N − k of the DFT over the sectors)."""
    grid = dofs.reshape(sectors, -1, dofs.shape[1])
    power = (np.abs(np.fft.fft(grid, axis=0)) ** 2).sum(axis=1)
    shares = np.zeros((sectors // 2 + 1, dofs.shape[1]))
    for k in range(sectors):
        shares[min(k, sectors - k)] += power[k]
    return shares / shares.sum(axis=0)


def every_diameter(sectors):
    """The diameters of one family of a tuned ring: 0 and N/2 once, the others twice."""
    return sorted(min(k, sectors - k) for k in range(sectors))


@pytest.mark.parametrize("n", [1, 2, 3, 7, 12, 36])
def test_a_ring_of_uncoupled_blades_gives_its_degenerate_family_every_diameter_once(n):
    """N identical blades whose shrouds are open: N modes at f₀ = √(k/m)/2π, one family,
    in which each diameter appears once (twice for 0 < ND < N/2), each mode a pure
    diameter, still mass-orthonormal."""
    blade = Blade(mass=MASS, damping=0.0, stiffness=GROUND)
    shroud = Interface(gap=1e-5, angle=0.5, normal=LinearSpring(stiffness=1e6),
                       friction=Coulomb(mu=0.3))
    group = BladeGroup.chain(n, blade, shroud)
    if n > 2:
        group.connect(f"blade{n}", "blade1", shroud)
    modes = linear_modes(scene_of(group), sectors=n)
    assert modes.frequencies == pytest.approx([hz(GROUND, MASS)] * n, rel=1e-12)
    assert sorted(modes.nodal_diameters.tolist()) == every_diameter(n)
    shares = diameter_shares(modes.shapes, n)
    assert np.all(shares[modes.nodal_diameters, np.arange(n)] > 1 - 1e-12)
    assert np.allclose(modes.shapes.T @ np.diag(ring_masses(n)) @ modes.shapes, np.eye(n))
    assert modes.families() == pytest.approx(np.full((n // 2 + 1, 1), hz(GROUND, MASS)))
    for nd in range(n // 2 + 1):
        assert modes.of_diameter(nd) == pytest.approx(
            [hz(GROUND, MASS)] * every_diameter(n).count(nd), rel=1e-12)


@pytest.mark.parametrize("n", [5, 6])
def test_a_ring_of_substructures_gives_each_degenerate_family_every_diameter_once(n):
    """N point masses in the plane (√(k_x/m), √(k_y/m)), their shroud faces open: two
    families of N modes, each with every diameter once, read from the two coordinates of
    each sector."""
    group = BladeGroup()
    names = [f"s{i}" for i in range(n)]
    for name in names:
        group.add_blade(name, point_mass(0.2, (3e5, 8e5)))
    for left, right in zip(names, names[1:] + names[:1]):
        group.connect((left, "tip"), (right, "tip"), Interface(
            gap=1e-5, normal=LinearSpring(stiffness=1e6), friction=Coulomb(mu=0.3),
            normal_direction=(0.6, 0.8), tangent_direction=(-0.8, 0.6)))
    scene = Scene(group=group, speed_rpm=3000.0, excitation=Excitation(
        engine_order=1, amplitudes=(0.0, 1.0), phases=EngineOrderWave(n)))
    modes = linear_modes(scene, sectors=n)
    low, high = hz(3e5, 0.2), hz(8e5, 0.2)
    for family, frequency in enumerate((low, high)):
        members = slice(family * n, (family + 1) * n)
        assert modes.frequencies[members] == pytest.approx([frequency] * n, rel=1e-12)
        assert sorted(modes.nodal_diameters[members].tolist()) == every_diameter(n)
    for nd in range(n // 2 + 1):
        twice = every_diameter(n).count(nd)
        assert modes.of_diameter(nd) == pytest.approx([low] * twice + [high] * twice,
                                                       rel=1e-12)
    assert modes.families() == pytest.approx(np.tile([low, high], (n // 2 + 1, 1)))


@pytest.mark.parametrize("ratio", [0.3, 1e-9])
@pytest.mark.parametrize(("n", "reach"), [(7, 1), (12, 1), (7, 2), (12, 2)])
def test_a_tuned_ring_of_couplings_has_each_diameter_at_its_closed_form(n, reach, ratio):
    """Each blade coupled to its ``reach``-th neighbour by k_c = ``ratio`` k:
    ω² = (k + 2 k_c (1 − cos(2π reach ND/N)))/m. With reach 2 the frequency rises and
    falls again with ND, and on 12 blades ND 0 and 6, 1 and 5, 2 and 4 share one
    frequency: eigenspaces of two diameters. With k_c = 10⁻⁹ k the whole family lies
    within the eigenspace tolerance and is projected as one; each diameter must still
    carry its own frequency, whose neighbours differ by ≥ 10⁻¹¹ of it."""
    coupling = ratio * GROUND
    group = BladeGroup()
    for s in range(n):
        group.add_blade(s, Blade(mass=MASS, damping=0.0, stiffness=GROUND))
    for s in range(n):
        group.connect(s, (s + reach) % n, Coupling(stiffness=coupling))
    modes = linear_modes(scene_of(group), sectors=n)
    for nd in range(n // 2 + 1):
        expected = hz(GROUND + 2 * coupling * (1 - math.cos(2 * math.pi * reach * nd / n)),
                      MASS)
        assert modes.of_diameter(nd) == pytest.approx(
            [expected] * every_diameter(n).count(nd), rel=1e-14, abs=0.0)
    shares = diameter_shares(modes.shapes, n)
    assert np.all(shares[modes.nodal_diameters, np.arange(n)] > 1 - 1e-9)
    assert np.all(np.diff(modes.frequencies) >= 0.0)
