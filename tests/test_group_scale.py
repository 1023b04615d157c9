"""Groups are built in time linear in their size, keep the numbering and order of their
edges, and refuse bad input at every door of ``BladeGroup`` with a message that names it; a
run too large for the machine's memory is refused with the memory it would need."""

from types import SimpleNamespace

import networkx as nx
import numpy as np
import pytest

from contact_laws import Coulomb, LinearSpring
from shroudnet import Blade, BladeGroup, Coupling, Excitation, Interface, Scene, Substructure
from shroudnet.run import footprint

BLADE = Blade(mass=0.08, damping=4.0, stiffness=1.5e5)
SHROUD = Interface(gap=2e-5, angle=1.0, normal=LinearSpring(stiffness=3e5),
                   friction=Coulomb(mu=0.3))
SPRING = Coupling(stiffness=1e4)


def one_by_one(names, bodies, interface, closed):
    """The group ``chain`` or ``ring`` should build, node by node and edge by edge."""
    group = BladeGroup()
    for name, body in zip(names, bodies):
        group.add_blade(name, body)
    for left, right in zip(names, names[1:] + names[:1] if closed else names[1:]):
        group.connect(left, right, interface)
    return group


def edge_data(group):
    return {frozenset((a, b)): data for a, b, data in group.graph.edges(data=True)}


# ---- scale -----------------------------------------------------------------------------------

def test_a_ring_of_100000_blades_has_every_blade_and_interface_in_order():
    n = 100_000
    group = BladeGroup.ring(n, BLADE, SHROUD)
    assert group.graph.number_of_nodes() == n and group.graph.number_of_edges() == n
    assert group.graph.graph["sectors"] == n
    blades = group.blades
    assert blades[0] == "blade1" and blades[-1] == f"blade{n}" and len(blades) == n
    interfaces = group.interfaces
    assert len(interfaces) == n and not group.couplings
    assert interfaces[0] == ("blade1", "blade2", SHROUD)
    assert interfaces[n - 2] == (f"blade{n - 1}", f"blade{n}", SHROUD)
    assert interfaces[-1] == (f"blade{n}", "blade1", SHROUD)
    closing = group.graph.edges[f"blade{n}", "blade1"]
    assert closing["index"] == n - 1 and closing["left"] == f"blade{n}"
    assert all(group.graph.edges[f"blade{i}", f"blade{i + 1}"]["index"] == i - 1
               for i in range(1, n, 997))
    assert not group.has_substructures
    assert group.edge_points("interface")[:2] == [(None, None), (None, None)]


@pytest.mark.parametrize("closed", [False, True])
def test_chain_and_ring_build_the_graph_connect_builds(closed):
    mistuned = [Blade(mass=0.08, damping=4.0, stiffness=k) for k in (1.4e5, 1.5e5, 1.6e5, 1.5e5)]
    for bodies in ([BLADE] * 4, mistuned):
        names = ["a", "b", "c", "d"]
        preset = (BladeGroup.ring if closed else BladeGroup.chain)(4, bodies, SHROUD, names)
        expected = one_by_one(names, bodies, SHROUD, closed)
        assert list(preset.graph.nodes(data=True)) == list(expected.graph.nodes(data=True))
        assert edge_data(preset) == edge_data(expected)
        assert preset.interfaces == expected.interfaces


def test_a_substructure_row_carries_the_points_connect_gives_it():
    body = Substructure(0.1 * np.eye(2), 1e5 * np.eye(2), points={"tip": [[1.0, 0.0]]})
    preset = BladeGroup.ring(3, [body, BLADE, body], SHROUD)
    expected = one_by_one(["blade1", "blade2", "blade3"], [body, BLADE, body], SHROUD, True)
    assert edge_data(preset) == edge_data(expected)
    assert preset.edge_points("interface") == [("tip", None), (None, "tip"), ("tip", "tip")]


def test_connect_numbers_each_kind_in_its_own_connect_order():
    group = BladeGroup().add_fixed("disc")
    for name in "abc":
        group.add_blade(name, BLADE)
    group.connect("a", "b", SHROUD).connect("disc", "a", SPRING).connect("c", "b", SHROUD)
    group.connect("c", "disc", SPRING).connect("a", "c", SHROUD)
    assert [(left, right) for left, right, _ in group.interfaces] == [("a", "b"), ("c", "b"),
                                                                      ("a", "c")]
    assert [(left, right) for left, right, _ in group.couplings] == [("disc", "a"),
                                                                     ("c", "disc")]
    assert group.graph.edges["b", "c"]["index"] == 1 and group.graph.edges["c", "disc"][
        "index"] == 1


def test_a_graph_built_with_networkx_is_read_and_grown_by_its_own_count():
    graph = nx.Graph()
    graph.add_node("a", blade=BLADE, motion=None)
    graph.add_node("b", blade=BLADE, motion=None)
    graph.add_node("ground", blade=None, motion=None)
    graph.add_edge("a", "b", interface=SHROUD, left="b", index=0)
    graph.add_edge("a", "ground", coupling=SPRING, left="a", index=0)
    group = BladeGroup()
    group.graph = graph
    group.add_blade("c", BLADE).connect("b", "c", SHROUD).connect("c", "ground", SPRING)
    assert group.interfaces == [("b", "a", SHROUD), ("b", "c", SHROUD)]
    assert group.couplings == [("a", "ground", SPRING), ("c", "ground", SPRING)]
    assert group.fixed == ["ground"]


def test_an_edge_slipped_into_the_graph_behind_connect_is_refused_when_read():
    group = BladeGroup.chain(3, BLADE, SHROUD)
    group.add_blade("d", BLADE)
    group.graph.add_edge("blade3", "d", interface=SHROUD, left="blade3", index=2)
    group.connect("d", "blade1", SHROUD)  # counts 2 interfaces: gives index 2 again
    with pytest.raises(ValueError, match=r"share the index 2; each interface needs its own"):
        group.interfaces  # noqa: B018
    group.graph = group.graph.copy()  # an assigned graph is counted afresh
    group.graph.remove_edge("d", "blade1")
    group.connect("d", "blade1", SHROUD)
    assert [left for left, _, _ in group.interfaces] == ["blade1", "blade2", "blade3", "d"]


def test_a_scene_copies_the_group_with_its_numbering():
    group = BladeGroup.ring(5, BLADE, SHROUD)
    scene = Scene(group=group, excitation=Excitation(engine_order=1, amplitudes=(0.0, 1.0),
                                                     phases=[0.0] * 5), speed_rpm=3000.0)
    assert scene.group.interfaces == group.interfaces
    group.add_blade("late", BLADE).connect("blade1", "late", SHROUD)
    assert group.graph.edges["blade1", "late"]["index"] == 5
    assert len(scene.group.interfaces) == 5


# ---- edges a graph must carry ----------------------------------------------------------------

def graph_group(**edge):
    graph = nx.Graph()
    graph.add_node("a", blade=BLADE, motion=None)
    graph.add_node("b", blade=BLADE, motion=None)
    graph.add_node("c", blade=BLADE, motion=None)
    graph.add_edge("a", "b", interface=SHROUD, left="a", index=0)
    graph.add_edge("b", "c", interface=SHROUD, **edge)
    group = BladeGroup()
    group.graph = graph
    return group


@pytest.mark.parametrize("edge, match", [
    ({"left": "b"}, r"interface between 'b' and 'c' needs an edge attribute 'index'.* none"),
    ({"left": "b", "index": "x"}, r"needs an edge attribute 'index'"),
    ({"left": "b", "index": 0}, r"share the index 0; each interface needs its own"),
    ({"index": 1}, r"between 'b' and 'c' needs the edge attribute 'left'.*got none"),
    ({"index": 1, "left": "a"}, r"attribute 'left', one of its two nodes; got 'a'"),
])
def test_an_edge_without_a_usable_index_or_left_is_refused_by_name(edge, match):
    group = graph_group(**edge)
    with pytest.raises(ValueError, match=match):
        group.interfaces  # noqa: B018


def test_a_node_without_a_blade_attribute_is_refused_by_name():
    group = BladeGroup()
    group.graph = nx.Graph([("a", "b")])
    for read in (lambda: group.blades, lambda: group.fixed, lambda: group.blade("a"),
                 lambda: group.connect("a", "b", SHROUD)):
        with pytest.raises(ValueError, match=r"node 'a' has no attribute 'blade'"):
            read()


# ---- bad input at every door -----------------------------------------------------------------

def test_a_missing_node_is_named_with_some_of_those_there():
    group = BladeGroup.ring(1000, BLADE, SHROUD)
    with pytest.raises(ValueError, match=r"^BladeGroup\.blade: no node 'missing' in the group; "
                                         r"its nodes are 'blade1', 'blade2', 'blade3', "
                                         r"'blade4', 'blade5', … \(1,000 in all\)$"):
        group.blade("missing")
    with pytest.raises(ValueError, match=r"unknown node 'ghost'; add it first \(nodes: "
                                         r"'blade1', .* \(1,000 in all\)\)$"):
        group.connect("blade1", "ghost", SHROUD)
    with pytest.raises(ValueError, match=r"its nodes are none yet"):
        BladeGroup().blade("a")
    with pytest.raises(ValueError, match=r"node 'disc' is fixed, not a blade"):
        BladeGroup().add_fixed("disc").blade("disc")


@pytest.mark.parametrize("build, error, match", [
    (lambda: BladeGroup.chain(3, 5, SHROUD), TypeError,
     r"BladeGroup\.chain\.blade must be a Blade, a Substructure or a sequence of n = 3 of "
     r"them, got int 5"),
    (lambda: BladeGroup.chain(3, "abc", SHROUD), TypeError, r"chain\.blade must be .* str"),
    (lambda: BladeGroup.ring(3, [BLADE, BLADE, 3.0], SHROUD), TypeError,
     r"BladeGroup\.ring\.blade\[2\] must be a Blade or a Substructure, got float 3\.0"),
    (lambda: BladeGroup.chain(3, [BLADE, BLADE], SHROUD), ValueError, r"2 blades for n = 3"),
    (lambda: BladeGroup.chain(0, BLADE, SHROUD), ValueError,
     r"BladeGroup\.chain\.n must be an int >= 1, got 0"),
    (lambda: BladeGroup.chain(-4, BLADE, SHROUD), ValueError, r"chain\.n must be an int >= 1"),
    (lambda: BladeGroup.chain(2.0, BLADE, SHROUD), TypeError,
     r"BladeGroup\.chain\.n must be an int, got float 2\.0"),
    (lambda: BladeGroup.chain(True, BLADE, SHROUD), TypeError, r"chain\.n must be an int"),
    (lambda: BladeGroup.chain(1, BLADE, "shroud"), TypeError,
     r"BladeGroup\.chain needs interface to be a shroudnet\.Interface or a "
     r"shroudnet\.Coupling, got str 'shroud'"),
    (lambda: BladeGroup.ring(2, BLADE, SHROUD), ValueError, r"ring needs n >= 3 blades, got 2"),
    (lambda: BladeGroup.ring(None, BLADE, SHROUD), TypeError, r"BladeGroup\.ring\.n must be"),
    (lambda: BladeGroup.ring(3, BLADE, SHROUD, names=7), TypeError,
     r"BladeGroup\.ring\.names must be a sequence of 3 node names, got int 7"),
    (lambda: BladeGroup.ring(3, BLADE, SHROUD, names="abc"), TypeError, r"ring\.names"),
    (lambda: BladeGroup.ring(3, BLADE, SHROUD, names=["a", "b"]), ValueError,
     r"got 2 names for 3 blades"),
    (lambda: BladeGroup.ring(3, BLADE, SHROUD, names=["a", "b", "a"]), ValueError,
     r"BladeGroup\.ring\.names must be distinct, got 'a' more than once"),
    (lambda: BladeGroup.ring(3, BLADE, SHROUD, names=["a", ["b"], "c"]), TypeError,
     r"names\[1\] must be a node's name .* got list \['b'\]"),
    (lambda: BladeGroup.chain(2, BLADE, SHROUD, names=["a", None]), TypeError,
     r"names\[1\] must be a node's name"),
    (lambda: BladeGroup.bladed_disc(2, BLADE, SPRING, [BLADE], [SPRING]), ValueError,
     r"bladed_disc\.sectors must be an int >= 3, got 2"),
    (lambda: BladeGroup.bladed_disc(3, 1.0, SPRING, [BLADE], [SPRING]), TypeError,
     r"bladed_disc\.disc must be a shroudnet\.Blade or Substructure, got float 1\.0"),
    (lambda: BladeGroup.bladed_disc(3, BLADE, 1e4, [BLADE], [SPRING]), TypeError,
     r"bladed_disc needs disc_coupling to be a shroudnet\.Interface or"),
    (lambda: BladeGroup.bladed_disc(3, BLADE, SPRING, 5, [SPRING]), TypeError,
     r"bladed_disc\.blade must be a Blade or Substructure or a sequence of them, got int 5"),
    (lambda: BladeGroup.bladed_disc(3, BLADE, SPRING, [BLADE], [SPRING, 2]), TypeError,
     r"bladed_disc\.blade_couplings\[1\] must be a Coupling or an Interface, got int 2"),
    (lambda: BladeGroup.bladed_disc(3, BLADE, SPRING, [BLADE], [SPRING], shroud=0.1),
     TypeError, r"needs shroud to be None or a shroudnet\.Interface"),
    (lambda: BladeGroup.bladed_disc(3, BLADE, SPRING, [], []), ValueError,
     r"one coupling per blade node"),
    (lambda: BladeGroup().add_blade(["a"], BLADE), TypeError,
     r"add_blade: name must be a node's name \(text, an integer or a tuple of them\), got "
     r"list \['a'\]"),
    (lambda: BladeGroup().add_fixed(None), TypeError, r"add_fixed: name must be a node's"),
    (lambda: BladeGroup().add_blade("a", 3), TypeError, r"needs a shroudnet\.Blade"),
    (lambda: BladeGroup().add_blade("a", BLADE).connect("a", {"b"}, SHROUD), TypeError,
     r"connect\('a', \{'b'\}\): an end must be a node's name"),
    (lambda: BladeGroup().add_blade("a", BLADE).connect(("a", "tip"), "a", SHROUD),
     ValueError, r"node 'a' is a Blade, whose one point is 'x'; got the point 'tip'"),
    (lambda: BladeGroup.chain(2, BLADE, SHROUD).edge_points("interfaces"), ValueError,
     r"edge_points: kind must be 'interface' or 'coupling', got 'interfaces'"),
    (lambda: BladeGroup.chain(2, BLADE, SHROUD).edge_points(0), TypeError,
     r"edge_points: kind must be 'interface' or 'coupling', got int 0"),
    (lambda: BladeGroup.chain(2, BLADE, SHROUD).blade([]), TypeError,
     r"BladeGroup\.blade: name must be a node's name"),
])
def test_bad_input_to_a_group_is_refused_naming_the_argument(build, error, match):
    with pytest.raises(error, match=match):
        build()


def test_numpy_integers_count_blades_as_ints_do():
    for n in (np.int64(5), np.int32(5), np.uint8(5)):
        assert BladeGroup.ring(n, BLADE, SHROUD).graph.graph["sectors"] == 5
        assert len(BladeGroup.chain(n, BLADE, SHROUD).interfaces) == 4
        assert type(BladeGroup.ring(n, BLADE, SHROUD).graph.graph["sectors"]) is int
    disc = BladeGroup.bladed_disc(np.int64(3), BLADE, SPRING, BLADE, SPRING)
    assert disc.graph.graph["sectors"] == 3 and len(disc.couplings) == 6
    assert BladeGroup().add_blade(np.int64(7), BLADE).blade(7) is BLADE


# ---- the memory of a run ---------------------------------------------------------------------

def allocated_bytes(records):
    if isinstance(records, np.ndarray):
        return records.nbytes
    return sum(allocated_bytes(r) for r in records) if isinstance(records, tuple) else 0


@pytest.mark.parametrize("n, columns", [(3, None), (40, None), (40, 4)])
def test_the_footprint_is_what_a_run_allocates_to_one_per_cent(n, columns):
    from shroudnet.engine.generate import kernel_scene
    from shroudnet.engine.records import allocate
    scene = Scene(group=BladeGroup.ring(n, BLADE, SHROUD), speed_rpm=3000.0,
                  excitation=Excitation(engine_order=1, amplitudes=(0.0, 1.0),
                                        phases=[0.0] * n))
    controls = SimpleNamespace(n_samples=1001, event_capacity=5000, zeno_events=50,
                               event_tolerance=1e-10, t0=0.0, sample_step=1e-4)
    tangent = np.zeros((2 * n, columns or 0))
    allocated = allocated_bytes(allocate(kernel_scene(scene), np.zeros(n), np.zeros(n), tangent,
                                         controls, flow=columns is not None))
    estimate = footprint.scene_footprint(scene, 1001, 5000, tangent_columns=columns)
    assert estimate.total == pytest.approx(allocated, rel=0.01)


def test_a_million_blades_are_refused_with_the_memory_they_would_need():
    arrays = SimpleNamespace(n_blades=10**6, n_prescribed=0, n_interfaces=10**6,
                             is_structure=False)
    with pytest.raises(ValueError) as refused:
        footprint.check_footprint(SimpleNamespace(arrays=arrays), 20_001, 10**6,
                                  memory=24 * 2**30)
    message = str(refused.value)
    assert "\n" not in message
    assert message.startswith("a run of 1,000,000 blades and 1,000,000 interfaces over 20,001 "
                              "samples would need 45,319 GiB (44,703 GiB of it the "
                              "stick-cluster matrices, whatever the periods), more than the "
                              "24 GiB of memory this machine has; simulate fewer blades")
    footprint.check_footprint(SimpleNamespace(arrays=arrays), 20_001, 10**6,
                              memory=46_000 * 2**30)


def test_the_counts_alone_refuse_what_a_scene_of_them_would_be_refused():
    """``check_group_size`` needs no scene: what the counts set, the same figures."""
    with pytest.raises(ValueError) as refused:
        footprint.check_group_size(10**6, 10**6, memory=24 * 2**30)
    assert str(refused.value) == (
        "a run of 1,000,000 nodes and 1,000,000 interfaces would need at least 44,704 GiB "
        "(44,703 GiB of it the stick-cluster matrices, whatever the periods), more than the "
        "24 GiB of memory this machine has")
    fixed = footprint.run_footprint(10**6, 10**6, 0, 0).total
    footprint.check_group_size(10**6, 10**6, memory=fixed)
    with pytest.raises(ValueError, match=r"check_group_size\.nodes must be an int >= 0"):
        footprint.check_group_size(-1, 0)


def test_a_small_run_fits_and_the_memory_is_read_as_bytes():
    memory = footprint.machine_memory()
    assert memory is None or (isinstance(memory, int) and memory > 0)
    scene = Scene(group=BladeGroup.ring(4, BLADE, SHROUD), speed_rpm=3000.0,
                  excitation=Excitation(engine_order=1, amplitudes=(0.0, 1.0),
                                        phases=[0.0] * 4))
    footprint.check_footprint(scene, 10_001, 1000)
    with pytest.raises(ValueError, match=r"^a run of 4 blades and 4 interfaces over 10,001 "
                                         r"samples would need 0\.00\d+ GiB"):
        footprint.check_footprint(scene, 10_001, 1000, memory=1000)
    # The record is simulate's own check, against the memory available: not refused here.
    need = footprint.scene_footprint(scene, 10**9, 1000)
    footprint.check_footprint(scene, 10**9, 1000, memory=need.total - need.record)


@pytest.mark.parametrize("arguments, error, match", [
    ((-1, 0, 1, 0), ValueError, r"run_footprint\.nodes must be an int >= 0, got -1"),
    ((1, 2.5, 1, 0), TypeError, r"run_footprint\.interfaces must be an int"),
    ((1, 1, "10", 0), TypeError, r"run_footprint\.samples must be an int"),
])
def test_footprint_arguments_are_checked_by_name(arguments, error, match):
    with pytest.raises(error, match=match):
        footprint.run_footprint(*arguments)
    assert footprint.run_footprint(np.int64(2), np.int32(1), np.uint16(3), 0).total > 0
