"""Bad input is refused before any work, with a message that names the argument (or the
file) and what is allowed: the cases that once let an internal exception out, passed
silently or hung, grouped by the door they come through."""

from __future__ import annotations

import functools
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

import contact_laws as cl
from shroudnet import (
    Adaptive,
    AntiPhase,
    Bifurcation,
    Blade,
    BladeGroup,
    Branch,
    EnergyLedger,
    EngineOrderWave,
    EventKind,
    EventLog,
    Excitation,
    Exponential,
    FixedStep,
    Interface,
    Scene,
    Simulation,
    SimulationError,
    Substructure,
    TravellingWave,
    classify_section,
    continuation,
    modal_truncation,
    read_matrices,
    simulate,
    zero_one_test,
)
from shroudnet.engine.codes import Status
from shroudnet.front.cli import main
from shroudnet.io import results, scenefile
from shroudnet.model import matrix_files
from shroudnet.run import scales
from shroudnet.run.methods import MOST_STEPS_PER_PERIOD, transient_for
from shroudnet.scenes import blade_pair, bladed_disc_24, modal_packet, three_blade_paper
from shroudnet.steady.continuation import _check_born_here
from shroudnet.steady.parametric import same_scene

from .test_file_validation import orbit


@functools.cache
def paper_run():
    """Two periods of the paper's group (its kernel is the one most tests compile)."""
    return simulate(three_blade_paper(), 2, samples_per_period=10)


# ---- the writers of files ------------------------------------------------------------------

WRITERS = {
    "document of a string": (lambda path: scenefile.document("scene"), TypeError,
                             r"scenefile\.document\.scene must be a shroudnet\.Scene, got "
                             r"str 'scene'"),
    "scene file with run settings of a string": (
        lambda path: scenefile.save(path, three_blade_paper(), run="fast"), TypeError,
        r"scenefile\.save\.run must be scenefile\.RunSettings\(\.\.\.\) or None, got str "
        r"'fast'"),
    "simulation of a string": (
        lambda path: results.save_simulation(path, "not a sim"), TypeError,
        r"results\.save_simulation\.sim must be a shroudnet\.Simulation \(what simulate "
        r"returns\), got str 'not a sim'"),
    "simulation with run settings of a string": (
        lambda path: results.save_simulation(path, paper_run(), run="fast"), TypeError,
        r"results\.save_simulation\.run must be scenefile\.RunSettings\(\.\.\.\) or None"),
    "branch of a string": (
        lambda path: results.save_branch(path, "x"), TypeError,
        r"results\.save_branch\.branch must be a shroudnet\.Branch \(what continuation "
        r"returns\), got str 'x'"),
}


@pytest.mark.parametrize("case", WRITERS)
def test_a_writer_refuses_what_is_not_its_own_by_name_and_writes_nothing(tmp_path, case):
    write, error, message = WRITERS[case]
    with pytest.raises(error, match=message):
        write(tmp_path / "file")
    assert list(tmp_path.iterdir()) == []


def test_a_scene_file_saves_what_loading_it_returned(tmp_path):
    """``save(path, load(file))`` writes the same scene, and the [run] table where the file
    had one."""
    with_run = scenefile.save(tmp_path / "with_run.toml", three_blade_paper(),
                              scenefile.RunSettings(periods=12, transient=4))
    without = scenefile.save(tmp_path / "without.toml", three_blade_paper(speed_rpm=5000.0))
    for path in (with_run, without):
        loaded = scenefile.load(path)
        again = scenefile.load(scenefile.save(tmp_path / f"again_{path.name}", loaded))
        assert again.document == loaded.document and again.run == loaded.run
        assert scenefile.save(loaded, tmp_path / "swapped.toml").read_text() \
            == (tmp_path / f"again_{path.name}").read_text()
    assert "[run]" in (tmp_path / "again_with_run.toml").read_text()
    assert "[run]" not in (tmp_path / "again_without.toml").read_text()


# ---- the methods ---------------------------------------------------------------------------

@pytest.mark.parametrize("method", [FixedStep, Exponential])
def test_a_method_on_a_grid_takes_at_most_a_million_steps_a_period(method):
    """10¹² steps a period would take some 220 days for one: refused as the method is
    made, before any run, and so is a scene file's [run] asking for them."""
    assert method(steps_per_period=MOST_STEPS_PER_PERIOD).steps_per_period == 10**6
    for steps in (MOST_STEPS_PER_PERIOD + 1, 10**12):
        with pytest.raises(ValueError, match=rf"^{method.__name__}\.steps_per_period must be "
                                             rf"an int >= 8 and <= 1000000, got {steps}$"):
            method(steps_per_period=steps)
    document = scenefile.document(three_blade_paper())
    document["run"] = {"method": {FixedStep: "fixed", Exponential: "exponential"}[method],
                       "steps_per_period": 10**12}
    with pytest.raises(scenefile.SceneFileError, match=r"run: .*steps_per_period must be an "
                                                       r"int >= 8 and <= 1000000"):
        scenefile.read(document)


# ---- scales a run cannot carry -------------------------------------------------------------

def chain(speed_rpm: float, **interface) -> Scene:
    """Three blades of constant stiffness in a row, their interfaces as given."""
    shroud = dict(gap=1e-5, angle=0.5, normal=cl.LinearSpring(stiffness=1e6),
                  friction=cl.Coulomb(mu=0.3)) | interface
    return Scene(group=BladeGroup.chain(3, Blade(mass=0.1, damping=1.0, stiffness=1e5),
                                        Interface(**shroud)),
                 excitation=Excitation(engine_order=1, amplitudes=(0.0, 1.0),
                                       phases=AntiPhase()), speed_rpm=speed_rpm)


def at_rest(scene: Scene) -> tuple[np.ndarray, np.ndarray]:
    n = scene.arrays.n_blades
    return np.zeros(n), np.zeros(n)


def test_a_speed_whose_period_has_no_step_a_float_can_tell_is_refused_by_name():
    """At 1e300 rpm the period is 6e-299 s, its smallest step 6e-313 s, a subnormal float
    (the scales check itself overflowed there, on ω_e²); at 1e200 rpm ω_e² overflows but
    the steps are normal floats: the check passes without an OverflowError."""
    with pytest.raises(SimulationError, match=r"^the run cannot start \(t = 0 s\): Scene\."
                                              r"speed_rpm = 1e\+300 rpm makes an excitation "
                                              r"period T_e = 6e-299 s .* smallest step, "
                                              r"1e-14 T_e = 6e-313 s, is below the smallest "
                                              r"normal float"):
        simulate(chain(1e300), 1)
    scene = chain(1e200)
    assert scales.check_scales(scene, 1, Adaptive(), at_rest(scene)) is None


@pytest.mark.parametrize("make, message", [
    (lambda: three_blade_paper(speed_rpm=1e300),
     r"Blade\.stiffness_at: k\(Ω\) = m \(2π f_d1\(Ω\)\)² overflows a float at speed_rpm = "
     r"1e\+300 \(Southwell"),
    (lambda: modal_packet(speed_rpm=1e300),
     r"Substructure\.matrices_at: K\(Ω\) = m ω\(Ω\)² of its modes overflows a float at "
     r"speed_rpm = 1e\+300"),
    (lambda: Substructure(np.eye(2), np.diag([1e4, 2e4]), stiffness_speed=np.eye(2),
                          damping_ratios=0.01, points={"p": [[1.0, 0.0]]}).matrices_at(1e300),
     r"Substructure\.matrices_at: K\(Ω\) = K₀ \+ Ω² K₁ overflows a float at speed_rpm = "
     r"1e\+300"),
])
def test_a_stiffness_that_overflows_at_the_speed_is_refused_naming_the_speed(make, message):
    with pytest.raises(ValueError, match=message):
        make()


@pytest.mark.parametrize("method", [Adaptive(), FixedStep(steps_per_period=1000)],
                         ids=["Adaptive", "FixedStep"])
@pytest.mark.parametrize("interface, what", [
    (dict(tangential_stiffness=1e300), r"its tangential_stiffness, 1e\+300 N/m"),
    (dict(normal=cl.LinearSpring(stiffness=1e300)),
     r"its normal law's stiffness ∂N/∂δ \(LinearSpring\), 1e\+300 N/m"),
])
def test_a_contact_no_step_can_follow_is_refused_by_name_whatever_the_method(
        method, interface, what):
    """Its natural frequency on the masses it joins is ω² = k gᵀ M⁻¹ g, g its row:
    (cos α, −cos α) on two blades of 0.1 kg for the tangent, (sin α, −sin α) for the
    normal. Before, the run started and stopped at once, blaming a law or the fixed step
    (the run was adaptive)."""
    row = math.cos(0.5) if "tangential_stiffness" in interface else math.sin(0.5)
    omega = math.sqrt(1e300 * row**2 * 2 / 0.1)
    with pytest.raises(SimulationError) as caught:
        simulate(chain(3000.0, **interface), 1, method=method)
    text = str(caught.value)
    assert re.search(rf"interface 0 \('blade1', 'blade2'\): {what}, on the masses it joins "
                     rf"makes a natural frequency of up to {re.escape(f'{omega:.3g}')} rad/s",
                     text), text
    assert "fixed step" not in text and "law returned" not in text


def test_a_stiff_contact_that_steps_can_follow_passes_the_check():
    """k_t = 1e12 N/m on 0.1 kg: ω ≈ 4.2e6 rad/s, a stable step of 7e-7 s against a
    smallest step of 2e-16 s."""
    scene = chain(3000.0, tangential_stiffness=1e12)
    assert scales.check_scales(scene, 1, Adaptive(), at_rest(scene)) is None


def test_a_non_finite_state_blames_the_fixed_step_only_in_a_run_on_a_fixed_grid():
    def text(fixed_step):
        return Status.NOT_FINITE.message("at t = 0 s", "", fixed_step=fixed_step)
    assert "the fixed step is too large" in text(True)
    assert "fixed step" not in text(False) and "law returned inf or NaN, or the scene" \
        in text(False)


# ---- finite-element files ------------------------------------------------------------------

@pytest.mark.parametrize("name, content, message", [
    ("empty.mat", b"", r"'empty\.mat' is empty \(0 bytes\): .*empty\.mat holds no matrices"),
    ("empty.npz", b"", r"'empty\.npz' is empty \(0 bytes\): .*empty\.npz holds no matrices"),
    ("text.mat", b"M = [1 0; 0 1]\n" * 20, r"'text\.mat' is not a readable \.mat file"),
    ("text.npz", b"M = [1 0; 0 1]\n" * 20,
     r"'text\.npz' is not a \.npz archive \(numpy\.savez writes a zip archive of arrays\): "
     r".*text\.npz holds something else"),
])
def test_a_matrix_file_that_holds_no_matrices_is_refused_naming_it(tmp_path, name, content,
                                                                  message):
    """Before: MatReadError, EOFError and "contains pickled (object) data", the first two
    without the file's name."""
    (tmp_path / name).write_bytes(content)
    with pytest.raises(ValueError, match=message):
        read_matrices(tmp_path / name)


#: Triplets of a 2 × 2 stiffness beside a dense 2 × 2 mass, one array replaced.
TRIPLETS = dict(K_rows=np.array([0, 1, 1]), K_cols=np.array([0, 0, 1]),
                K_values=np.array([2.0, -1.0, 3.0]), K_shape=np.array([2, 2]))


@pytest.mark.parametrize("replaced, message", [
    (dict(K_rows=np.array([0, 5, 1])), r"K_rows must lie in \[0, 1\], got 5"),
    (dict(K_cols=np.array([0, -1, 1])), r"K_cols must lie in \[0, 1\], got -1"),
    (dict(K_rows=np.array([0.5, 1.0, 1.0])),
     r"K_rows must hold whole numbers \(0-based indices\), got 0\.5 at position 0"),
    (dict(K_shape=np.array([-2, 2])), r"K_shape must lie in \[1, inf\), got -2"),
    (dict(K_shape=np.array([2.5, 2])), r"K_shape must hold whole numbers \(sizes\), got 2\.5"),
    (dict(K_shape=np.array([2, 2, 2])), r"K_shape must hold two sizes \(rows, columns\)"),
    (dict(K_shape=np.array([10**12, 10**12])),
     r"K_shape = \[1000000000000, 1000000000000\]: a sparse matrix of 1,000,000,000,000 "
     r"rows needs 7,451 GiB for its row index alone, more than the 16 GiB"),
    (dict(K_values=np.array([2.0, -1.0])), r"K_values must hold one entry per row index of "
                                           r"K_rows \(3\), got 2"),
])
def test_sparse_triplets_are_checked_array_by_array(tmp_path, monkeypatch, replaced, message):
    """Before: numpy's and scipy's messages without the file (an index out of range, a
    negative shape), a MemoryError for 7 TiB (a shape of 1e12), and a row index 0.5 cut to
    0 without a word."""
    monkeypatch.setattr(matrix_files, "machine_memory", lambda: 16 * 2**30)
    path = tmp_path / "blade.npz"
    np.savez(path, M=np.eye(2), **(TRIPLETS | replaced))
    with pytest.raises(ValueError, match=r"^blade\.npz\." + message):
        read_matrices(path)


def test_sparse_triplets_stored_as_whole_floats_read_as_their_integers(tmp_path):
    np.savez(tmp_path / "blade.npz", M=np.eye(2),
             **{k: v.astype(float) for k, v in TRIPLETS.items()})
    np.testing.assert_array_equal(read_matrices(tmp_path / "blade.npz").stiffness.toarray(),
                                  [[2.0, 0.0], [-1.0, 3.0]])


# ---- reductions ----------------------------------------------------------------------------

@pytest.mark.parametrize("q, shape", [(np.zeros(3), r"\(2\), got shape \(3,\)"),
                                      (np.zeros((3, 5)), r"\(2×n\), got shape \(3, 5\)"),
                                      (np.zeros((5, 2)), r"\(2×n\), got shape \(5, 2\)")])
def test_a_reduction_expands_only_its_own_number_of_coordinates(q, shape):
    """Before: numpy's matmul message about a gufunc signature's core dimension."""
    reduced = modal_truncation(np.eye(4), np.diag([1.0, 2.0, 3.0, 4.0]) * 1e4, 2,
                               points={"p": [[1.0, 0.0, 0.0, 0.0]]})
    with pytest.raises(ValueError, match=r"^Substructure\.expand\.q must have shape " + shape):
        reduced.expand(q)
    states = np.array([[1.0, 2.0], [3.0, -1.0]])  # one column per instant
    np.testing.assert_array_equal(reduced.expand(states),
                                  np.column_stack([reduced.basis @ c for c in states.T]))


# ---- continuation from a bifurcation -------------------------------------------------------

def doubling_at(gamma1: float, of: float | None = None) -> Bifurcation:
    """A made-up period doubling at γ1 = ``gamma1`` whose orbit is one of the paper's group
    at γ1 = ``of`` (default the same)."""
    return Bifurcation(kind="period-doubling", parameter=gamma1,
                       orbit=orbit(three_blade_paper(gamma1=gamma1 if of is None else of), 1.0),
                       multiplier=complex(-1.0), index=0, bracket=(gamma1 - 0.1, gamma1 + 0.1))


def paper_at(gamma1: float) -> Scene:
    return three_blade_paper(gamma1=gamma1)


@pytest.mark.parametrize("bifurcation, scene_at, message", [
    (doubling_at(20.0), paper_at,
     r"from_bifurcation lies at 20, outside the range start = 1 … stop = 3"),
    (doubling_at(2.0, of=2.5), paper_at,
     r"from_bifurcation is a bifurcation of another scene: its orbit's scene is not "
     r"scene_at\(2\)"),
    (doubling_at(2.0), lambda gamma1: modal_packet(gap=-gamma1 * 1e-6),
     r"from_bifurcation is a bifurcation of another scene"),
])
def test_a_branch_starts_only_from_a_bifurcation_of_its_own_scene_and_range(
        bifurcation, scene_at, message):
    """Before: a corrector that ran and failed ("a corrector step of 13.3 leaves the
    prediction's reach 1"; "simulate.initial must be (x0, v0)" from another scene's
    state)."""
    with pytest.raises(ValueError, match=r"^continuation\." + message):
        continuation(scene_at, 1.0, 3.0, from_bifurcation=bifurcation)
    _check_born_here(doubling_at(2.0), paper_at, 1.0, 3.0)  # its own: no error


def test_the_same_scene_is_told_for_substructures_too():
    """Their coordinates' layout is a record without an equality of its own: two equal
    packets were taken for different ones, so a scene_at that ignored its value passed."""
    assert same_scene(modal_packet(), modal_packet())
    assert not same_scene(modal_packet(), modal_packet(speed_rpm=2801.0))
    with pytest.raises(ValueError, match="scene_at returns the same scene for different "
                                         "values"):
        continuation(lambda p: modal_packet(), 2700.0, 2900.0)


# ---- an excitation taken from one scene for another group ----------------------------------

def ring_of(n: int, excitation: Excitation) -> Scene:
    shroud = Interface(gap=1e-5, angle=0.5, normal=cl.LinearSpring(stiffness=1e6),
                       friction=cl.Coulomb(mu=0.3))
    return Scene(group=BladeGroup.ring(n, Blade(mass=0.1, damping=1.0, stiffness=1e5), shroud),
                 excitation=excitation, speed_rpm=3000.0)


@pytest.mark.parametrize("engine_order, grown", [(5, 4), (8, 8), (3, 7)])
def test_an_engine_order_wave_taken_from_one_ring_is_the_wave_on_another(engine_order, grown):
    """φ_i = 2π (l mod N) i / N on the new ring of N, whatever ring the excitation came
    from. Before: the first ring's TravellingWave, refused for its diameter (l = 5 from 6
    blades to 4) or kept with the wrong one, silently (l = 8 from 6 blades to 8: ND 2 where
    it is 0)."""
    six = ring_of(6, Excitation(engine_order=engine_order, amplitudes=(0.0, 1.0),
                                phases=EngineOrderWave()))
    assert six.excitation.phases == TravellingWave(engine_order % 6)
    other = ring_of(grown, six.excitation)
    assert other.excitation.phases == TravellingWave(engine_order % grown)
    expected = 2 * math.pi * (engine_order % grown) * np.arange(grown) / grown
    np.testing.assert_allclose(other.arrays.phases, expected, rtol=0, atol=1e-12)
    with pytest.raises(ValueError, match=r"TravellingWave\.nodal_diameter must be in"):
        ring_of(4, Excitation(engine_order=1, amplitudes=(0.0, 1.0),
                              phases=TravellingWave(5)))  # a wave given as such stays one


def test_an_engine_order_wave_taken_from_one_bladed_disc_is_the_wave_on_another():
    """Every node of sector s at 2π (l mod N) s / N. Before: "ExplicitPhases has 18 phases
    for 24 blades", a pattern the user never gave."""
    six, eight = bladed_disc_24(sectors=6), bladed_disc_24(sectors=8)
    grown = Scene(group=eight.group, excitation=six.excitation, speed_rpm=3000.0)
    sector = np.repeat(np.arange(8), 3)  # three nodes a sector, in sector order
    expected = np.angle(np.exp(2j * math.pi * 6 * sector / 8))
    np.testing.assert_allclose(np.angle(np.exp(1j * grown.arrays.phases)), expected,
                               rtol=0, atol=1e-12)
    np.testing.assert_allclose(grown.arrays.phases, eight.arrays.phases, rtol=0, atol=0)


# ---- readings of a run ---------------------------------------------------------------------

@pytest.mark.parametrize("series", [[], np.arange(49.0)], ids=["empty", "49 points"])
def test_the_zero_one_test_refuses_a_series_too_short_to_tell(series):
    """Before: NaN, silently."""
    with pytest.raises(ValueError, match=r"^zero_one_test\.series needs at least 50 entries, "
                                         rf"got {len(series)}$"):
        zero_one_test(series)


def test_too_few_poincare_points_still_classify_as_undetermined():
    """classify_section asks the 0–1 test only where it can tell."""
    angles = 1.3 * np.arange(10.0)  # an irrational rotation: no period
    kind = classify_section(np.column_stack([np.sin(angles), np.cos(angles)]))
    assert kind.label == "undetermined" and math.isnan(kind.zero_one)
    assert "10 Poincaré points are too few for the 0–1 test (it needs 50)" in str(kind)


# ---- results files -------------------------------------------------------------------------

def made_run(scene: Scene, second: bool) -> Simulation:
    """Four periods of a scene, made up (nothing integrated): zeros of the right shapes,
    with the friction along t₂ where ``second``."""
    n, m, samples = scene.arrays.n_blades, scene.arrays.n_interfaces, 21
    settings = {"method": "FixedStep", "steps_per_period": 10, "periods": 4,
                "samples_per_period": 5, "event_tolerance": 1e-10,
                "zeno": {"events": 200, "window": 1e-4}}
    events = EventLog(time=np.zeros(0), interface=np.zeros(0, dtype=np.int64),
                      kind=np.zeros(0, dtype=np.int64),
                      counts={kind.name.lower(): 0 for kind in EventKind})
    return Simulation(scene=scene, settings=settings,
                      t=np.linspace(0.0, 4 * scene.excitation_period, samples),
                      x=np.zeros((samples, n)), v=np.zeros((samples, n)),
                      normal_force=np.zeros((samples, m)), friction_force=np.zeros((samples, m)),
                      modes=np.zeros((samples, m), dtype=np.int8), events=events,
                      energy=EnergyLedger(0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
                      work=np.zeros((samples, 5)), samples_per_period=5, steps=40,
                      friction_force_second=np.full((samples, m), 7.0) if second else None)


def rewritten(path: Path, change) -> Path:
    """A copy of the results file ``path`` with ``change(arrays, meta)`` made to it."""
    with np.load(path) as data:
        arrays = {name: data[name] for name in data.files}
    meta = json.loads(arrays["meta"].tobytes())
    change(arrays, meta)
    arrays["meta"] = np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8)
    copy = path.with_name("changed.npz")
    np.savez(copy, **arrays)
    return copy


@pytest.mark.parametrize("elastic", [False, True], ids=["rigid", "elastic"])
def test_a_results_file_must_hold_the_friction_along_t2_exactly_where_its_scene_has_it(
        tmp_path, elastic):
    """A rigid contact's file with the array added read 7 N along t₂, an elastic one's with
    it removed 0 N: each is refused by the array's name."""
    scene = blade_pair(tangential_stiffness=1e6 if elastic else None)
    path = results.save_simulation(tmp_path / "run.npz", made_run(scene, second=elastic))
    assert results.load_simulation(path).friction_along(0, 2)[0] == (7.0 if elastic else 0.0)

    def flip(arrays, meta):
        if elastic:
            del arrays["friction_force_second"]
        else:
            arrays["friction_force_second"] = np.full_like(arrays["friction_force"], 7.0)
    message = ("has no array 'friction_force_second', which a run of a scene with elastic "
               "contacts" if elastic else "holds an array 'friction_force_second', which "
               "only a run of a scene with elastic contacts")
    with pytest.raises(results.ResultsError, match=f"changed.npz: {message}"):
        results.load_simulation(rewritten(path, flip))


def test_a_results_file_that_counts_an_unknown_kind_of_event_is_refused(tmp_path):
    path = results.save_simulation(tmp_path / "run.npz", made_run(blade_pair(), False))
    changed = rewritten(path, lambda arrays, meta: meta["event_counts"].update(bogus=3))
    with pytest.raises(results.ResultsError,
                       match=r"changed\.npz: meta\.event_counts counts the unknown event kind "
                             r"'bogus'; the kinds are closing, separation, sticking, reversal, "
                             r"breakaway"):
        results.load_simulation(changed)
    branch = results.save_branch(tmp_path / "branch.npz", Branch(
        parameter=np.array([1.0]), orbits=(orbit(three_blade_paper(gamma1=2.0), 1.0),),
        bifurcations=(), periods=1, name="gamma1", ended="stop reached"))
    changed = rewritten(branch, lambda arrays, meta: meta["event_counts"][0].update(slip=1))
    with pytest.raises(results.ResultsError, match=r"meta\.event_counts\[0\] counts the "
                                                   r"unknown event kind 'slip'"):
        results.load_branch(changed)


# ---- the command line ----------------------------------------------------------------------

def test_a_short_run_saved_without_its_settings_plots(tmp_path):
    """Its settings are the defaults fitted to it: a transient of 300 periods in a file of
    2 was refused ("Simulation.poincare.skip must be a whole number of periods in [0, 2)
    ..., got 300")."""
    path = results.save_simulation(tmp_path / "run.npz", paper_run())
    settings = results.load_run_settings(path)
    assert (settings.periods, settings.transient) == (2, 1)
    assert main(["plot", str(path)]) == 0
    assert (tmp_path / "run.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("periods, transient", [(1, 0), (5, 2), (300, 150), (301, 300),
                                                (10_000, 300)])
def test_the_transient_given_to_a_run_without_one_leaves_it_periods_to_read(periods,
                                                                             transient):
    assert transient_for(periods) == transient < periods


# ---- a state given as an array -------------------------------------------------------------

def test_a_start_given_as_a_two_row_array_is_taken_as_the_same_nested_list():
    """Before: the nested list ran and the 2 × 3 array was refused."""
    start = [[1e-5, 0.0, -1e-5], [0.0, 0.1, 0.0]]
    scene = three_blade_paper()
    as_list = simulate(scene, 1, samples_per_period=10, initial=start)
    as_array = simulate(scene, 1, samples_per_period=10, initial=np.array(start))
    np.testing.assert_array_equal(as_array.x, as_list.x)
    np.testing.assert_array_equal(as_array.x[0], start[0])
    np.testing.assert_array_equal(as_array.v[0], start[1])
    for wrong in (np.zeros((3, 3)), np.zeros(6)):
        with pytest.raises(ValueError, match=r"^simulate\.initial must be \(x0, v0\), a pair "
                                             r"of 3 displacements"):
            simulate(scene, 1, initial=wrong)


# ---- a blade held by contacts alone --------------------------------------------------------

FREE = Blade(mass=0.1, damping=1.0, stiffness=0.0)  # no spring to ground
SPRUNG = Blade(mass=0.1, damping=1.0, stiffness=1e5)


def stop(angle: float = 0.5, normal=None) -> Interface:
    return Interface(gap=1e-5, angle=angle, normal=normal or cl.LinearSpring(stiffness=1e6),
                     friction=cl.Coulomb(mu=0.3))


def scene_of(group: BladeGroup, q0: float = 0.0) -> Scene:
    blades = len(group.blades)
    return Scene(group=group, speed_rpm=3000.0, excitation=Excitation(
        engine_order=1, amplitudes=(q0, 1.0), phases=[0.0] * blades))


def one_stop() -> BladeGroup:
    """A free blade that touches a wall on its +x side."""
    return BladeGroup().add_fixed("wall").add_blade("b", FREE).connect("b", "wall", stop())


@pytest.mark.parametrize("make, message", [
    (lambda: scene_of(one_stop()),
     r"blades \['b'\] are held only by contacts that open, \[\('b', 'wall'\)\], which stop "
     r"them moving \+x: .* their mean force, 0 N, does not press them"),
    (lambda: scene_of(one_stop(), q0=-2.0), r".*stop them moving \+x: .* mean force, -2 N"),
    (lambda: scene_of(BladeGroup().add_fixed("wall").add_blade("b", FREE).connect(
        "wall", "b", stop())), r".*\[\('wall', 'b'\)\], which stop them moving −x"),
    # a chain of two free blades on one wall: b drifts off it, pushing a along
    (lambda: scene_of(one_stop().add_blade("a", FREE).connect("a", "b", stop())),
     r"blades \['b'\] are held only by contacts that open, \[\('b', 'wall'\)\], which "
     r"stop them moving \+x"),
    # a contact at α = 0 has no normal force along x
    (lambda: scene_of(BladeGroup().add_fixed("wall").add_blade("b", FREE).connect(
        "b", "wall", stop(angle=0.0))),
     r"blades \['b'\] are held along x by no spring, no Coupling and no contact that can "
     r"stop them"),
])
def test_blades_that_contacts_hold_one_way_only_are_refused(make, message):
    """Before: the scene was taken, and the blade drifted off after its first impact."""
    with pytest.raises(ValueError, match=r"^Scene\.group: " + message):
        make()


@pytest.mark.parametrize("make", [
    # pressed onto its stop by its mean force, as a ball onto a table
    lambda: scene_of(one_stop(), q0=2.0),
    # a stop on each side
    lambda: scene_of(one_stop().add_fixed("other").connect("other", "b", stop())),
    # two free blades between two walls: each holds the other
    lambda: scene_of(one_stop().add_blade("a", FREE).connect("a", "b", stop())
                     .add_fixed("left").connect("left", "a", stop())),
    # a free blade pressed on a sprung one from the +x side, and held by a wall beyond it
    lambda: scene_of(BladeGroup().add_blade("a", SPRUNG).add_blade("b", FREE)
                     .add_fixed("wall").connect("a", "b", stop()).connect("b", "wall", stop())),
    # a contact that never opens holds both ways (a damper pressed on its platform)
    lambda: scene_of(BladeGroup().add_fixed("wall").add_blade("b", FREE).connect(
        "b", "wall", stop(normal=cl.ConstantLoad(force=10.0)))),
])
def test_blades_held_both_ways_or_pressed_onto_their_stop_are_taken(make):
    assert isinstance(make(), Scene)
