"""States in the user's coordinates: every state a run takes or gives (``initial``,
``guess``, ``Simulation.x``, ``PeriodicOrbit.initial`` and ``monodromy``, a branch's
orbits and its file, linear modes and responses) is by the nodes' own degrees of freedom
q, stacked in ``Scene.blades`` order, whatever coordinates the engine integrates in.

The references are written here from the nodes' own matrices (``matrices_at``, the load
vectors and points): the linear forced response in closed form, the exponential of the
first-order system, and the engine's raw record taken to q by the block-diagonal matrix of
its modes. The scenes' modal blades have masses 0.06, 0.05 and 0.04 kg, so that the
engine's coordinates are not their degrees of freedom."""

import json

import numpy as np
import pytest
import scipy.linalg

import shroudnet as sn
from contact_laws import Coulomb, LinearSpring
from shroudnet import scenes
from shroudnet.io.results import (
    ResultsError,
    load_branch,
    load_simulation,
    load_sweep,
    save_branch,
    save_simulation,
)
from shroudnet.model.lowering import to_dofs
from shroudnet.run.simulate import integrate

#: Two modal blades whose shroud contact never closes (a 1 mm gap): a linear scene.
SPEED = 2800.0


def open_pair(speed_rpm: float = SPEED) -> sn.Scene:
    return scenes.modal_packet(blades=2, gap=1e-3, speed_rpm=speed_rpm)


def matrices(scene):
    """M, C, K [SI] of the group by its nodes' own degrees of freedom (block-diagonal: the
    packet has no couplings), and the complex amplitude F of the first harmonic of the
    excitation on them, Q_i = q1 sin(ω t + φ_i) along s_i b_i."""
    bodies = [scene.group.blade(name) for name in scene.blades]
    found = [body.matrices_at(scene.speed_rpm) for body in bodies]
    phases = scene.excitation.blade_phases(len(bodies))
    q1 = scene.excitation.amplitudes[1]
    load = np.concatenate([body.excitation_scale * body.load_vector * q1 * np.exp(1j * phase)
                           for body, phase in zip(bodies, phases)])
    return (*(scipy.linalg.block_diag(*(getattr(m, name) for m in found))
              for name in ("mass", "damping", "stiffness")), load)


def steady_state(scene):
    """(q(0), q̇(0)) of the steady response q(t) = Im(X e^{iωt}),
    X = (K − ω² M + iω C)⁻¹ F, and X."""
    mass, damping, stiffness, load = matrices(scene)
    omega = scene.excitation.engine_order * scene.omega
    response = np.linalg.solve(stiffness - omega**2 * mass + 1j * omega * damping, load)
    return (response.imag, (1j * omega * response).imag), response


def period_map(scene):
    """exp(A T_e) of the first-order system y = (q, q̇), A = [[0, I], [−M⁻¹K, −M⁻¹C]]:
    the monodromy of a linear scene by its degrees of freedom."""
    mass, damping, stiffness, _ = matrices(scene)
    n = len(mass)
    system = np.block([[np.zeros((n, n)), np.eye(n)],
                       [-np.linalg.solve(mass, stiffness), -np.linalg.solve(mass, damping)]])
    return scipy.linalg.expm(system * scene.excitation_period)


def engine_to_dofs(scene):
    """D, block-diagonal: q = D η from the engine's coordinates η, node by node."""
    return scipy.linalg.block_diag(*scene.arrays.layout.bases)


def test_the_engines_coordinates_are_not_the_dofs_here():
    scene = open_pair()
    assert scene.arrays.is_structure and not scene.arrays.layout.identity
    assert np.abs(engine_to_dofs(scene) - np.eye(scene.arrays.n_blades)).max() > 1.0
    np.testing.assert_array_equal(scene.dof_matrix(), np.eye(scene.arrays.n_blades))


def test_a_guess_in_closed_form_is_the_orbit_and_the_orbit_is_given_in_dofs():
    """The closed form's state is the orbit: Newton starts on it, and the orbit's
    ``initial``, its first sample and its monodromy are those of q."""
    scene = open_pair()
    guess, _ = steady_state(scene)
    orbit = sn.periodic_orbit(scene, guess=guess, history=True)
    size = np.abs(guess[0]).max()
    # Measured: 1.5e-16 and 1.8e-16 of the response: Newton has nothing to do.
    assert np.abs(orbit.initial[0] - guess[0]).max() <= 1e-9 * size
    assert np.abs(orbit.initial[1] - guess[1]).max() <= 1e-9 * np.abs(guess[1]).max()
    first = np.concatenate([orbit.history.dofs(name)[0] for name in scene.blades])
    # Measured: 1.5e-16.
    assert np.abs(first - orbit.initial[0]).max() <= 1e-14 * size
    shroud = scene.group.blade("blade1").point("shroud")
    np.testing.assert_allclose(orbit.history.displacement("blade1", "shroud")[0],
                               shroud @ orbit.initial[0][:3], rtol=0, atol=1e-14 * size)
    expected = period_map(scene)
    # Measured: 2.6e-15 of its largest entry.
    assert np.abs(orbit.monodromy - expected).max() <= 1e-8 * np.abs(expected).max()


def test_a_run_from_the_closed_form_stays_on_it():
    scene = open_pair()
    start, response = steady_state(scene)
    sim = sn.simulate(scene, 1, initial=start, samples_per_period=20,
                      method=sn.Adaptive(rtol=1e-10))
    omega = scene.excitation.engine_order * scene.omega
    expected = (response[None, :] * np.exp(1j * omega * sim.t[:, None])).imag
    # Measured: 3.2e-12 of the response.
    assert np.abs(sim.x - expected).max() <= 1e-8 * np.abs(response).max()
    np.testing.assert_array_equal(sim.state(0)[0], sim.x[0])


def test_linear_modes_and_responses_are_by_the_nodes_dofs():
    """Mode shapes mass-normalised with the nodes' own mass matrices, and the open
    frequency response the closed form's X."""
    scene = open_pair()
    mass, _, _, _ = matrices(scene)
    shapes = sn.linear_modes(scene).shapes
    # Measured: 2.2e-16.
    assert np.abs(shapes.T @ mass @ shapes - np.eye(len(mass))).max() <= 1e-12
    _, response = steady_state(scene)
    frequency = scene.excitation.engine_order * scene.speed_rpm / 60.0
    found = sn.frequency_response(scene, [frequency]).response[0]
    # Measured: 2.5e-15.
    assert np.abs(found - response).max() <= 1e-12 * np.abs(response).max()


def test_a_branch_is_by_dofs_and_its_file_keeps_them(tmp_path):
    """Each orbit of a branch over speed is the closed form at its speed, its monodromy
    exp(A T_e) (measured: 5.3e-11, 1.3e-11 and 5.8e-15 at worst); the file round trip
    keeps both exactly."""
    branch = sn.continuation(open_pair, 2700.0, 2900.0, max_points=4)
    path = save_branch(tmp_path / "branch.npz", branch)
    loaded = load_branch(path)
    assert len(loaded) == len(branch) >= 2
    for orbit, again in zip(branch.orbits, loaded.orbits):
        (x0, v0), _ = steady_state(orbit.scene)
        assert np.abs(orbit.initial[0] - x0).max() <= 1e-9 * np.abs(x0).max()
        assert np.abs(orbit.initial[1] - v0).max() <= 1e-9 * np.abs(v0).max()
        expected = period_map(orbit.scene)
        assert np.abs(orbit.monodromy - expected).max() <= 1e-8 * np.abs(expected).max()
        np.testing.assert_array_equal(again.state, orbit.state)
        np.testing.assert_array_equal(again.monodromy, orbit.monodromy)


def settled_by_hand(scene, periods):
    """The state after ``periods`` periods from rest, from the engine's own record taken
    to the nodes' dofs here (q = D η)."""
    out = integrate(scene, periods, samples_per_period=1, event_capacity=0).run.output
    to_q = engine_to_dofs(scene)
    return to_q @ out.x[-1], to_q @ out.v[-1]


@pytest.fixture(scope="module")
def sliding_pair():
    """Two modal blades of a disc of eight, forced out of phase: their preloaded contact
    closes, slips one way and back, and opens every period."""
    return scenes.modal_packet(blades=2, gap=-1e-6, q1=3.0, speed_rpm=3100.0,
                               blades_on_disc=8)


def test_a_settled_state_in_dofs_is_a_guess_newton_finishes(sliding_pair):
    """100 periods from rest settle near the orbit (|μ|max = 0.885): Newton from there
    lands on the orbit, which is given in the coordinates the guess was."""
    scene = sliding_pair
    guess = settled_by_hand(scene, 100)
    orbit = sn.periodic_orbit(scene, guess=guess, history=True)
    assert {(0, "closing"), (0, "reversal"), (0, "separation")} <= set(orbit.switches)
    # Measured: 1.5e-8 of the motion.
    assert np.abs(orbit.initial[0] - guess[0]).max() <= 1e-6 * np.abs(guess[0]).max()
    first = np.concatenate([orbit.history.dofs(name)[0] for name in scene.blades])
    # Measured: 1.8e-16 (rounding, through the engine's coordinates and back).
    assert np.abs(first - orbit.initial[0]).max() <= 1e-14 * np.abs(first).max()


def test_the_monodromy_by_dofs_is_the_derivative_of_runs_by_dofs(sliding_pair):
    """Central differences of ``simulate``'s map y ↦ y(T_e), both ends by dofs, against
    ``monodromy`` at a settled state."""
    scene = sliding_pair
    method = sn.Adaptive(rtol=1e-12)
    start = np.concatenate(settled_by_hand(scene, 100))
    n = scene.arrays.n_blades

    def end(y):
        run = sn.simulate(scene, 1, method=method, samples_per_period=1, event_capacity=0,
                          initial=(y[:n], y[n:]), event_tolerance=1e-13)
        return np.concatenate([run.x[-1], run.v[-1]])

    frequency = scene.arrays.excitation_frequency
    scale = np.concatenate([np.full(n, np.abs(start[:n]).max()),
                            np.full(n, np.abs(start[:n]).max() * frequency)])
    columns = []
    for j in range(2 * n):
        step = np.zeros(2 * n)
        step[j] = 1e-5 * scale[j]
        columns.append((end(start + step) - end(start - step)) / (2 * step[j]))
    differenced = np.column_stack(columns)
    matrix = sn.monodromy(scene, 1, initial=(start[:n], start[n:]), method=method)
    weighted = (matrix - differenced) * scale[None, :] / scale[:, None]
    # Measured: 4.1e-9 of the scaled map's unit (rounding takes over below this step:
    # 4.6e-8 at a tenth of it).
    assert np.abs(weighted).max() <= 1e-6


def test_scenes_of_blades_cross_the_boundary_untouched():
    """One-mass blades' coordinates are their displacements: nothing is converted, not
    even with elastic contacts, whose scenes are lowered as substructures."""
    values = np.arange(6.0).reshape(2, 3)
    blades = scenes.three_blade_paper()
    assert blades.arrays.layout is None and to_dofs(blades.arrays.layout, values) is values
    group = sn.BladeGroup().add_blade("a", sn.Blade(mass=0.1, damping=1.0, stiffness=1e5))
    group.add_fixed("ground").connect("a", "ground", sn.Interface(
        gap=-1e-5, angle=0.4, normal=LinearSpring(stiffness=1e5), friction=Coulomb(mu=0.3),
        tangential_stiffness=1e5))
    elastic = sn.Scene(group=group, excitation=blades.excitation, speed_rpm=6000.0)
    layout = elastic.arrays.layout
    column = np.ones((4, 1))
    assert layout.identity and to_dofs(layout, column) is column


# ---- files written before states were by dofs ------------------------------------------------

def _as_format_one(path):
    """Rewrite a results file's header as format 1, its arrays as they are."""
    with np.load(path) as data:
        arrays = {name: data[name] for name in data.files}
    meta = json.loads(arrays.pop("meta").tobytes())
    meta["format"] = 1
    np.savez(path, meta=np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8), **arrays)


def test_files_of_substructures_in_format_one_are_refused_by_name(tmp_path):
    scene = open_pair()
    run = save_simulation(tmp_path / "run.npz", sn.simulate(scene, 1))
    orbit = sn.periodic_orbit(scene)
    branch = save_branch(tmp_path / "branch.npz", sn.Branch(
        parameter=np.array([SPEED]), orbits=(orbit,), bifurcations=(), periods=1,
        name="speed", ended="test"))
    for path, read, what in ((run, load_simulation, "x and v"),
                             (branch, load_branch, "initial states and monodromy")):
        _as_format_one(path)
        with pytest.raises(ResultsError, match=rf"{path.name}: written in results format 1, "
                                               rf".*{what}.* engine's modal coordinates"):
            read(path)


def test_files_of_blades_in_format_one_read_as_they_are(tmp_path):
    sim = sn.simulate(scenes.three_blade_paper(), 2)
    path = save_simulation(tmp_path / "run.npz", sim)
    _as_format_one(path)
    np.testing.assert_array_equal(load_simulation(path).x, sim.x)


def test_a_sweep_folder_of_format_one_is_read_only_where_it_shows_blades(tmp_path):
    folder = tmp_path / "sweep"
    sn.sweep(lambda q1: scenes.three_blade_paper(q1=q1), [10.0, 20.0], transient=2,
             record=3, workers=1, progress=False, save_to=folder)
    manifest = json.loads((folder / "sweep.json").read_text())
    manifest["format"] = 1
    (folder / "sweep.json").write_text(json.dumps(manifest))
    with pytest.raises(ResultsError, match=r"sweep\.json: written in results format 1, "
                                           r".*nothing in it says whether"):
        load_sweep(folder)
    with pytest.raises(ResultsError, match=r"holds a sweep written in results format 1"):
        sn.sweep(lambda q1: scenes.three_blade_paper(q1=q1), [10.0, 20.0], transient=2,
                 record=3, workers=1, progress=False, save_to=folder)
    manifest["settings"]["scenes"] = {"document": {"blades": [{"mass": 0.1}]}, "path": "q1"}
    (folder / "sweep.json").write_text(json.dumps(manifest))
    assert len(load_sweep(folder).points) == 2
