"""Tuned rings and discs at the cost of one sector: the travelling-wave orbit as a fixed
point of the reduced map S⁻ᵏ φ_τ, against the full shooting over T_e (which knows no
symmetry), its monodromy S^{kN/g} A^{N/g} against the full one, the wave numbers of the
multipliers against a linear ring's closed form, and the refusals."""

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shroudnet.linear.modes import nodal_diameters

import shroudnet as sn
import shroudnet.steady.stroboscopic as stroboscopic_module
from contact_laws import LinearSpring
from shroudnet.run.simulate import integrate
from shroudnet.scenes import bladed_disc_24, three_blade_paper
from shroudnet.steady.cyclic import cyclic_symmetry, reduced_step, whole_tangent

PAPER = three_blade_paper()
BLADE = PAPER.group.blade("blade1")
SHROUD = PAPER.group.interfaces[0][2]
#: Both solvers with this map, its switches located to this fraction of a period, and to
#: this residual, so that their orbits may be compared to 1e-10 of the scale.
EXACT = sn.Adaptive(rtol=1e-11)
LOCATED = 1e-13
TIGHT = 1e-12


def ring(n, engine_order, speed_rpm=6000.0, blade=BLADE, shroud=SHROUD, phases=None):
    """The paper's blade and shroud round a ring of ``n``, forced in ``engine_order``."""
    group = sn.BladeGroup.ring(n, blade, shroud)
    return sn.Scene(group=group, excitation=sn.Excitation(
        engine_order=engine_order, amplitudes=(0.0, PAPER.excitation.amplitudes[1]),
        phases=sn.EngineOrderWave() if phases is None else phases), speed_rpm=speed_rpm)


def agreement(scene):
    """(state gap over the scale, largest multiplier gap, the symmetric orbit): the
    symmetric orbit against the full shooting started on it."""
    settings = dict(tolerance=TIGHT, method=EXACT, event_tolerance=LOCATED)
    symmetric = sn.periodic_orbit(scene, symmetry="cyclic", **settings)
    full = sn.periodic_orbit(scene, symmetry="none", guess=symmetric.initial, **settings)
    n = len(full.initial[0])
    gap = np.abs(full.state - symmetric.state)
    state = max(gap[:n].max(), gap[n:].max() / scene.arrays.excitation_frequency)
    # Every sector's extremes, the first one's located on runs shorter than τ (measured:
    # at most 1.4e-9 of the scale; the kinetic energy's peak, where an impact's kink may
    # set it, 1.4e-8 of itself).
    for name in ("maximum", "minimum", "peak"):
        assert np.abs(getattr(full, name) - getattr(symmetric, name)).max() \
            <= 1e-8 * full.scale, name
    assert abs(full.kinetic_peak - symmetric.kinetic_peak) <= 1e-6 * full.kinetic_peak
    return state / full.scale, _multiset_gap(full.multipliers, symmetric.multipliers), symmetric


def _multiset_gap(a, b):
    """The largest distance from a multiplier of either set to the nearest of the other:
    multipliers of equal modulus (the open blades of a ring, a degenerate pair per blade)
    come in no particular order."""
    distances = np.abs(a[:, None] - b[None, :])
    return max(distances.min(axis=0).max(), distances.min(axis=1).max())


@pytest.mark.parametrize("engine_order", [1, 2, 3, 6], ids=[
    "l=1 (τ = T/6)", "l=2 (g = 2)", "l=3 (ND = N/2)", "l=6 (ND = 0)"])
def test_the_symmetric_orbit_is_the_full_shootings_on_a_ring_of_six(engine_order):
    state, multipliers, orbit = agreement(ring(6, engine_order))
    # Measured: states 4.6e-12, 7.3e-13, 0 and 0 of the scale (for ND = N/2 and 0 the
    # symmetric orbit is already a fixed point of the full map to 1e-12), multipliers
    # 7.6e-13, 1.2e-12, 8.4e-13 and 0.
    assert state <= 1e-10
    assert multipliers <= 1e-8
    assert len(orbit.events.time) > 0 or engine_order == 6


@pytest.mark.slow
@pytest.mark.parametrize("engine_order, speed_rpm", [(5, 2000.0), (12, 3000.0)])
def test_the_symmetric_orbit_is_the_full_shootings_on_the_24_sector_disc(engine_order,
                                                                         speed_rpm):
    """Three nodes a sector; l = 5 is coprime with 24 (τ = T_e/24: its shrouds close,
    stick, slip and open), l = 12 the standing wave ND = N/2 (they close and open).
    Measured: states 5.9e-12 and 0, multipliers 3.2e-11 and 5.0e-12."""
    state, multipliers, orbit = agreement(bladed_disc_24(engine_order=engine_order,
                                                         speed_rpm=speed_rpm))
    assert state <= 1e-10
    assert multipliers <= 1e-8
    assert orbit.events.counts["closing"] == 24


@pytest.mark.parametrize("engine_order", [5, 6, 12, 24], ids=[
    "l=5 (τ = T/24)", "l=6 (τ = T/4)", "l=12 (ND = N/2)", "l=24 (ND = 0)"])
def test_the_24_blade_rings_reduced_map_gives_the_full_monodromy(engine_order):
    """24 blades (measured at l = 5: state 1.6e-12, multipliers 1.6e-12; the largest,
    1.156, has ND 2: the wave of ND 5 is unstable to perturbations of another
    diameter)."""
    state, multipliers, orbit = agreement(ring(24, engine_order))
    assert state <= 1e-10
    assert multipliers <= 1e-8
    if engine_order == 5:
        assert not orbit.stable and orbit.wave_numbers[0] == 2


def test_newtons_map_on_the_repeating_states_is_the_whole_rings_restricted_to_them():
    """l = 4 on 12 blades: g = 4, the forcing comes round every N/g = 3 sectors. The map
    z ↦ B⁺ G(B z) Newton solves on, with its 6-column tangent flow, against the whole
    ring's G and its 24-column Jacobian A: B⁺ G(B z) and B⁺ A B."""
    scene = ring(12, 4)
    symmetry = cyclic_symmetry(scene)
    assert (symmetry.share, symmetry.repeating) == (4, 3)
    start = sn.simulate(scene, 30, samples_per_period=1)
    z = symmetry.restricted(np.concatenate([start.x[-1], start.v[-1]]))
    y = symmetry.tiled(z)
    assert np.array_equal(symmetry.restricted(y), z)
    assert np.array_equal(y[:12], np.tile(z[:3], 4))
    settings = dict(method=EXACT, event_tolerance=LOCATED)
    whole = reduced_step(scene, symmetry, np.split(y, 2), **settings)
    repeating = reduced_step(scene, symmetry, np.split(z, 2), repeating=True, **settings)
    assert repeating.jacobian.shape == (6, 6)
    basis = symmetry.tiled(np.eye(6))
    assert np.abs(repeating.end - symmetry.restricted(whole.end)).max() \
        <= 1e-12 * np.abs(whole.end).max()
    # The whole ring's map keeps the repeating states: its end repeats too.
    assert np.abs(symmetry.tiled(symmetry.restricted(whole.end)) - whole.end).max() \
        <= 1e-12 * np.abs(whole.end).max()
    expected = symmetry.restricted(whole.jacobian @ basis)
    assert np.abs(repeating.jacobian - expected).max() <= 1e-9 * np.abs(expected).max()


def test_the_whole_rings_tangent_is_its_first_sectors_columns_moved_round():
    """From a state that repeats every N/g sectors, Φ_τ commutes with that shift: its 24
    columns (12 blades, l = 4) are the first 3 sectors' 6 moved round the ring
    (``whole_tangent``), against a tangent flow that carries all 24."""
    scene = ring(12, 4)
    symmetry = cyclic_symmetry(scene)
    start = sn.simulate(scene, 30, samples_per_period=1)
    y = symmetry.tiled(symmetry.restricted(np.concatenate([start.x[-1], start.v[-1]])))
    run = integrate(scene, 1, method=EXACT, samples_per_period=1, event_tolerance=LOCATED,
                    initial=np.split(y, 2), event_capacity=0, tangent=np.eye(24),
                    until=symmetry.fraction * scene.excitation_period).run
    every = run.tangent.matrix
    assert run.events.counts.sum() > 0  # the shrouds switch on the way
    first = symmetry.restricted(np.arange(24))
    moved = whole_tangent(symmetry, every[:, first])
    # Measured: 2.7e-16 of the largest entry.
    assert np.abs(moved - every).max() <= 1e-12 * np.abs(every).max()


#: Gaps of the property's rings: none, or at least 1 nm either way. An interference
#: within rounding of 0 (hypothesis draws −2e-244 m) leaves an in-phase ring's shrouds
#: touching at a force of 1e-238 N all period, stuck on the edge of breakaway: the full
#: solver's start, 1e-12 of the scale from the symmetric orbit's, breaks them away and
#: follows another sequence of modes, so the two solvers' tangents are of different runs.
GAPS = st.one_of(st.just(0.0), st.floats(1e-9, 5e-6), st.floats(-5e-6, -1e-9))


@settings(max_examples=6)
@given(n=st.integers(3, 6), order=st.integers(1, 12), speed=st.floats(4500.0, 7500.0),
       gap=GAPS)
def test_for_small_tuned_rings_the_symmetric_and_the_full_solver_agree(n, order, speed, gap):
    shroud = sn.Interface(gap=gap, angle=SHROUD.angle, normal=SHROUD.normal,
                          friction=SHROUD.friction)
    state, multipliers, _ = agreement(ring(n, order, speed, shroud=shroud))
    assert state <= 1e-9
    assert multipliers <= 1e-7


def test_the_wave_numbers_are_a_linear_rings_modes():
    """A linear ring (blades coupled by springs, no contact): each multiplier is
    e^{(−c/2m ± iω_p) T} with ω_p² = (k + 2k_c(1 − cos 2πp/N))/m − (c/2m)², its
    eigenvector the travelling waves of diameter p: the multiplier's angle names its
    wave number."""
    n, m, c, k, k_c = 7, 0.1, 2.0, 1e5, 3e4
    group = sn.BladeGroup.ring(n, sn.Blade(mass=m, damping=c, stiffness=k),
                               sn.Coupling(stiffness=k_c))
    scene = sn.Scene(group=group, excitation=sn.Excitation(
        engine_order=2, amplitudes=(0.0, 1.0), phases=sn.EngineOrderWave()),
        speed_rpm=3000.0)
    orbit = sn.periodic_orbit(scene)
    period = scene.excitation_period
    decay = c / (2.0 * m)
    for multiplier, p in zip(orbit.multipliers, orbit.wave_numbers):
        omega = math.sqrt((k + 2.0 * k_c * (1.0 - math.cos(2.0 * math.pi * p / n))) / m
                          - decay ** 2)
        expected = np.exp((-decay + 1j * omega) * period)
        assert min(abs(multiplier - expected), abs(multiplier - expected.conjugate())) \
            <= 1e-8 * abs(expected)


def test_a_tuned_ring_forced_in_engine_order_is_solved_symmetrically_by_default(
        monkeypatch):
    calls = []
    reduced = stroboscopic_module.reduced_step
    monkeypatch.setattr(stroboscopic_module, "reduced_step",
                        lambda *args, **kwargs: calls.append(1) or reduced(*args, **kwargs))
    sn.periodic_orbit(ring(6, 1), transient=20)
    assert calls
    calls.clear()
    sn.periodic_orbit(ring(6, 1), periods=2, transient=20)  # period 2: whole periods
    sn.periodic_orbit(PAPER, transient=20)  # no ring
    assert not calls


def test_what_breaks_the_symmetry_is_named():
    heavier = dataclasses.replace(BLADE, mass=1.01 * BLADE.mass)
    mistuned = sn.BladeGroup.ring(6, [BLADE] * 5 + [heavier], SHROUD)
    scene = sn.Scene(group=mistuned, excitation=ring(6, 1).excitation, speed_rpm=6000.0)
    with pytest.raises(ValueError, match="mistuned: node 4's mass"):
        sn.periodic_orbit(scene, symmetry="cyclic")
    with pytest.raises(ValueError, match="not an engine-order wave of l = 1 on 6 sectors"):
        sn.periodic_orbit(ring(6, 1, phases=sn.AntiPhase()), symmetry="cyclic")
    with pytest.raises(ValueError, match="needs a ring or a disc of sectors"):
        sn.periodic_orbit(PAPER, symmetry="cyclic")
    with pytest.raises(ValueError, match="period-1 orbits"):
        sn.periodic_orbit(ring(6, 1), periods=2, symmetry="cyclic")
    with pytest.raises(ValueError, match="symmetry must be one of 'cyclic', 'none'"):
        sn.periodic_orbit(ring(6, 1), symmetry="yes")
    open_shroud = sn.Interface(gap=1e-3, angle=SHROUD.angle,
                               normal=LinearSpring(stiffness=1e5))
    uneven = sn.BladeGroup.ring(6, BLADE, open_shroud)
    uneven.connect("blade1", "blade3", sn.Coupling(stiffness=10.0))
    with pytest.raises(ValueError, match="coupling 0 between nodes 0 and 2"):
        cyclic_symmetry(sn.Scene(group=uneven, excitation=ring(6, 1).excitation,
                                 speed_rpm=6000.0))


def test_continuation_follows_the_travelling_waves_as_the_full_solver_does():
    """Six blades in engine order 2 over 5000–5400 rpm: the reduced branch meets the
    full branch's period doublings at the same speeds, with the same multipliers."""
    def scene_at(speed_rpm):
        return ring(6, 2, speed_rpm)

    branches = [sn.continuation(scene_at, 5000.0, 5400.0, symmetry=symmetry)
                for symmetry in ("cyclic", "none")]
    found = [[(b.kind, b.parameter, b.multiplier) for b in branch.bifurcations
              if b.kind == "period-doubling"] for branch in branches]
    assert len(found[0]) == len(found[1]) == 2
    for (kind, p, multiplier), (other_kind, q, other) in zip(*found):
        # Measured: the speeds to 1.2e-7 rpm, the multipliers to 1.1e-10.
        assert kind == other_kind and p == pytest.approx(q, abs=1e-3)
        assert abs(multiplier - other) <= 1e-5
    assert branches[0].parameter[-1] == branches[1].parameter[-1] == 5400.0


@pytest.fixture(scope="module")
def breaking():
    """The travelling wave of ND 1 on six blades over 3000–3300 rpm, and its
    symmetry-breaking bifurcations."""
    branch = sn.continuation(lambda speed_rpm: ring(6, 1, speed_rpm), 3000.0, 3300.0,
                             symmetry="cyclic")
    return branch, [b for b in branch.bifurcations if b.kind == "symmetry-breaking"]


def test_a_symmetry_breaking_bifurcation_is_located_with_its_wave_number(breaking):
    """A real multiplier passes +1 along a wave of ND 2, on the branch forced in ND 1,
    and back: between the two, the travelling wave is unstable."""
    branch, found = breaking
    assert [b.wave_number for b in found] == [2, 2]
    for b in found:
        # Measured: |μ − 1| of 1.8e-11 and 6e-13 at 3133.97 and 3169.10 rpm.
        assert abs(b.multiplier - 1.0) <= 1e-6
    between = [orbit for p, orbit in zip(branch.parameter, branch.orbits)
               if found[0].parameter < p < found[1].parameter]
    assert between and not any(orbit.stable for orbit in between)
    assert all(orbit.wave_numbers[0] == 2 for orbit in between)


def test_a_transient_near_the_unstable_wave_leaves_it_for_the_predicted_wave_number(
        breaking):
    """Started 1e-6 off the unstable travelling wave, the motion departs from it by the
    multiplier's factor a period, along the diameter its eigenvector has."""
    branch, found = breaking
    middle = 0.5 * (found[0].parameter + found[1].parameter)
    orbit = branch.orbits[int(np.argmin(np.abs(branch.parameter - middle)))]
    growth = abs(orbit.multipliers[0])
    start = orbit.state * (1.0 + 1e-6 * np.random.default_rng(1).standard_normal(12))
    run = sn.simulate(orbit.scene, 12, samples_per_period=1, initial=np.split(start, 2),
                      method=sn.Adaptive(rtol=1e-11), event_tolerance=1e-13)
    departure = run.x - orbit.initial[0]
    sizes = np.abs(departure).max(axis=1)
    # Measured: 2.0 per period over periods 6–12 against |μ| = 2.008.
    assert (sizes[12] / sizes[6]) ** (1.0 / 6.0) == pytest.approx(growth, rel=0.05)
    assert sizes[12] > 100.0 * sizes[1]
    assert nodal_diameters(departure[12][:, None], 6)[0] == orbit.wave_numbers[0] == 2


def test_from_a_symmetry_breaking_bifurcation_the_broken_branch_is_followed(breaking):
    branch, found = breaking
    broken = sn.continuation(lambda speed_rpm: ring(6, 1, speed_rpm), 3000.0, 3300.0,
                             from_bifurcation=found[0], max_points=6)
    assert len(broken.parameter) == 6
    last = broken.orbits[-1].initial[0]
    # Its blades no longer repeat one another: the orbit is not a travelling wave.
    assert np.ptp(np.sort(np.abs(last))) > 0.1 * np.abs(last).max()
    with pytest.raises(ValueError, match="followed with the full solver"):
        sn.continuation(lambda speed_rpm: ring(6, 1, speed_rpm), 3000.0, 3300.0,
                        from_bifurcation=found[0], symmetry="cyclic")
