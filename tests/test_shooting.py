"""Shooting at the scale of FE models: the stroboscopic map, Newton–Krylov and Arnoldi,
the exponential method's tangent, neutral directions, and Newton's fallbacks.

References computed here without the code under test: matrices of a chosen spectrum and
numpy's solvers for GMRES and Arnoldi; the dense monodromy (one run of every tangent
column) for the Jacobian–vector products and the multipliers; the adaptive method at a
tight tolerance for the exponential one; and for neutral directions, the family of
orbits itself (two starts with two slider offsets, each keeping its own).
"""

import dataclasses

import numpy as np
import pytest

import shroudnet as sn
from contact_laws import ConstantLoad, Coulomb
from shroudnet.run.methods import Exponential
from shroudnet.steady import orbits as orbits_module
from shroudnet.steady import stroboscopic as stroboscopic_module
from shroudnet.steady.continuation import Bifurcation, merged
from shroudnet.steady.krylov import arnoldi_step, gmres, leading_eigenvalues
from shroudnet.steady.stroboscopic import StroboscopicMap
from tests.test_structures import modal_pair

#: Orbits compared between solvers: each map as exact as it goes, its switches located
#: to 1e-13 periods, solved to 1e-12 of the scale.
EXACT = sn.Adaptive(rtol=1e-12)
LOCATED = 1e-13
TIGHT = 1e-12


# ---- the Krylov methods on matrices of known spectrum ---------------------------------------

def known_matrix(values, seed=0):
    """A non-normal matrix V diag(values) V⁻¹ (real: ``values`` holds conjugate pairs)."""
    rng = np.random.default_rng(seed)
    n = len(values)
    blocks = np.zeros((n, n))
    k = 0
    while k < n:
        value = values[k]
        if abs(value.imag) > 0.0:
            blocks[k:k + 2, k:k + 2] = [[value.real, value.imag], [-value.imag, value.real]]
            k += 2
        else:
            blocks[k, k] = value.real
            k += 1
    shape = np.eye(n) + 0.3 * rng.standard_normal((n, n))
    return shape @ blocks @ np.linalg.inv(shape)


SPECTRUM = np.array([0.95 + 0.2j, 0.95 - 0.2j, -0.9, 0.8, 0.5 + 0.5j, 0.5 - 0.5j, 0.3, 0.2,
                     0.1, 0.05, 0.02, 0.01, 0.0, 0.0])


def test_arnoldi_finds_the_leading_eigenvalues_of_a_matrix_of_known_spectrum():
    """The four of largest modulus (a complex pair, a real negative and a real positive),
    to 1e-10, from products alone; each found vector is an eigenvector (residual 1e-9)."""
    matrix = known_matrix(SPECTRUM)
    found = leading_eigenvalues(lambda v: matrix @ v, np.ones(len(SPECTRUM)), count=4,
                                tolerance=1e-12)
    expected = SPECTRUM[np.argsort(-np.abs(SPECTRUM), kind="stable")][:4]
    assert len(found.values) == 4
    for value in expected:
        assert np.abs(found.values - value).min() <= 1e-10
    residual = matrix @ found.vectors - found.vectors * found.values
    assert np.abs(residual).max() <= 1e-9


def test_the_arnoldi_step_keeps_the_basis_orthonormal_and_the_relation_exact():
    """A Q_m = Q_{m+1} H̄_m, to rounding, with QᵀQ = I, after 12 steps on a non-normal
    matrix."""
    matrix = known_matrix(SPECTRUM, seed=3)
    n, steps = len(SPECTRUM), 12
    basis = np.zeros((n, steps + 1))
    basis[:, 0] = np.arange(1.0, n + 1.0) / np.linalg.norm(np.arange(1.0, n + 1.0))
    hessenberg = np.zeros((steps + 1, steps))
    for m in range(steps):
        column, _ = arnoldi_step(basis, matrix @ basis[:, m], m)
        hessenberg[:m + 2, m] = column
    assert np.abs(basis.T @ basis - np.eye(steps + 1)).max() <= 1e-13
    assert np.abs(matrix @ basis[:, :steps] - basis @ hessenberg).max() <= 1e-13


def test_gmres_solves_to_its_tolerance_and_a_right_preconditioner_is_undone():
    """x of (A − I) x = b against numpy's solve: to the tolerance asked; with the exact
    inverse as right preconditioner, allowed a single product."""
    shifted = known_matrix(SPECTRUM, seed=5) - np.eye(len(SPECTRUM))
    b = np.linspace(-1.0, 2.0, len(SPECTRUM))
    exact = np.linalg.solve(shifted, b)
    solved = gmres(lambda v: shifted @ v, b, tolerance=1e-11, most=40)
    assert solved.residual <= 1e-11
    assert np.linalg.norm(shifted @ solved.x - b) <= 1.001e-11 * np.linalg.norm(b)
    assert np.abs(solved.x - exact).max() <= 1e-9 * np.abs(exact).max()
    inverse = np.linalg.inv(shifted)
    once = gmres(lambda v: shifted @ v, b, tolerance=1e-12, most=1,
                 preconditioner=lambda v: inverse @ v)
    assert once.residual <= 1e-12
    assert np.abs(once.x - exact).max() <= 1e-12 * np.abs(exact).max()


# ---- the map, and shooting by its products ----------------------------------------------------

def test_the_maps_products_are_columns_of_its_dense_jacobian():
    """On the paper's group at γ1 = 3.5 (stick, slip, impacts): Φ V from a run of two
    columns against the dense Φ times V, to the runs' own error; φ(y) is the state a
    run of ``simulate`` reaches."""
    scene = sn.scenes.three_blade_paper(gamma1=3.5)
    y = sn.periodic_orbit(scene, 3, stability=False).state
    stroboscopic = StroboscopicMap(scene=scene, periods=3)
    vectors = np.random.default_rng(2).standard_normal((6, 2))
    dense = stroboscopic.dense(y).jacobian
    columns = stroboscopic.products(y, vectors).columns
    # Measured: 2.1e-9 of the product's scale (the runs take different steps).
    assert np.abs(columns - dense @ vectors).max() <= 1e-7 * np.abs(dense @ vectors).max()
    run = sn.simulate(scene, 3, samples_per_period=1, initial=np.split(y, 2),
                      method=stroboscopic.state_method,
                      event_tolerance=stroboscopic.state_event_tolerance)
    np.testing.assert_array_equal(stroboscopic(y), np.concatenate([run.x[-1], run.v[-1]]))


def test_products_for_a_loose_solve_are_taken_at_a_looser_tolerance_and_still_columns():
    """A linear solve to a relative residual r takes its products at rtol 1e-3 r, within
    [the map's rtol, 1e-7]; the exponential method has no rtol to loosen. The loose
    products are Φ's columns to their own tolerance, against a dense Φ at rtol 1e-12
    (measured 7.2e-7 of their scale at rtol 1e-8, 8.2e-9 at the map's 1e-10)."""
    scene = sn.scenes.three_blade_paper(gamma1=3.5)
    stroboscopic = StroboscopicMap(scene=scene, periods=3, method=sn.Adaptive(rtol=1e-10))
    assert stroboscopic.for_solve(1e-2).method.rtol == 1e-7  # capped
    assert stroboscopic.for_solve(1e-6).method.rtol == pytest.approx(1e-9)
    assert stroboscopic.for_solve(1e-8) is stroboscopic  # never tighter than the map's
    exponential = StroboscopicMap(scene=modal_pair(), method=Exponential())
    assert exponential.for_solve(1e-3) is exponential
    loose = stroboscopic.for_solve(1e-5)  # rtol 1e-8
    assert loose.work is stroboscopic.work  # counted with the map's runs
    y = sn.periodic_orbit(scene, 3, stability=False).state
    vectors = np.random.default_rng(4).standard_normal((6, 2))
    exact = dataclasses.replace(stroboscopic, method=EXACT, event_tolerance=LOCATED)
    expected = exact.dense(y).jacobian @ vectors
    columns = loose.products(y, vectors).columns
    gap = np.abs(columns - expected).max() / np.abs(expected).max()
    assert gap <= 1e3 * loose.method.rtol, gap


def agreement(dense, other):
    """(state gap over the scale, largest gap of the leading multipliers) of two orbits."""
    gap = np.abs(other.state - dense.state) * orbits_module.state_weights(dense.scene,
                                                                          dense.state)
    found = other.multipliers
    leading = dense.multipliers[:len(found)]
    return gap.max(), max(np.abs(leading - value).min() for value in found)


@pytest.mark.parametrize(("gamma1", "periods"), [(1.0, 1), (3.5, 3), (8.8, 1)],
                         ids=["period 1", "period 3 with stick", "unstable, chaos around"])
def test_krylov_and_dense_shooting_find_one_orbit_and_its_leading_multipliers(gamma1, periods):
    """The paper's group: GMRES on Jacobian–vector products lands on the dense Newton's
    orbit, and Arnoldi on the same products finds the dense monodromy's leading
    multipliers (at γ1 = 8.8 an unstable orbit, |μ| = 1.57)."""
    scene = sn.scenes.three_blade_paper(gamma1=gamma1)
    settings = dict(method=EXACT, event_tolerance=LOCATED, tolerance=TIGHT)
    dense = sn.periodic_orbit(scene, periods, **settings)
    krylov = sn.periodic_orbit(scene, periods, guess=dense.initial, jacobian="krylov",
                               **settings)
    state, multipliers = agreement(dense, krylov)
    assert state <= 1e-10 and multipliers <= 1e-8, (state, multipliers)
    assert krylov.monodromy is None and krylov.work.arnoldi_products > 0
    assert krylov.stable == dense.stable


def test_newton_krylov_converges_from_a_transient_on_an_elastic_pair():
    """Two three-mode blades with 2-D elastic faces (their stretches in the state): from
    the transient's start, Newton–Krylov and dense Newton find one orbit, and Arnoldi the
    dense multipliers."""
    scene = sn.scenes.modal_packet(blades=2, tangential_stiffness=3e4, gap=-1e-6, q1=3.0,
                                   speed_rpm=3100.0, blades_on_disc=8)
    settings = dict(method=EXACT, event_tolerance=LOCATED, tolerance=TIGHT, transient=40)
    dense = sn.periodic_orbit(scene, **settings)
    krylov = sn.periodic_orbit(scene, jacobian="krylov", **settings)
    state, multipliers = agreement(dense, krylov)
    assert state <= 1e-10 and multipliers <= 1e-8, (state, multipliers)
    assert krylov.work.krylov_iterations > 0


@pytest.mark.slow  # compiles the exponential integrator with its tangent flow
def test_the_exponential_methods_orbit_and_multipliers_are_the_adaptive_ones():
    """The preloaded modal pair (impacts, stick, breakaway, slip) and two unreduced beams
    with a shroud contact: the orbit from Newton on the exponential map, its tangent
    e^{JΔt} a phase and the saltations at its switches, against the adaptive map's at
    rtol 1e-12; and its Lyapunov exponents against the adaptive ones."""
    for scene in (modal_pair(), sn.scenes.beam_pair()):
        exponential = sn.periodic_orbit(scene, method=Exponential(), transient=60,
                                        event_tolerance=LOCATED, tolerance=TIGHT)
        # the others from 1e-3 off it: none starts on the orbit it is checked against
        off = tuple(1.001 * part for part in exponential.initial)
        adaptive = sn.periodic_orbit(scene, guess=off, method=EXACT,
                                     event_tolerance=LOCATED, tolerance=TIGHT)
        assert adaptive.iterations > 0
        state, multipliers = agreement(adaptive, exponential)
        assert state <= 1e-10 and multipliers <= 1e-8, (state, multipliers)
        krylov = sn.periodic_orbit(scene, guess=off, method=Exponential(),
                                   event_tolerance=LOCATED, tolerance=TIGHT,
                                   jacobian="krylov")
        state, multipliers = agreement(exponential, krylov)
        assert state <= 1e-10 and multipliers <= 1e-8, (state, multipliers)
    settled = (exponential.initial[0], exponential.initial[1])
    # the fewest periods lyapunov takes: adaptive steps through the beams' stiff modes take
    # 1.6 s a period
    by_phase = sn.lyapunov(scene, 10, transient=0, initial=settled, exponents=3,
                           method=Exponential())
    by_step = sn.lyapunov(scene, 10, transient=0, initial=settled, exponents=3,
                          method=sn.Adaptive(rtol=1e-11))
    np.testing.assert_allclose(by_phase.per_period, by_step.per_period, rtol=1e-7)


@pytest.mark.slow  # the exponential integrator with its tangent flow, as the test above
def test_the_exponential_methods_monodromy_and_branch_are_the_adaptive_ones():
    """The preloaded modal pair: the monodromy carried by phases (each phase's e^{JΔt}
    and the saltations at its switches) against the one integrated by adaptive steps at
    rtol 1e-12, at a settled state; and a branch over the forcing continued on the
    exponential map, each of its orbits the one Newton finds on the adaptive map there."""
    scene = modal_pair()
    settled = sn.simulate(scene, 40, samples_per_period=1)
    start = (settled.x[-1], settled.v[-1])
    by_phase = sn.monodromy(scene, 1, initial=start, method=Exponential(),
                            event_tolerance=LOCATED)
    by_step = sn.monodromy(scene, 1, initial=start, method=EXACT, event_tolerance=LOCATED)
    # Measured: 6.1e-13 of the largest entry.
    assert np.abs(by_phase - by_step).max() <= 1e-9 * np.abs(by_step).max()
    branch = sn.continuation(lambda force: modal_pair(amplitude=force), 20.0, 24.0,
                             method=Exponential(), event_tolerance=LOCATED, tolerance=TIGHT,
                             max_points=6, transient=40)
    assert len(branch) >= 3 and branch.ended == "reached p = 24"
    guesses = [None, *(orbit.initial for orbit in branch.orbits[:-1])]
    for force, orbit, guess in zip(branch.parameter, branch.orbits, guesses):
        # Newton on the adaptive map from the transient, or from the branch's previous
        # orbit: not from the orbit it is checked against. Measured: 2e-16 and 3.6e-12.
        adaptive = sn.periodic_orbit(modal_pair(amplitude=force), guess=guess, transient=40,
                                     method=EXACT, event_tolerance=LOCATED, tolerance=TIGHT)
        assert adaptive.iterations > 0
        state, multipliers = agreement(adaptive, orbit)
        assert state <= 1e-10 and multipliers <= 1e-8, (force, state, multipliers)


# ---- neutral directions: a contact stuck all through -------------------------------------------

def jenkins_chain(speed_rpm, q1=1.0):
    """ground — k1 — m1 — k2 — m2, and m2 pressed (10 N) on the ground by a Jenkins
    element (k_t = 5e4 N/m, μ = 0.3), m1 forced: stuck at small amplitudes, slipping
    near the stuck chain's resonances; its frequency response has no fold."""
    group = sn.BladeGroup()
    group.add_blade("m1", sn.Blade(mass=1.0, damping=2.0, stiffness=1e4))
    group.add_blade("m2", sn.Blade(mass=0.5, damping=1.0, stiffness=0.0,
                                   excitation_scale=0.0))
    group.add_fixed("ground")
    group.connect("m1", "m2", sn.Coupling(stiffness=2e4))
    group.connect("m2", "ground", sn.Interface(
        gap=0.0, angle=0.0, normal=ConstantLoad(force=10.0), friction=Coulomb(mu=0.3),
        tangential_stiffness=5e4))
    return sn.Scene(group=group, speed_rpm=speed_rpm, excitation=sn.Excitation(
        engine_order=1, amplitudes=(0.0, q1), phases=sn.AntiPhase()))


def slider_offset(orbit):
    """w = r_t − u of the chain's contact at the orbit's start (m2's x less the stretch
    along the face)."""
    return orbit.initial[0][1] - orbit.initial[2][0]


def test_a_contact_stuck_all_through_is_neutral_its_offset_pinned_at_the_starts():
    """Stuck all through, the slider's offset is free: two starts whose offsets differ
    give two orbits, each keeping its own (the condition ``neutral`` states), both
    periodic; their multipliers 1 (one per frozen offset: along t₁, and the stretch
    along a second direction the face does not have) are named and left out of
    ``stable``."""
    scene = jenkins_chain(600.0)
    first = sn.periodic_orbit(scene)
    moved = (first.initial[0] + np.array([0.0, 2e-5]), first.initial[1], first.initial[2])
    second = sn.periodic_orbit(scene, guess=moved)
    for orbit in (first, second):
        assert orbit.neutral == (0,) and orbit.neutral_directions == 2
        assert orbit.switches == {} and orbit.residual <= 1e-10
        assert np.abs(orbit.multipliers[:2] - 1.0).max() <= 1e-8
        assert orbit.stable and len(orbit.tested_multipliers) == len(orbit.multipliers) - 2
    assert slider_offset(second) - slider_offset(first) == pytest.approx(2e-5, rel=1e-9)
    assert np.abs(second.state - first.state).max() > 1e-6  # two members of the family


@pytest.mark.slow  # some 60 orbits: 8–11 s
def test_the_chain_continued_from_the_fully_stuck_range_reaches_the_far_end_without_a_fold():
    """From 300 rpm (stuck all through, its offset pinned) over both resonances of the
    stuck chain and the onset of slip (a kink, measured at 1280.3 ± 3.1 rpm) to 1500 rpm:
    the parameter rises at every point, and no fold is reported."""
    branch = sn.continuation(jenkins_chain, 300.0, 1500.0, max_points=300)
    assert branch.ended == "reached p = 1500"
    assert np.all(np.diff(branch.parameter) > 0.0)
    assert not [b for b in branch.bifurcations if b.kind == "fold"]
    assert branch.orbits[0].neutral == (0,) and branch.orbits[-1].neutral == ()
    kinks = [b for b in branch.bifurcations if b.kink]
    assert [b.kind for b in kinks] == ["stick-slip"] and 1270.0 < kinks[0].parameter < 1290.0
    assert branch.orbits[kinks[0].index].neutral == (0,)
    assert branch.orbits[kinks[0].index + 1].neutral == ()


@pytest.mark.slow  # some 100 orbits, 20 s
def test_the_blade_pair_continued_from_the_fully_stuck_range_reaches_the_far_end_without_a_fold():
    """Two blades pressed together by a Jenkins face (k_t = 1e6 N/m), their forcing from
    2 N (stuck all through) to 60 N (slipping twice a cycle): no fold."""
    branch = sn.continuation(
        lambda q1: sn.scenes.blade_pair(tangential_stiffness=1e6, q1=q1), 2.0, 60.0,
        max_points=300)
    assert branch.ended == "reached p = 60"
    assert np.all(np.diff(branch.parameter) > 0.0)
    assert not [b for b in branch.bifurcations if b.kind == "fold"]
    assert branch.orbits[0].neutral == (0,)


# ---- fallbacks --------------------------------------------------------------------------------

def test_a_newton_that_fails_from_a_guess_is_taken_up_from_a_transient_and_says_so(
        monkeypatch):
    """From a guess 30 times the orbit, Newton needs five steps; allowed two, it fails
    there, and the orbit comes from the transient's start, the same orbit, saying so."""
    scene = sn.scenes.three_blade_paper(gamma1=1.0)
    orbit = sn.periodic_orbit(scene)
    monkeypatch.setattr(orbits_module, "NEWTON_ITERATIONS", 2)
    far = np.split(30.0 * orbit.state, 2)
    with pytest.raises(sn.ConvergenceError):
        sn.periodic_orbit(scene, guess=far, transient=0)
    found = sn.periodic_orbit(scene, guess=far)
    assert found.notes and "guess" in found.notes[0] and "transient" in found.notes[0]
    assert np.abs(found.state - orbit.state).max() <= 1e-9 * np.abs(orbit.state).max()


def test_a_newton_at_the_maps_noise_floor_tightens_the_map_once_and_says_so(monkeypatch):
    """A map whose φ carries an error of 3e-10 of the scale (deterministic in y) at its
    default accuracy, and none once tightened: Newton stalls above the tolerance 1e-10,
    tightens once, converges, and says so; where the error stays, it returns the residual
    it reached (within ``NOISE_FLOOR`` times the tolerance), and says that too."""
    scene = sn.scenes.three_blade_paper(gamma1=1.0)
    orbit = sn.periodic_orbit(scene)
    value = StroboscopicMap.value
    scale = orbit.scale

    def noisy(stays):
        def evaluate(self, y):
            found = value(self, y)
            if self.method.rtol < 1e-11 and not stays:
                return found
            noise = 3e-10 * scale * np.sin(1e15 * np.asarray(y) / scale)
            return dataclasses.replace(found, end=found.end + noise)
        return evaluate

    monkeypatch.setattr(StroboscopicMap, "value", noisy(False))
    found = sn.periodic_orbit(scene, guess=orbit.initial)
    assert found.residual <= 1e-10 and "tightened" in found.notes[0]
    monkeypatch.setattr(StroboscopicMap, "value", noisy(True))
    reached = sn.periodic_orbit(scene, guess=orbit.initial)
    assert 1e-10 < reached.residual <= orbits_module.NOISE_FLOOR * 1e-10
    assert "again" in reached.notes[-1]


def test_bifurcations_at_one_parameter_are_one():
    """A fold located a second time (1e-9 of the range on) and a kink at its parameter are
    the first fold; a fold 1e-3 of the range on is another."""
    orbit = sn.periodic_orbit(sn.scenes.three_blade_paper(gap=1.0), transient=2)

    def at(kind, p):
        return Bifurcation(kind, p, orbit, complex(1.0) if kind == "fold"
                           else complex(np.nan), 0, (p, p))

    span = 100.0
    fold = at("fold", 6000.0)
    kept = merged([fold], [at("fold", 6000.0 + 1e-9 * span), at("stick-slip", 6000.0),
                           None], span)
    assert kept == [fold]
    other = at("fold", 6000.0 + 1e-3 * span)
    assert merged(kept, [other], span) == [fold, other]


def test_a_stroboscopic_map_counts_its_runs_by_kind():
    """The breakdown an orbit reports: its dense run of 6 columns, and its outputs."""
    scene = sn.scenes.three_blade_paper(gamma1=1.0)
    orbit = sn.periodic_orbit(scene)
    work = orbit.work
    assert work.jacobian == "dense" and work.columns["dense"] == 6 * work.runs["dense"]
    assert work.runs["outputs"] >= 1 and work.total_seconds > 0.0
    assert stroboscopic_module.KINDS == tuple(work.runs)


def test_the_default_jacobian_is_krylov_only_where_columns_cost_as_runs():
    """By default: Krylov for the six eight-mode blades with elastic faces (106 state
    variables, phases not linear), dense for the same blades with rigid stick (every
    phase linear: a column costs next to nothing) and for the smaller elastic packet (46);
    a jacobian asked for is kept, and one not known is refused by name."""
    from shroudnet.front.bench import ELASTIC_PACKET, fe_packet

    def default(scene):
        return orbits_module.jacobian_kind("periodic_orbit", None, StroboscopicMap(scene=scene))

    assert default(fe_packet()) == "krylov"
    assert default(fe_packet(elastic=False)) == "dense"
    assert default(sn.scenes.modal_packet(**ELASTIC_PACKET)) == "dense"
    assert orbits_module.jacobian_kind("periodic_orbit", "dense",
                                       StroboscopicMap(scene=fe_packet())) == "dense"
    with pytest.raises(ValueError, match="periodic_orbit.jacobian"):
        sn.periodic_orbit(sn.scenes.three_blade_paper(), jacobian="gmres")
