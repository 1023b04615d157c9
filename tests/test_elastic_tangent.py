"""The tangent flow of elastic contacts: the Jacobian of their sliders' vector field in
every mode, the monodromy through closing, breakaway, sticking and separation of 2-D
Jenkins elements, runs that take up another's sliders, Lyapunov exponents, and periodic
orbits and branches whose state holds the springs' stretches.

The references are computed here: central differences of the kernel's vector field and
of the trajectories ``simulate`` computes, and the multipliers of a monodromy matrix."""

import numpy as np
import pytest
import scipy.linalg

import shroudnet as sn
from contact_laws import Coulomb, KelvinVoigt
from shroudnet.analysis import stability
from shroudnet.engine.codes import OPEN, SLIP_POSITIVE, STICK
from shroudnet.engine.generate import kernel_scene, load_kernel
from shroudnet.io.results import load_branch, save_branch
from shroudnet.run.simulate import integrate
from tests.test_tangent import EXACT, scaled_error, settled_state, settled_through_every_switch


def pair_on_a_disc():
    """Two three-mode blades of the packet, 2-D elastic faces (k_t = 30 kN/m), forced as
    two of eight blades on a disc: every period the face closes, sticks, breaks away,
    sticks again, breaks away and opens."""
    return sn.scenes.modal_packet(blades=2, tangential_stiffness=3e4, gap=-1e-6, q1=3.0,
                                  speed_rpm=3100.0, blades_on_disc=8)


def first_order_field(kernel, s, t, y, modes, n):
    """(ẋ, ẍ) of the kernel's state y = (x with the stretches, ẋ) in fixed ``modes``, each
    stretch's rate u̇ in its x-row (``derivative`` leaves it in its acceleration slot)."""
    _, acceleration = kernel.linearise_at(t, y[:n].copy(), y[n:].copy(), modes, s,
                                          np.zeros((2 * n, 0)))
    field = np.concatenate([y[n:], acceleration])
    for k in s.slider_index[s.slider_index >= 0]:
        field[k:k + 2] = field[n + k:n + k + 2]
        field[n + k:n + k + 2] = 0.0
    return field


def stroboscopic_state(scene, y):
    """(x, ẋ, u) one period after y = (x, ẋ, u), by ``simulate``."""
    parts = stability.state_parts(scene, y)
    run = sn.simulate(scene, 1, method=EXACT, samples_per_period=1, initial=parts,
                      event_capacity=0, event_tolerance=1e-13)
    return np.concatenate([run.x[-1], run.v[-1], run.stretches[-1]])


def differenced_map(scene, y, scale):
    """∂(map)/∂y of ``stroboscopic_state`` by fourth-order central differences, step
    1e-5·scale_j."""
    columns = []
    for j in range(len(y)):
        step = 1e-5 * scale[j]
        values = {}
        for k in (-2, -1, 1, 2):
            moved = y.copy()
            moved[j] += k * step
            values[k] = stroboscopic_state(scene, moved)
        columns.append((8.0 * (values[1] - values[-1]) - (values[2] - values[-2]))
                       / (12.0 * step))
    return np.array(columns).T


def full_scale(scene, y):
    """Per component of y = (x, ẋ, u): max |x|, max |ẋ|, and max |x| for the stretches."""
    n = scene.arrays.n_blades
    size, speed = np.abs(y[:n]).max(), np.abs(y[n:2 * n]).max()
    return np.concatenate([np.full(n, size), np.full(n, speed), np.full(len(y) - 2 * n, size)])


@pytest.mark.parametrize("mode", [OPEN, STICK, SLIP_POSITIVE])
def test_the_sliders_jacobian_agrees_with_differences_of_their_vector_field(mode):
    """In slip the stretch turns with ṙ_t (û = u/|u| in u̇ = ṙ_t − û λ): the terms
    λ δû and û (δû·u̇) of its variation are the ones a rigid contact does not have."""
    scene = pair_on_a_disc()
    s = kernel_scene(scene)
    kernel = load_kernel(scene, tangent=True)
    n = len(s.mass)
    k = int(s.slider_index[0])
    rng = np.random.default_rng(3)
    y = np.concatenate([rng.normal(size=n) * 1e-6, rng.normal(size=n) * 1e-2])
    y[n + k:n + k + 2] = 0.0  # a stretch has no velocity of its own
    if mode == OPEN:
        y[k:k + 2] = 0.0
    modes = np.array([mode], dtype=np.int64)
    jacobian, _ = kernel.linearise_at(1e-3, y[:n].copy(), y[n:].copy(), modes, s,
                                      np.zeros((2 * n, 0)))
    columns = []
    for j in range(2 * n):
        step = 1e-11 if j < n else 1e-7
        up, down = y.copy(), y.copy()
        up[j] += step
        down[j] -= step
        columns.append((first_order_field(kernel, s, 1e-3, up, modes, n)
                        - first_order_field(kernel, s, 1e-3, down, modes, n)) / (2 * step))
    reference = np.array(columns).T
    keep = np.r_[0:n, n:n + k, n + k + 2:2 * n]  # a stretch's velocity slot is no state
    reference, jacobian = reference[:, keep], jacobian[:, keep]
    row_scale = np.abs(reference).max(axis=1, keepdims=True) + 1.0
    # Measured: 1.6e-11, 3.0e-11 and 3.6e-11 of each row's largest entry (open, stuck, slipping).
    assert (np.abs(jacobian - reference) <= 1e-7 * row_scale).all()
    if mode == OPEN:
        assert not jacobian[k:k + 2].any()


def test_monodromy_through_stick_slip_and_separation_of_2d_elastic_faces():
    """The face is open at t = 0 (its stretch relaxed); the saltations on the way:
    closing (the stretch starts to follow ṙ_t), breakaway (μN − k_t|u| = 0), sticking
    (λ = 0, continuous: the identity) and opening (the stretch reset to 0)."""
    scene = pair_on_a_disc()
    y = np.concatenate([settled_through_every_switch(scene, 20), np.zeros(2)])
    scale = full_scale(scene, y)
    matrix = sn.monodromy(scene, 1, initial=stability.state_parts(scene, y), method=EXACT)
    reference = differenced_map(scene, y, scale)
    # Measured: 1.5e-8 (0.60 with the sliders' rows left out of the tangent).
    assert scaled_error(matrix, reference, scale) <= 1e-6


def test_a_run_takes_up_the_sliders_where_another_left_them():
    """Six periods, or one and then five from its end with its stretches: the contacts
    slipping at the hand-over slip on at the limit (restarted relaxed, the motion moves
    by 8e-4 of its size)."""
    scene = sn.scenes.modal_packet(tangential_stiffness=3e5, speed_rpm=2800.0)
    method = sn.Adaptive(rtol=1e-10)
    whole = integrate(scene, 6, method=method, samples_per_period=1, event_capacity=0)
    first = integrate(scene, 1, method=method, samples_per_period=1, event_capacity=0)
    assert SLIP_POSITIVE in first.run.output.modes[-1]
    end = first.run.output
    rest = integrate(scene, 5, method=method, samples_per_period=1, event_capacity=0,
                     initial=(end.x[-1], end.v[-1], first.stretches[-1]))
    size = np.abs(whole.run.output.x).max()
    # Measured: 6.7e-11 of the motion, 1.1e-10 of the stretches.
    assert np.abs(rest.run.output.x[-1] - whole.run.output.x[-1]).max() <= 1e-8 * size
    assert np.abs(rest.stretches[-1] - whole.stretches[-1]).max() \
        <= 1e-8 * np.abs(whole.stretches).max()


def test_stretches_of_the_wrong_length_or_not_finite_are_refused_by_name():
    scene = sn.scenes.modal_packet(tangential_stiffness=3e5, speed_rpm=2800.0)
    n = scene.arrays.n_blades
    assert scene.arrays.n_stretches == 2 * len(scene.arrays.elastic_interfaces) == 10
    for u0 in (np.zeros(3), np.full(10, np.nan)):
        with pytest.raises(ValueError, match=r"simulate\.initial must be .*u0 must hold the "
                                             r"10 finite stretches \[m\]"):
            sn.simulate(scene, 1, initial=(np.zeros(n), np.zeros(n), u0))


def test_largest_lyapunov_exponent_of_a_stable_elastic_orbit_is_its_largest_multipliers_log():
    """The pair's orbit is stable: λ_max = ln|μ_max| per period (the transient hands its
    sliders on to the measured run)."""
    scene = pair_on_a_disc()
    y = settled_state(scene, 100)
    multipliers = np.linalg.eigvals(sn.monodromy(scene, 1, initial=np.split(y, 2),
                                                 method=EXACT))
    expected = np.log(np.abs(multipliers).max())
    result = sn.lyapunov(scene, 300, transient=100)
    # Measured: −0.131 ± 0.009 against −0.122.
    assert expected < 0.0
    assert result.largest == pytest.approx(expected, abs=max(3 * result.error[0], 0.01))


def test_the_tangent_flow_of_an_elastic_contact_with_a_varying_slope_is_refused_by_name():
    voigt = sn.scenes.modal_packet(blades=2, tangential_stiffness=3e4, blades_on_disc=8,
                                   normal_law=KelvinVoigt(stiffness=1e5, damping=1.0),
                                   friction=Coulomb(mu=0.3))
    with pytest.raises(ValueError, match=r"\('blade1', 'blade2'\).*constant slopes.*"
                                         "KelvinVoigt"):
        sn.monodromy(voigt, 1)


def test_the_elastic_packets_orbit_carries_its_stretches_and_its_monodromy_agrees():
    """Newton on (x, ẋ, u): at t = 0 faces are open, stuck with their springs stretched,
    and slipping on their limit (a start there puts u on the limit, and the tangent with
    it). The monodromy over all three agrees with differences of the map."""
    scene = sn.scenes.modal_packet(tangential_stiffness=3e5, speed_rpm=2800.0)
    orbit = sn.periodic_orbit(scene, method=EXACT)
    n = scene.arrays.n_blades
    y = orbit.state
    assert len(y) == 2 * n + 10 and orbit.residual <= 1e-10 and not orbit.singular
    start = sn.simulate(scene, 1, method=EXACT, samples_per_period=1,
                        initial=orbit.initial).modes[0]
    assert {sn.Mode.OPEN, sn.Mode.STICK, sn.Mode.SLIP_NEGATIVE} <= set(start)
    scale = full_scale(scene, y)
    reference = differenced_map(scene, y, scale)
    # Measured: 4.5e-6, in the column of a slipping face's stretch along its slip: the
    # map has a kink in its second derivative there (inside the limit the face sticks and
    # breaks away, outside its stretch is put on it), which fourth-order differences feel
    # at first order. By the nodes' dofs a step of the displacements' scale is a larger
    # one on the stiff modes' small amplitudes: 5.4e-7 where the same differences step
    # by the engine's coordinates, which a static load moves alike (2.2e-7 at a tenth of
    # that step, where rounding takes over).
    assert scaled_error(orbit.monodromy, reference, scale) <= 1e-5


def test_a_branch_of_elastic_orbits_carries_their_stretches_and_saves_them(tmp_path):
    """Continuation on (x, ẋ, u, p): each orbit of a three-blade packet's branch holds its
    faces' stretches, is the orbit Newton finds alone from it, and loads back whole."""
    def scene_at(rpm):
        return sn.scenes.modal_packet(blades=3, tangential_stiffness=3e5, speed_rpm=rpm)

    branch = sn.continuation(scene_at, 2900.0, 3000.0, max_points=6)
    n = scene_at(2900.0).arrays.n_blades
    # Whether the six points reach 3000 rpm depends on the steps, which rounding moves:
    # what matters is a branch of several orbits that stopped for a reason of its own.
    assert branch.ended.startswith("reached") and len(branch) >= 3
    assert 2900.0 < branch.parameter[-1] <= 3000.0
    last = branch.orbits[-1]
    assert all(len(orbit.state) == 2 * n + 4 for orbit in branch.orbits)
    assert np.abs(last.initial[2]).max() > 0.0  # a face is closed at the start
    alone = sn.periodic_orbit(scene_at(branch.parameter[-1]), guess=last.initial)
    # Measured: 5.9e-10 of the state.
    assert np.abs(alone.state - last.state).max() <= 1e-8 * np.abs(last.state).max()
    path = save_branch(tmp_path / "elastic.npz", branch)
    loaded = load_branch(path)
    assert len(loaded.orbits[-1].initial) == 3
    np.testing.assert_array_equal(loaded.orbits[-1].state, last.state)
    np.testing.assert_array_equal(loaded.orbits[-1].multipliers, last.multipliers)


def test_an_orbits_friction_losses_sum_both_directions_of_each_face_to_the_ledgers_loss():
    """Over an orbit ∮ f·dr_t = ∮ f·dw along t₁ and t₂ together (the spring's ½k_t|u|²
    returns), so the faces' losses add up to the ledger's friction per cycle, to the
    samples' trapezoidal error; t₁ alone holds 4 % less."""
    scene = pair_on_a_disc()
    orbit = sn.periodic_orbit(scene, method=EXACT)
    ledger = orbit.energy_per_cycle.friction
    gaps = [abs(orbit.friction_losses(samples).sum() - ledger) / ledger
            for samples in (100, 400)]
    # Measured: 1.8e-3 and 3.1e-4 of the loss (t₁ alone: 4.2e-2 short at 400).
    assert gaps[1] <= 1e-3 and gaps[0] / gaps[1] > 4.0
    along_first = sn.hysteresis_loop(orbit.simulation(400), 0, 0).area_per_cycle()
    assert ledger - along_first > 0.02 * ledger


def test_classify_runs_its_lyapunov_exponent_from_the_whole_state_it_reads(monkeypatch):
    """Where no period repeats, λ_max is measured from the run's state at ``skip``
    periods, the elastic faces' stretches included: the exponent's run starts where the
    simulation was, not with its sliders relaxed. (At the run's rtol 1e-8 the tangent
    flow of one column collapses its step where a face separates, from either start.)"""
    scene = sn.scenes.modal_packet(blades=3, tangential_stiffness=3e5, speed_rpm=2800.0)
    sim = sn.simulate(scene, 12, method=sn.Adaptive(rtol=1e-10), samples_per_period=20)
    skip, row = 2, 2 * 20
    stretched = sim.stretches[row]
    assert np.abs(stretched).max() > 1e-7  # a face is closed and strained there
    runs = []

    def recorded(*args, **kwargs):
        runs.append(integrate(*args, **kwargs))
        return runs[-1]

    monkeypatch.setattr(stability, "integrate", recorded)
    kind = sn.classify(sim, scene.responses[0], skip)
    assert np.isfinite(kind.lyapunov) and len(runs) == 1
    first, start = runs[0].run.output, runs[0].stretches[0]  # by the engine's coordinates
    to_dofs = scipy.linalg.block_diag(*scene.arrays.layout.bases)  # q = D η, node by node
    size = np.abs(sim.x[row]).max()
    # Measured: 2.3e-17 and 1.6e-16 (rounding, through the coordinates and back).
    assert np.abs(to_dofs @ first.x[0] - sim.x[row]).max() <= 1e-14 * size
    assert np.abs(to_dofs @ first.v[0] - sim.v[row]).max() <= 1e-14 * np.abs(sim.v[row]).max()
    # Measured: 4.8e-9 of the stretches: a face slipping there starts with its stretch put
    # on its friction limit, which the run's state meets to its integration error.
    assert np.abs(start - stretched).max() <= 1e-7 * np.abs(stretched).max()
    with pytest.raises(ValueError, match=r"Simulation\.state\.sample must be an int >= -241 "
                                         r"and <= 240, got 241"):
        sim.state(241)
