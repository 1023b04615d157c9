"""Face points on the builders and sector frames (DESIGN §8): a ring of blades in frames of
their own, each turned by 2πs/N, is the same ring given in the group's frame with every
sector's points and directions turned by hand; the independent reference reads the frames
on its own; identical sectors give identical rows one sector on; sectors declared by hand;
frames and faces through scene files. No run: nothing here compiles a kernel."""

import dataclasses
import math

import numpy as np
import scipy.linalg
import pytest

import shroudnet as sn
from contact_laws import Coulomb, LinearSpring
from shroudnet import scenes
from shroudnet.io import scenefile
from shroudnet.model.group import sector_frame
from shroudnet.references.structures import structure_from_substructures
from shroudnet.steady.cyclic import cyclic_symmetry

POINTS = 4
LEFT, RIGHT = (scenes.face_point_names(side, POINTS) for side in "LR")
BLADE = scenes.faced_blade(face_points=POINTS)
#: A face inclined about the radial axis, in the left blade's frame, one tangent direction:
#: rigid stick (what the reference takes).
FACE = sn.Interface(gap=-1e-6, normal=LinearSpring(stiffness=2e4), friction=Coulomb(mu=0.3),
                    normal_direction=(0.0, math.cos(0.6), math.sin(0.6)),
                    tangent_direction=(0.0, -math.sin(0.6), math.cos(0.6)))
EXCITATION = sn.Excitation(engine_order=2, amplitudes=(0.0, 1.0), phases=sn.EngineOrderWave())


def scene_of(group):
    return sn.Scene(group=group, excitation=EXCITATION, speed_rpm=3000.0)


def turned(body, frame):
    """``body`` (a modal substructure) with its points of three components turned by
    ``frame``: the same blade, given in the group's frame."""
    shapes = {name: frame @ matrix if matrix.shape[0] == 3 else matrix
              for name, matrix in body.points.items()}
    return sn.Substructure(body.mass, None, damping_ratios=body.damping_ratios,
                           points=shapes, load=body.load,
                           modal_frequencies=body.modal_frequencies)


def test_a_ring_built_face_to_face_is_the_ring_connected_by_hand():
    ring = sn.BladeGroup.ring(5, BLADE, FACE, points=(LEFT, RIGHT))
    by_hand = sn.BladeGroup()
    names = [f"blade{s}" for s in range(1, 6)]
    for s, name in enumerate(names):
        by_hand.add_blade(name, BLADE, frame=sector_frame(2.0 * math.pi * s / 5, 3))
    for s, name in enumerate(names):
        by_hand.connect((name, RIGHT), (names[(s + 1) % 5], LEFT), FACE)
    by_hand.declare_sectors(5)
    assert ring.sectors == by_hand.sectors == 5
    assert list(ring.graph.nodes(data=True)) == list(by_hand.graph.nodes(data=True))
    assert list(ring.graph.edges(data=True)) == list(by_hand.graph.edges(data=True))
    assert np.array_equal(ring.frame("blade2"), sector_frame(2.0 * math.pi / 5, 3))
    assert ring.frame("blade1") is not None and np.array_equal(ring.frame("blade1"),
                                                               np.eye(3))
    assert len(scene_of(ring).contacts) == 5 * POINTS


def test_sector_frames_are_the_sectors_turned_into_the_groups_frame():
    """The ring of blades in their own frames against the same ring given in the group's
    frame: each blade's points turned by hand, each interface's directions turned with
    its left blade. The lowered rows agree to rounding."""
    n = 4
    framed = scene_of(sn.BladeGroup.ring(n, BLADE, FACE, points=(LEFT, RIGHT)))
    group = sn.BladeGroup()
    names = [f"blade{s}" for s in range(1, n + 1)]
    for s, name in enumerate(names):
        group.add_blade(name, turned(BLADE, sector_frame(2.0 * math.pi * s / n, 3)))
    for s, name in enumerate(names):
        frame = sector_frame(2.0 * math.pi * s / n, 3)
        face = dataclasses.replace(
            FACE, normal_direction=tuple(frame @ FACE.normal_direction),
            tangent_direction=tuple(frame @ FACE.tangent_direction), tangent_directions=None)
        group.connect((name, RIGHT), (names[(s + 1) % n], LEFT), face)
    plain = scene_of(group)
    for field in ("normal_rows", "tangent_rows", "normal_gap", "structure_stiffness"):
        ours, theirs = getattr(framed.arrays, field), getattr(plain.arrays, field)
        # Measured: 8.5e-18 of the largest entry.
        assert np.abs(ours - theirs).max() <= 1e-14 * np.abs(theirs).max(), field
    # the readings stay in each blade's own frame
    local = framed.point_rows("blade3", "R0")[:, 8:12]
    assert np.allclose(local, framed.point_rows("blade1", "R0")[:, 0:4], rtol=0, atol=1e-15)


def test_the_reference_reads_the_frames_on_its_own():
    """The reference (``references.structures``) turns each blade's points and each
    interface's directions into the group's frame over the physical degrees of freedom;
    the lowering takes each difference in its left blade's frame over modal coordinates:
    the two contacts' rows meet through q = Φ η, node by node."""
    scene = scene_of(sn.BladeGroup.ring(3, BLADE, FACE, points=(LEFT, RIGHT)))
    problem = structure_from_substructures(scene)
    dofs = scene.dof_matrix() @ scipy.linalg.block_diag(*scene.arrays.layout.bases)
    n = scene.arrays.n_blades
    for c, contact in enumerate(problem.contacts):
        for theirs, ours in ((contact.normal_row, scene.arrays.normal_rows[c, :n]),
                             (contact.tangent_row, scene.arrays.tangent_rows[c, :n])):
            # Measured: 1.2e-16 of the largest entry.
            assert np.abs(theirs @ dofs - ours).max() <= 1e-14 * np.abs(ours).max()


def test_identical_sectors_give_identical_rows_one_sector_on():
    scene = scene_of(sn.BladeGroup.ring(6, BLADE, FACE, points=(LEFT, RIGHT)))
    a = scene.arrays
    per_sector = a.n_blades // 6
    image = (np.arange(a.n_blades) + per_sector) % a.n_blades
    for c in range(a.n_interfaces):
        twin = (c + POINTS) % a.n_interfaces
        for rows in (a.normal_rows, a.tangent_rows):
            # Measured: 3.4e-16 of the largest entry (the frames round apart).
            assert np.abs(rows[twin, image] - rows[c]).max() <= 1e-15 * np.abs(rows[c]).max()
    symmetry = cyclic_symmetry(scene)
    assert (symmetry.sectors, symmetry.per_sector) == (6, 4)


def test_a_chain_on_a_disc_turns_its_blades_and_a_disc_its_sectors():
    chain = sn.BladeGroup.chain(3, BLADE, FACE, points=(LEFT, RIGHT), blades_on_disc=36)
    assert np.allclose(chain.frame("blade3"), sector_frame(2.0 * 2.0 * math.pi / 36, 3))
    assert chain.sectors is None
    assert sn.BladeGroup.chain(3, BLADE, FACE, points=(LEFT, RIGHT)).frame("blade3") is None
    tips = sn.BladeGroup.bladed_disc(
        4, sn.Blade(mass=0.5, damping=1.0, stiffness=1e6), sn.Coupling(stiffness=1e5),
        [sn.Blade(mass=0.05, damping=0.1, stiffness=0.0)], [sn.Coupling(stiffness=2e5)])
    assert tips.sectors == 4


def test_a_bladed_disc_meets_its_tips_face_to_face_in_sector_frames():
    hub = sn.Substructure(np.eye(3) * 0.2, np.eye(3) * 1e6, points={"x": np.eye(3)})
    rooted = sn.Substructure(BLADE.mass, None, damping_ratios=BLADE.damping_ratios,
                             points=dict(BLADE.points) | {"root": np.eye(3, 4) * 0.1},
                             load="load", modal_frequencies=BLADE.modal_frequencies)
    disc = sn.BladeGroup.bladed_disc(
        4, hub, sn.Coupling(stiffness=1e5), [rooted], [sn.Coupling(stiffness=1e5)], FACE,
        points=(LEFT, RIGHT))
    assert disc.edge_points("coupling")[0] == ("x", "root")
    assert disc.sectors == 4
    assert np.allclose(disc.frame("disc2"), sector_frame(math.pi / 2, 3))
    assert np.allclose(disc.frame("blade2_1"), sector_frame(math.pi / 2, 3))
    assert disc.edge_points("interface")[0] == (tuple(RIGHT), tuple(LEFT))


def test_sectors_are_declared_by_hand_and_checked():
    group = sn.BladeGroup()
    for s in range(3):
        group.add_blade(f"b{s}", BLADE, frame=sector_frame(2.0 * math.pi * s / 3, 3))
    for s in range(3):
        group.connect((f"b{s}", RIGHT), (f"b{(s + 1) % 3}", LEFT), FACE)
    with pytest.raises(ValueError, match=r"needs a ring or a disc of sectors"):
        cyclic_symmetry(scene_of(group))
    assert group.declare_sectors(3) is group and group.sectors == 3
    assert cyclic_symmetry(scene_of(group)).per_sector == 4
    with pytest.raises(ValueError, match=r"2 sectors must share the group's 3 moving nodes"):
        group.declare_sectors(2)
    with pytest.raises(ValueError, match=r"must be an int >= 1"):
        group.declare_sectors(0)
    wrong = sn.BladeGroup()
    for s in range(3):  # one blade left in the group's frame: not tuned
        wrong.add_blade(f"b{s}", BLADE, frame=None if s == 1 else sector_frame(
            2.0 * math.pi * s / 3, 3))
    for s in range(3):
        wrong.connect((f"b{s}", RIGHT), (f"b{(s + 1) % 3}", LEFT), FACE)
    wrong.declare_sectors(3)
    with pytest.raises(ValueError, match=r"the ring is not tuned: contact \d+ differs"):
        cyclic_symmetry(scene_of(wrong))


@pytest.mark.parametrize("frame, blade, message", [
    (np.eye(3) * 2.0, BLADE, r"frame must be a rotation"),
    (np.diag([1.0, 1.0, -1.0]), BLADE, r"frame must be a rotation"),
    (np.eye(4), BLADE, r"frame must be a 2 × 2 or 3 × 3 rotation"),
    (np.eye(2), BLADE, r"a frame of 2 × 2 turns points of 2 components .* points of 3"),
    (np.eye(3), sn.Blade(mass=1.0, damping=0.0, stiffness=1.0), r"a Blade's one point"),
    ([[1.0, float("nan")], [0.0, 1.0]], BLADE, r"frame must be finite|frame .*NaN"),
])
def test_a_frame_that_is_no_rotation_of_the_points_is_refused_by_name(frame, blade, message):
    with pytest.raises(ValueError, match=message):
        sn.BladeGroup().add_blade("a", blade, frame=frame)


def test_builders_refuse_faces_that_are_not_points_by_name():
    with pytest.raises(TypeError, match=r"BladeGroup.ring.points must be \(left face, right "
                                        r"face\)"):
        sn.BladeGroup.ring(3, BLADE, FACE, points="L0")
    with pytest.raises(ValueError, match=r"has no point 'nowhere'"):
        sn.BladeGroup.ring(3, BLADE, FACE, points=("nowhere", "R0"))
    with pytest.raises(ValueError, match=r"both ends name as many points"):
        sn.BladeGroup.ring(3, BLADE, FACE, points=(LEFT, RIGHT[:2]))
    with pytest.raises(ValueError, match=r"BladeGroup.chain.blades_on_disc must be an int "
                                         r">= 3"):
        sn.BladeGroup.chain(3, BLADE, FACE, points=(LEFT, RIGHT), blades_on_disc=2)


def test_scene_files_carry_frames_faces_and_declared_sectors(tmp_path):
    scene = scene_of(sn.BladeGroup.ring(3, BLADE, FACE, points=(LEFT, RIGHT)))
    path = scenefile.save(tmp_path / "ring.toml", scene)
    again = scenefile.load(path).scene
    assert again.group.sectors == 3
    for name in scene.blades:
        assert np.array_equal(again.group.frame(name), scene.group.frame(name))
    for field in ("normal_rows", "tangent_rows", "structure_stiffness"):
        assert np.array_equal(getattr(again.arrays, field), getattr(scene.arrays, field))
    document = scenefile.document(scene)
    shorthand = {"speed_rpm": 3000.0, "excitation": document["excitation"],
                 "group": {"shape": "ring", "count": 3, "blade": document["blades"][0]
                           | {"name": None}, "interface": document["interfaces"][0]
                           | {"left": None}, "points": [LEFT, RIGHT]}}
    del shorthand["group"]["blade"]["name"], shorthand["group"]["blade"]["frame"]
    del shorthand["group"]["interface"]["left"], shorthand["group"]["interface"]["right"]
    built = scenefile.read(shorthand).scene
    for field in ("normal_rows", "tangent_rows"):
        assert np.array_equal(getattr(built.arrays, field), getattr(scene.arrays, field))
    with pytest.raises(scenefile.SceneFileError, match=r"group.blades_on_disc: turns the "
                                                       r"blades of a chain"):
        scenefile.read(shorthand | {"group": shorthand["group"] | {"blades_on_disc": 36}})
