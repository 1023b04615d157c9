"""Contacts with a normal and two tangent directions, and elastic stick (a tangential
stiffness k_t): the interface's geometry and its checks, and the group's linear limits
with such contacts stuck, against closed forms assembled here from the user's data."""

import math

import numpy as np
import pytest

import shroudnet as sn
from contact_laws import Coulomb, LinearSpring, Regularised
from shroudnet.io import scenefile
from shroudnet.model.substructure import Substructure

SILENT = sn.Excitation(engine_order=1, amplitudes=(0.0, 0.0), phases=sn.AntiPhase())
SPEED = 3000.0
MASS, GROUND, CONTACT = 0.2, 4e5, 3e5


def face(angle=0.4):
    """A unit normal n and tangents t₁, t₂ of a face tilted by ``angle`` about z, then
    turned about n: an orthonormal frame with no zero component."""
    c, s = math.cos(angle), math.sin(angle)
    normal = np.array([c, s, 0.0])
    first, second = np.array([-s, c, 0.0]), np.array([0.0, 0.0, 1.0])
    turn = 0.3
    t1 = math.cos(turn) * first + math.sin(turn) * second
    t2 = -math.sin(turn) * first + math.cos(turn) * second
    return tuple(normal), tuple(t1), tuple(t2)


def elastic(k_t, *, gap=-1e-5, tangents=None, friction=Coulomb(mu=0.3)):
    normal, t1, t2 = face()
    return sn.Interface(gap=gap, normal=LinearSpring(stiffness=CONTACT), friction=friction,
                        normal_direction=normal, tangent_directions=tangents or (t1, t2),
                        tangential_stiffness=k_t)


def point_mass_on_ground(interface, *, amplitude=0.0):
    """A point mass (3 degrees of freedom, K = k I) pressed onto a fixed node through
    ``interface``, loaded along (1, 1, 1)/√3."""
    body = Substructure(MASS * np.eye(3), GROUND * np.eye(3), 1e-3 * GROUND * np.eye(3),
                        points={"tip": np.eye(3)}, load=np.ones(3) / math.sqrt(3.0))
    group = sn.BladeGroup().add_blade("mass", body).add_fixed("ground")
    group.connect(("mass", "tip"), "ground", interface)
    excitation = sn.Excitation(engine_order=1, amplitudes=(0.0, amplitude),
                               phases=sn.AntiPhase())
    return sn.Scene(group=group, excitation=excitation, speed_rpm=SPEED)


def hz(stiffness, mass):
    return math.sqrt(stiffness / mass) / (2.0 * math.pi)


# ---- the interface ------------------------------------------------------------------------

def test_one_tangent_direction_is_the_tangent_direction_and_copies_keep_the_fields():
    import dataclasses
    one = sn.Interface(gap=0.0, normal=LinearSpring(stiffness=1e6), normal_direction=(0.8, 0.6),
                       tangent_directions=[(-0.6, 0.8)])
    assert one.tangent_direction == (-0.6, 0.8) and one.tangent_directions == ((-0.6, 0.8),)
    assert dataclasses.replace(one, gap=1e-6).tangent_directions == ((-0.6, 0.8),)
    two = elastic(1e5)
    assert two.tangent_direction is None and len(two.tangent_directions) == 2
    assert dataclasses.replace(two, gap=0.0) == dataclasses.replace(two, gap=0.0)
    assert two.elastic and not one.elastic and two.tangential_stiffness == 1e5


@pytest.mark.parametrize("change, message", [
    (dict(tangential_stiffness=0.0), r"tangential_stiffness must be in \(0, inf\) N/m"),
    (dict(tangential_stiffness=-5.0), r"tangential_stiffness must be in \(0, inf\)"),
    (dict(tangential_stiffness=math.nan), "tangential_stiffness must be a number"),
    (dict(tangential_stiffness="stiff"), "tangential_stiffness must be a real number"),
    (dict(friction=None), "tangential_stiffness needs an exact friction law"),
    (dict(friction=Regularised(law=Coulomb(mu=0.3), velocity=1e-3)),
     "needs an exact friction law"),
    (dict(tangential_stiffness=None), "rigid stick in two tangent directions is not "
                                      "supported; give the contact its tangential_stiffness"),
    (dict(tangent_directions=((0.0, 0.0, 1.0), (0.0, 0.0, 1.0))),
     r"tangent_directions must be orthogonal to each other"),
    (dict(tangent_directions=((0.0, 0.0, 1.0), (0.6, 0.8, 0.0))),
     r"tangent_directions\[1\] must be orthogonal to normal_direction"),
    (dict(tangent_directions=((0.0, 0.0, 2.0),)), "must be a unit vector"),
    (dict(tangent_directions=((0.0, 0.0, 1.0),) * 3), "one or two directions, got 3"),
    (dict(tangent_directions=((0.0, 1.0),)), "must have as many components, got 3 and 2"),
    (dict(tangent_directions=7), "tangent_directions must be a sequence"),
    (dict(tangent_direction=(0.0, 0.0, 1.0)), "tangent_direction= or tangent_directions="),
])
def test_bad_geometry_and_stiffness_are_refused_by_name(change, message):
    normal, t1, t2 = face()
    fields = dict(gap=0.0, normal=LinearSpring(stiffness=1e6), friction=Coulomb(mu=0.3),
                  normal_direction=(1.0, 0.0, 0.0), tangent_directions=((0.0, 1.0, 0.0),
                                                                        (0.0, 0.0, 1.0)),
                  tangential_stiffness=1e5)
    fields.update(change)
    with pytest.raises((ValueError, TypeError), match=message):
        sn.Interface(**fields)


def test_a_point_of_fewer_components_than_the_directions_is_refused():
    body = Substructure(MASS * np.eye(2), GROUND * np.eye(2), points={"tip": np.eye(2)})
    group = sn.BladeGroup().add_blade("mass", body).add_fixed("ground")
    with pytest.raises(ValueError, match="has 2 component.*directions have 3"):
        group.connect(("mass", "tip"), "ground", elastic(1e5))


def test_scene_files_carry_the_tangent_plane_and_the_tangential_stiffness(tmp_path):
    scene = point_mass_on_ground(elastic(2.5e5), amplitude=1.0)
    path = scenefile.save(tmp_path / "elastic.toml", scene)
    assert "tangential_stiffness = 250000.0" in path.read_text()
    assert scenefile.load(path).scene.group.interfaces[0][2] == scene.group.interfaces[0][2]
    one = point_mass_on_ground(elastic(None, tangents=(face()[1],)), amplitude=1.0)
    copy = scenefile.load(scenefile.save(tmp_path / "rigid.toml", one)).scene
    assert copy.group.interfaces[0][2] == one.group.interfaces[0][2]
    document = scenefile.document(scene)
    document["interfaces"][0]["tangential_stiffness"] = -1.0
    with pytest.raises(ValueError, match="tangential_stiffness must be in"):
        scenefile.read(document)


# ---- the linear limits ----------------------------------------------------------------------

def test_a_stuck_elastic_contact_is_springs_along_its_normal_and_tangent_plane():
    """K = k I + k_n n nᵀ + k_t (t₁t₁ᵀ + t₂t₂ᵀ): ω² = (k + k_n)/m once and (k + k_t)/m
    twice; open, ω² = k/m three times."""
    k_t = 1.2e6
    scene = point_mass_on_ground(elastic(k_t))
    assert sn.linear_modes(scene, "stuck").frequencies == pytest.approx(
        sorted([hz(GROUND + CONTACT, MASS), hz(GROUND + k_t, MASS), hz(GROUND + k_t, MASS)]),
        rel=1e-12)
    assert sn.linear_modes(scene, "open").frequencies == pytest.approx(
        [hz(GROUND, MASS)] * 3, rel=1e-12)


def test_one_elastic_tangent_direction_leaves_the_other_free():
    normal, t1, _ = face()
    k_t = 7e5
    scene = point_mass_on_ground(elastic(k_t, tangents=(t1,)))
    assert sn.linear_modes(scene, "stuck").frequencies == pytest.approx(
        sorted([hz(GROUND, MASS), hz(GROUND + CONTACT, MASS), hz(GROUND + k_t, MASS)]),
        rel=1e-12)


def test_the_frequency_response_of_a_stuck_elastic_contact_is_its_closed_form():
    """Along each of n, t₁, t₂ the point mass answers F·e / (k_e − ω² m + iω c) with
    k_e = k + k_n, k + k_t, k + k_t and c = 10⁻³ k."""
    k_t = 9e5
    normal, t1, t2 = face()
    scene = point_mass_on_ground(elastic(k_t), amplitude=2.0)
    frequencies = np.array([150.0, 300.0, 410.0])
    found = sn.frequency_response(scene, frequencies, "stuck").displacement("mass", "tip")
    load = 2.0 * np.ones(3) / math.sqrt(3.0)
    omega = 2 * math.pi * frequencies
    expected = np.zeros((len(frequencies), 3), dtype=complex)
    for direction, stiffness in ((normal, GROUND + CONTACT), (t1, GROUND + k_t),
                                 (t2, GROUND + k_t)):
        e = np.asarray(direction)
        scale = (load @ e) / (stiffness - omega ** 2 * MASS + 1j * omega * 1e-3 * GROUND)
        expected += scale[:, None] * e[None, :]
    # The response's phase convention is the library's; the moduli and the relative
    # phases of the components are physical.
    assert np.abs(found) == pytest.approx(np.abs(expected), rel=1e-10)
    ratio = found / expected
    assert np.allclose(ratio, ratio[:, :1], rtol=1e-10)


@pytest.mark.parametrize("angle", [0.3, 1.1])
def test_elastic_stick_of_blades_is_a_spring_k_t_cos2_alpha_that_tends_to_rigid_stick(angle):
    """A blade pair joined by a preloaded contact at angle α: stuck elastic, the edge's
    spring along x is k_n sin²α + k_t cos²α; as k_t grows the frequencies approach those
    of rigid stick (the pair as one body), the lower one as 1/k_t."""
    group = sn.BladeGroup().add_blade("a", sn.Blade(mass=0.1, damping=0.0, stiffness=1e5))
    group.add_blade("b", sn.Blade(mass=0.3, damping=0.0, stiffness=2e5))

    def pair(k_t):
        interface = sn.Interface(gap=-1e-5, angle=angle, normal=LinearSpring(stiffness=CONTACT),
                                 friction=Coulomb(mu=0.3), tangential_stiffness=k_t)
        copy = sn.BladeGroup().add_blade("a", group.blade("a")).add_blade("b",
                                                                            group.blade("b"))
        return sn.Scene(group=copy.connect("a", "b", interface), excitation=SILENT,
                        speed_rpm=SPEED)

    k_t = 4e5
    spring = CONTACT * math.sin(angle) ** 2 + k_t * math.cos(angle) ** 2
    stiffness = np.array([[1e5 + spring, -spring], [-spring, 2e5 + spring]])
    expected = np.sqrt(np.sort(np.linalg.eigvals(np.diag([10.0, 1 / 0.3]) @ stiffness).real))
    assert sn.linear_modes(pair(k_t), "stuck").frequencies == pytest.approx(
        expected / (2 * math.pi), rel=1e-12)
    rigid = sn.linear_modes(pair(None), "stuck").frequencies[0]
    assert rigid == pytest.approx(hz(3e5, 0.4), rel=1e-12)
    gaps = [rigid - sn.linear_modes(pair(k), "stuck").frequencies[0]
            for k in (1e8, 1e9, 1e10)]
    assert all(g > 0.0 for g in gaps)
    rates = np.array(gaps[:-1]) / np.array(gaps[1:])
    assert rates == pytest.approx(10.0, rel=0.05)


def test_the_baselines_refuse_an_elastic_contact_too():
    from shroudnet.references.blades import solve_ivp_baseline
    from shroudnet.references.structures import structure_from_scene, structure_from_substructures
    scene = point_mass_on_ground(elastic(1e5), amplitude=1.0)
    with pytest.raises(ValueError, match="not elastic ones"):
        structure_from_substructures(scene)
    group = sn.BladeGroup().add_blade("a", sn.Blade(mass=0.1, damping=0.0, stiffness=1e5))
    group.add_fixed("g").connect("a", "g", sn.Interface(
        gap=0.0, angle=0.3, normal=LinearSpring(stiffness=1e6), friction=Coulomb(mu=0.3),
        tangential_stiffness=1e5))
    blades = sn.Scene(group=group, excitation=SILENT, speed_rpm=SPEED)
    for refuse in (lambda: solve_ivp_baseline(blades, 1), lambda: structure_from_scene(blades)):
        with pytest.raises(ValueError, match="rigid stick only"):
            refuse()
