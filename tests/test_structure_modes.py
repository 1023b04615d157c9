"""The linear modes of groups of substructures (DESIGN §7), checked in the nodes' own degrees
of freedom, against the engine's stuck motion, by nodal diameter, and mistuned.

Every reference here is assembled in the test from what the user gives (``matrices_at``,
``Substructure.point``, the interfaces' directions), in physical degrees of freedom, never
from the lowered coordinates the library solves in.
"""

import math

import numpy as np
import pytest
import scipy.linalg

import shroudnet as sn
from contact_laws import Coulomb, LinearSpring
from shroudnet import scenes
from shroudnet.model.lowering import from_dofs
from shroudnet.model.substructure import Substructure
from shroudnet.studies.mistuning import mistuned_group
from tests.test_structures import as_substructures, stuck_ring

SPEED = 6000.0
SILENT = sn.Excitation(engine_order=1, amplitudes=(0.0, 0.0), phases=sn.AntiPhase())
#: Mass-proportional damping C = α M [1/s]: every mode of any constrained group then decays
#: as exp(−α t / 2), at ω_d = √(ω² − α²/4).
ALPHA = 20.0
BETA = 0.5  # the angle of the shroud faces' normal in their points' plane [rad]
NORMAL = (math.cos(BETA), math.sin(BETA))
TANGENT = (-math.sin(BETA), math.cos(BETA))


def three_masses(masses, ground, link, *, spin=0.0, damping=0.0):
    """Three masses in a row, the first on a spring to ground; the point "root" (d = 1) is
    the first, "shroud" (d = 2) mixes the second and third; K₁ = spin·K₀."""
    mass = np.diag(masses)
    stiffness = np.array([[ground + link, -link, 0.0], [-link, 2 * link, -link],
                          [0.0, -link, link]])
    return Substructure(mass, stiffness, damping * mass,
                        stiffness_speed=None if spin == 0.0 else spin * stiffness,
                        points={"root": [[1.0, 0.0, 0.0]],
                                "shroud": [[0.0, 1.0, 0.0], [0.0, 0.3, 1.0]]}, load="root")


def beam():
    return sn.cantilever_beam(length=0.08, youngs_modulus=2e11, density=7800.0, width=0.02,
                              thickness=0.004, elements=2, tip_mass=0.01, hub_radius=0.2)


def modal():
    return Substructure.modal([sn.Southwell(f0=400.0, coefficient=3.0), 1300.0], 0.0,
                              [0.05, 0.02], {"tip": [1.0, -0.5]})


def nodes():
    """Four nodes of every kind: dense with K₁, a sparse beam, modal, a Blade."""
    return {"a": three_masses([0.1, 0.05, 0.04], 4e5, 2e5, spin=1e-3), "beam": beam(),
            "modal": modal(), "blade": sn.Blade(mass=0.08, damping=0.0, stiffness=3e5)}


class Physical:
    """The nodes' own degrees of freedom, stacked in the order of ``bodies``: M, K(Ω) and
    the rows r = P q of any point (a fixed node has none)."""

    def __init__(self, bodies, speed_rpm):
        self.bodies = bodies
        blocks = []
        for body in bodies.values():
            if isinstance(body, Substructure):
                matrices = body.matrices_at(speed_rpm)
                blocks.append((matrices.mass, matrices.stiffness))
            else:
                blocks.append((np.array([[body.mass]]),
                               np.array([[body.stiffness_at(speed_rpm)]])))
        self.mass = scipy.linalg.block_diag(*(m for m, _ in blocks))
        self.stiffness = scipy.linalg.block_diag(*(k for _, k in blocks))
        sizes = [len(m) for m, _ in blocks]
        self.offsets = dict(zip(bodies, np.concatenate([[0], np.cumsum(sizes)[:-1]])))
        self.n = int(sum(sizes))

    def rows(self, node, point=None):
        if node not in self.bodies:
            return None
        body = self.bodies[node]
        local = body.point(point) if isinstance(body, Substructure) else np.eye(1)
        rows = np.zeros((local.shape[0], self.n))
        rows[:, self.offsets[node]:self.offsets[node] + local.shape[1]] = local
        return rows

    def relative(self, left, right):
        """D with r_left − r_right = D q; an end is a node or (node, point)."""
        a, b = (self.rows(*end) if isinstance(end, tuple) else self.rows(end)
                for end in (left, right))
        return -b if a is None else a if b is None else a - b


def hz(eigenvalues):
    return np.sqrt(np.clip(eigenvalues, 0.0, None)) / (2 * math.pi)


def stacked(modes, scene):
    """The mode shapes in every node's own degrees of freedom, nodes in order."""
    return np.vstack([modes.node_shapes(node) for node in scene.blades])


def group_of(bodies, edges, fixed=()):
    group = sn.BladeGroup()
    for name, body in bodies.items():
        group.add_blade(name, body)
    for name in fixed:
        group.add_fixed(name)
    for left, right, edge in edges:
        group.connect(left, right, edge)
    return group


# ---- open and stuck, against the physical degrees of freedom ----------------------------------

def test_open_modes_are_those_of_the_nodes_matrices_side_by_side():
    bodies = nodes()
    edges = [(("a", "shroud"), ("beam", "shroud"), sn.Interface(
                 gap=-1e-5, normal=LinearSpring(stiffness=1e6), friction=Coulomb(mu=0.3),
                 normal_direction=NORMAL, tangent_direction=TANGENT)),
             (("modal", "tip"), "blade", sn.Interface(
                 gap=-1e-5, angle=0.6, normal=LinearSpring(stiffness=1e6)))]
    scene = sn.Scene(group=group_of(bodies, edges), excitation=SILENT, speed_rpm=SPEED)
    modes = sn.linear_modes(scene, "open")
    reference = Physical(bodies, SPEED)
    expected = scipy.linalg.eigh(reference.stiffness, reference.mass, eigvals_only=True)
    assert scene.arrays.is_structure and len(modes.frequencies) == reference.n == 14
    np.testing.assert_allclose(modes.frequencies, hz(expected), rtol=1e-9)
    # Each shape, read in the nodes' own degrees of freedom, is a mode of K(Ω), M.
    shapes = stacked(modes, scene)
    np.testing.assert_allclose(shapes.T @ reference.mass @ shapes, np.eye(14), atol=1e-9)
    residual = reference.stiffness @ shapes - reference.mass @ shapes * (
        2 * math.pi * modes.frequencies) ** 2
    assert np.abs(residual).max() <= 1e-9 * np.abs(reference.stiffness @ shapes).max()
    np.testing.assert_allclose(modes.point_shapes("beam", "shroud"),
                               bodies["beam"].point("shroud") @ modes.node_shapes("beam"),
                               atol=1e-12)
    np.testing.assert_array_equal(modes.point_shapes("blade"), modes.node_shapes("blade"))


def test_stuck_modes_eliminate_the_tangential_constraints_in_the_physical_dofs():
    bodies = nodes()
    spring, link = 1e6, 5e4
    stick = sn.Interface(gap=-2e-5, normal=LinearSpring(stiffness=spring),
                         friction=Coulomb(mu=0.3), normal_direction=NORMAL,
                         tangent_direction=TANGENT)
    open_stick = sn.Interface(gap=1e-5, angle=0.6, normal=LinearSpring(stiffness=spring),
                              friction=Coulomb(mu=0.3))
    impact = sn.Interface(gap=-1e-6, angle=math.pi / 2, normal=LinearSpring(stiffness=spring),
                          friction=Coulomb(mu=0.3))  # no tangential part: never sticks
    frictionless = sn.Interface(gap=-1e-5, normal=LinearSpring(stiffness=2 * spring),
                                normal_direction=TANGENT, tangent_direction=NORMAL)
    edges = [(("a", "shroud"), ("beam", "shroud"), stick),
             (("modal", "tip"), "blade", open_stick),
             (("beam", "load"), "casing", impact),
             (("a", "shroud"), "casing", frictionless),
             ("blade", ("a", "root"), sn.Coupling(stiffness=link))]
    scene = sn.Scene(group=group_of(bodies, edges, fixed=["casing"]), excitation=SILENT,
                     speed_rpm=SPEED)
    modes = sn.linear_modes(scene, "stuck")

    p = Physical(bodies, SPEED)
    d_stick, d_open = p.relative(*edges[0][:2]), p.relative(*edges[1][:2])
    d_impact, d_frictionless = p.relative(*edges[2][:2]), p.relative(*edges[3][:2])
    d_link = p.relative(*edges[4][:2])
    stiffness = p.stiffness + link * d_link.T @ d_link
    for d, direction, k in ((d_stick, NORMAL, spring), (d_impact, (1.0,), spring),
                            (d_frictionless, TANGENT, 2 * spring)):  # closed at rest
        row = np.asarray(direction) @ d
        stiffness = stiffness + k * np.outer(row, row)
    constraints = np.vstack([np.asarray(TANGENT) @ d_stick, math.cos(0.6) * d_open[0]])
    basis = scipy.linalg.null_space(constraints)
    expected = scipy.linalg.eigh(basis.T @ stiffness @ basis, basis.T @ p.mass @ basis,
                                 eigvals_only=True)
    assert len(modes.frequencies) == p.n - 2
    np.testing.assert_allclose(modes.frequencies, hz(expected), rtol=1e-9)
    shapes = stacked(modes, scene)
    assert np.abs(constraints @ shapes).max() <= 1e-9 * np.abs(shapes).max()
    np.testing.assert_allclose(shapes.T @ p.mass @ shapes, np.eye(p.n - 2), atol=1e-9)
    # open: the same group with nothing from the interfaces but the coupling
    open_ = sn.linear_modes(scene, "open")
    np.testing.assert_allclose(open_.frequencies, hz(scipy.linalg.eigh(
        p.stiffness + link * d_link.T @ d_link, p.mass, eigvals_only=True)), rtol=1e-9)


def test_a_prescribed_motion_node_is_held_as_a_fixed_one():
    grip = sn.Interface(gap=-1e-5, angle=0.4, normal=LinearSpring(stiffness=1e6),
                        friction=Coulomb(mu=0.3))
    found = {}
    for kind in ("fixed", "shaker"):
        group = sn.BladeGroup().add_blade("modal", modal()).add_blade("a", nodes()["a"])
        if kind == "fixed":
            group.add_fixed("held")
        else:
            group.add_prescribed("held", sn.HarmonicMotion(amplitude=1e-5, frequency=50.0))
        group.connect(("modal", "tip"), "held", grip)
        group.connect(("a", "root"), "held", sn.Coupling(stiffness=1e5))
        scene = sn.Scene(group=group, excitation=SILENT, speed_rpm=SPEED)
        found[kind] = [sn.linear_modes(scene, c).frequencies for c in ("open", "stuck")]
    for fixed, shaken in zip(found["fixed"], found["shaker"]):
        np.testing.assert_allclose(shaken, fixed, rtol=1e-12)
    assert len(found["shaker"][1]) == len(found["shaker"][0]) - 1 == 4


def test_sectors_of_unequal_nodes_and_shapes_without_a_scene_are_refused():
    group = sn.BladeGroup().add_blade("a", nodes()["a"]).add_blade("modal", modal())
    scene = sn.Scene(group=group, excitation=SILENT, speed_rpm=SPEED)
    with pytest.raises(ValueError, match="different numbers of degrees of freedom"):
        sn.linear_modes(scene, sectors=2)
    modes = sn.linear_modes(scene)
    bare = sn.LinearModes(modes.frequencies, modes.shapes, None, "open", None, SPEED)
    with pytest.raises(ValueError, match="node_shapes needs the scene"):
        bare.node_shapes("a")


# ---- the engine's stuck motion vibrates at the stuck modes --------------------------------------

def stuck_group():
    """Two three-mass nodes and a blade held by preloaded interfaces whose friction never
    lets go, two of them on a fixed casing; damping α M everywhere."""
    grip = Coulomb(mu=50.0)
    group = sn.BladeGroup()
    group.add_blade("a", three_masses([0.1, 0.05, 0.04], 4e5, 2e5, damping=ALPHA))
    group.add_blade("b", three_masses([0.12, 0.06, 0.03], 5e5, 1.5e5, damping=ALPHA))
    group.add_blade("c", sn.Blade(mass=0.08, damping=ALPHA * 0.08, stiffness=3e5))
    group.add_fixed("casing")
    group.connect(("a", "shroud"), ("b", "shroud"), sn.Interface(
        gap=-2e-5, normal=LinearSpring(stiffness=1e5), friction=grip,
        normal_direction=NORMAL, tangent_direction=TANGENT))
    group.connect(("b", "root"), "c", sn.Interface(
        gap=-1e-5, angle=0.6, normal=LinearSpring(stiffness=2e5), friction=grip))
    group.connect(("a", "shroud"), "casing", sn.Interface(
        gap=-1e-5, normal=LinearSpring(stiffness=1e5), friction=grip,
        normal_direction=TANGENT, tangent_direction=NORMAL))
    return group


def stuck_equilibrium(scene):
    """The nodes' own degrees of freedom at rest with every interface stuck (t·r = 0) and
    its preload pushing, solved with the constraint forces as Lagrange multipliers."""
    p = Physical({name: scene.group.blade(name) for name in scene.blades}, scene.speed_rpm)
    stiffness, force, constraints = p.stiffness.copy(), np.zeros(p.n), []
    for (left, right, interface), points in zip(scene.group.interfaces,
                                                scene.group.edge_points("interface")):
        ends = [node if point is None or node not in p.bodies else (node, point)
                for node, point in zip((left, right), points)]
        d = p.relative(*ends)
        if interface.normal_direction is None:
            s, c = math.sin(interface.angle), math.cos(interface.angle)
            normal, tangent, gap = s * d[0], c * d[0], interface.gap * s
        else:
            normal = np.asarray(interface.normal_direction) @ d
            tangent = np.asarray(interface.tangent_direction) @ d
            gap = interface.gap
        k = interface.normal.stiffness  # N = k (n·r − Δ), closed: −N n on the left point
        stiffness += k * np.outer(normal, normal)
        force += k * gap * normal
        constraints.append(tangent)
    g = np.array(constraints)
    kkt = np.block([[stiffness, g.T], [g, np.zeros((len(g), len(g)))]])
    return np.linalg.solve(kkt, np.concatenate([force, np.zeros(len(g))]))[:p.n]


def test_a_group_stuck_at_every_interface_vibrates_at_its_stuck_modes():
    """The monodromy of the engine's stick phase is exp(A T) of the constrained linear
    system: with C = α M each mode's multiplier is exp((−α/2 ± i ω_d) T), ω_d² = ω² − α²/4,
    ω from ``linear_modes(contacts="stuck")``; each stuck interface adds a multiplier 0 (its
    relative velocity, projected away) and 1 (its frozen relative displacement)."""
    group = stuck_group()
    highest = sn.linear_modes(sn.Scene(group=group, excitation=SILENT, speed_rpm=SPEED),
                              "stuck").frequencies.max()
    # a period shorter than half the fastest mode's: arg μ = ω_d T lies in (0, π)
    scene = sn.Scene(group=group, excitation=SILENT, speed_rpm=60.0 * 2.5 * highest)
    modes = sn.linear_modes(scene, "stuck")
    x0 = stuck_equilibrium(scene)
    a = scene.arrays
    n = a.n_blades
    closed = a.normal_rows[:, :n] @ from_dofs(a.layout, x0) - a.normal_gap
    assert np.all(closed > 0.0)  # every contact closed
    matrix = sn.monodromy(scene, 1, initial=(x0, np.zeros(n)),
                          method=sn.Adaptive(rtol=1e-10, max_step=0.01))
    multipliers = np.linalg.eigvals(matrix)
    zeros = np.abs(multipliers) < 1e-10
    ones = np.abs(multipliers - 1.0) < 1e-8
    assert zeros.sum() == ones.sum() == a.n_interfaces == 3
    modal = multipliers[~zeros & ~ones]
    period = scene.excitation_period
    assert len(modal) == 2 * len(modes.frequencies) == 2 * (n - 3)
    np.testing.assert_allclose(np.abs(modal), math.exp(-ALPHA * period / 2), rtol=1e-10)
    damped = np.sort(np.angle(modal)[np.angle(modal) > 0.0]) / period
    found = np.sqrt(damped**2 + ALPHA**2 / 4) / (2 * math.pi)
    np.testing.assert_allclose(found, modes.frequencies, rtol=1e-10)


# ---- rings: nodal diameters ----------------------------------------------------------------------

def projectors(modes, mass):
    """Φ_f Φ_fᵀ M of each group of equal frequencies (a degenerate pair's shapes are any
    basis of its plane; the projector is not)."""
    groups, start = [], 0
    f = modes.frequencies
    for k in range(1, len(f) + 1):
        if k == len(f) or f[k] > f[start] * (1 + 1e-9):
            shapes = modes.shapes[:, start:k]
            groups.append(shapes @ shapes.T @ mass)
            start = k
    return groups


def blade_ring():
    interface = sn.Interface(gap=-1e-5, angle=0.7, normal=LinearSpring(stiffness=3e5))
    return sn.Scene(group=sn.BladeGroup.ring(7, sn.Blade(mass=0.1, damping=0.0,
                                                         stiffness=1e5), interface),
                    excitation=SILENT, speed_rpm=SPEED)


@pytest.mark.parametrize("make", [blade_ring, scenes.bladed_disc_24],
                         ids=["preloaded frictionless ring", "bladed disc that sticks"])
@pytest.mark.parametrize("contacts", ["open", "stuck"])
def test_one_dof_substructures_have_the_blades_modes_and_diameters(make, contacts):
    blades = make()
    structures = as_substructures(blades)
    expected, found = (sn.linear_modes(s, contacts) for s in (blades, structures))
    assert structures.arrays.is_structure and found.sectors == expected.sectors
    np.testing.assert_allclose(found.frequencies, expected.frequencies, rtol=1e-9)
    np.testing.assert_array_equal(found.nodal_diameters, expected.nodal_diameters)
    mass = np.diag(blades.arrays.mass)
    physical = stacked(found, structures)  # x of each blade: its 1-DOF substructure's q
    as_blades = sn.LinearModes(found.frequencies, physical, found.nodal_diameters,
                               contacts, found.sectors, found.speed_rpm)
    for got, want in zip(projectors(as_blades, mass), projectors(expected, mass)):
        assert np.abs(got - want).max() <= 1e-7


DISC = sn.Blade(mass=0.3, damping=0.0, stiffness=2e6)


def cyclic_ring(sectors, ring_link, root_link, spring, *, spin=1e-3):
    """``sectors`` sectors of a disc node (a Blade) and a three-mass blade on it (its point
    "root" coupled to the disc), the discs coupled round the ring, the blades' shrouds
    joined by preloaded interfaces that stick."""
    body = three_masses([0.1, 0.05, 0.04], 4e5, 2e5, spin=spin)
    group = sn.BladeGroup()
    for s in range(sectors):
        group.add_blade(f"disc{s}", DISC).add_blade(f"blade{s}", body)
        group.connect(f"disc{s}", (f"blade{s}", "root"), sn.Coupling(stiffness=root_link))
    for s in range(sectors):
        following = (s + 1) % sectors
        group.connect(f"disc{s}", f"disc{following}", sn.Coupling(stiffness=ring_link))
        group.connect((f"blade{s}", "shroud"), (f"blade{following}", "shroud"), sn.Interface(
            gap=-1e-5, normal=LinearSpring(stiffness=spring), friction=Coulomb(mu=0.5),
            normal_direction=NORMAL, tangent_direction=TANGENT))
    return body, group


@pytest.mark.parametrize("contacts", ["open", "stuck"])
def test_a_ring_of_substructures_sorts_its_modes_by_the_cyclic_reduction(contacts):
    """Sector s moves as Re(ŷ e^{i s θ}), θ = 2π ND/N, ŷ = (x̂_disc, q̂): the ring's modes of
    diameter ND are those of one sector whose ring-wise springs k are scaled by
    2 − 2 cos θ (the discs' couplings; the shrouds' normal springs k_n Φ_sᵀ n nᵀ Φ_s when
    stuck), under tᵀ Φ_s q̂ = 0 when stuck and θ ≠ 0 (tᵀ Φ_s q̂ (1 − e^{iθ}) = 0)."""
    sectors, ring_link, root_link, spring = 8, 1e6, 5e5, 2e5
    body, group = cyclic_ring(sectors, ring_link, root_link, spring)
    scene = sn.Scene(group=group, excitation=SILENT, speed_rpm=SPEED)
    modes = sn.linear_modes(scene, contacts, sectors=sectors)
    matrices = body.matrices_at(SPEED)
    root, shroud = body.point("root"), body.point("shroud")
    held = np.hstack([-np.ones((1, 1)), root])  # x_disc − r_root over (x_disc, q)
    mass = scipy.linalg.block_diag([[DISC.mass]], matrices.mass)
    normal = np.hstack([[0.0], np.asarray(NORMAL) @ shroud])
    tangent = np.hstack([[0.0], np.asarray(TANGENT) @ shroud])
    for nd in range(sectors // 2 + 1):
        factor = 2 - 2 * math.cos(2 * math.pi * nd / sectors)
        stiffness = scipy.linalg.block_diag([[DISC.stiffness + factor * ring_link]],
                                            matrices.stiffness) + root_link * held.T @ held
        basis = np.eye(4)
        if contacts == "stuck":
            stiffness = stiffness + factor * spring * np.outer(normal, normal)
            if nd:
                basis = scipy.linalg.null_space(tangent[None, :])
        expected = hz(scipy.linalg.eigh(basis.T @ stiffness @ basis,
                                        basis.T @ mass @ basis, eigvals_only=True))
        if 0 < nd < sectors / 2:
            expected = np.repeat(expected, 2)
        np.testing.assert_allclose(modes.of_diameter(nd), expected, rtol=1e-9)
    # the Campbell diagram runs on it too: its crossings are modes of the diameter excited
    campbell = sn.group_campbell(scene, np.linspace(2000.0, 60000.0, 12), engine_orders=(3,),
                                 contacts=contacts, sectors=sectors)
    assert campbell.crossings
    for order, mode, speed, frequency in campbell.crossings:
        at = sn.linear_modes(sn.Scene(group=group, excitation=SILENT, speed_rpm=speed),
                             contacts, sectors=sectors)
        assert at.nodal_diameters[mode] == 3
        assert at.frequencies[mode] == pytest.approx(frequency, rel=1e-8)


# ---- mistuning ----------------------------------------------------------------------------------

def test_a_mistuned_substructure_has_every_frequency_scaled_at_every_speed():
    bodies = nodes()
    bodies["table"] = Substructure.modal(
        [sn.FrequencyTable(speeds_rpm=(0.0, 10000.0), frequencies=(300.0, 360.0)),
         sn.ConstantFrequency(hz=900.0)], 0.01, 0.04, {"tip": [1.0, 0.2]})
    edges = [(("a", "shroud"), ("beam", "shroud"), sn.Interface(
                 gap=-1e-5, normal=LinearSpring(stiffness=1e6), friction=Coulomb(mu=0.3),
                 normal_direction=NORMAL, tangent_direction=TANGENT)),
             (("modal", "tip"), "blade", sn.Coupling(stiffness=4e4)),
             (("table", "tip"), ("a", "root"), sn.Coupling(stiffness=3e4))]
    scene = sn.Scene(group=group_of(bodies, edges), excitation=SILENT, speed_rpm=SPEED)
    factors = {"a": 1.05, "beam": 0.9, "modal": 1.1, "blade": 0.97, "table": 1.0}
    group = mistuned_group(scene, [factors[name] for name in scene.blades])
    for speed in (0.0, SPEED):
        for name, body in bodies.items():
            if isinstance(body, Substructure):
                np.testing.assert_allclose(group.blade(name).frequencies_at(speed),
                                           factors[name] * body.frequencies_at(speed),
                                           rtol=1e-10)
            else:
                assert group.blade(name).stiffness_at(speed) == pytest.approx(
                    factors[name] ** 2 * body.stiffness_at(speed))
    assert group.blade("table") is bodies["table"]  # ε = 0: the node is kept
    assert group.blade("a").points["shroud"] is not None
    assert group.edge_points("interface") == scene.group.edge_points("interface")
    assert group.edge_points("coupling") == scene.group.edge_points("coupling")
    links = [c.stiffness for *_, c in group.couplings]
    assert links == pytest.approx([4e4 * 1.1 * 0.97, 3e4 * 1.05**2])  # one mistuned end
    # the group's open modes without couplings: each node's, scaled
    alone = sn.Scene(group=group_of({n: group.blade(n) for n in ("a", "beam", "modal")},
                                    edges[:1]), excitation=SILENT, speed_rpm=SPEED)
    expected = np.sort(np.concatenate([factors[n] * bodies[n].frequencies_at(SPEED)
                                       for n in ("a", "beam", "modal")]))
    np.testing.assert_allclose(sn.linear_modes(alone).frequencies, expected, rtol=1e-9)


def test_a_study_of_one_dof_substructures_finds_the_blades_amplification():
    """The study's amplitude of a substructure is the largest of its points' components: for
    one-mass blades rebuilt as one-DOF substructures (point "x" = the blade's x), the
    blades' own peaks."""
    blades = stuck_ring()
    pattern = np.array([[0.03, 0.0, -0.02, 0.01]])
    studies = [sn.mistuning_study(scene, spread=0.03, samples=1, speeds_rpm=[2800.0, 3000.0],
                                  patterns=pattern, transient=5, record=3, workers=1,
                                  progress=False)
               for scene in (blades, as_substructures(blades))]
    np.testing.assert_allclose(studies[1].peaks, studies[0].peaks, rtol=1e-6)
    assert studies[1].amplification == pytest.approx(studies[0].amplification, rel=1e-6)
