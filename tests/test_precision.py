"""Accuracy knobs that mean something: the asked accuracy is delivered, errors shrink as
the knobs tighten, and the work–precision study measures what it says."""

from dataclasses import replace

import numpy as np
import pytest

from contact_laws import Coulomb, Regularised
from shroudnet import Accuracy, Adaptive, FixedStep, simulate, sweep
from shroudnet.scenes import three_blade_paper
from shroudnet.studies.precision import (
    REFERENCE,
    Measurement,
    Setting,
    Study,
    errors,
    outcome,
    paper_regimes,
    regularised,
    run,
    sampling_floor,
    summary,
)
from tests.test_simulate import linear_response

#: The paper's p1 and p3 regimes, shortened: still periodic, errors still settled.
SHORT = {r.name: replace(r, transient=150, record=12)
         for r in paper_regimes() if not r.chaotic}


@pytest.fixture(scope="module")
def references():
    return {name: outcome(run(regime, REFERENCE), regime) for name, regime in SHORT.items()}


def error_of(name, setting, references):
    regime = SHORT[name]
    return max(errors(outcome(run(regime, setting), regime), references[name],
                      chaotic=False).values())


@pytest.mark.parametrize("target", [1e-3, 1e-5, 1e-7])
def test_accuracy_delivers_what_it_asks_for_in_periodic_regimes(target, references):
    asked = Setting(family="Accuracy", label="", method=Accuracy(target=target))
    for name in SHORT:
        assert error_of(name, asked, references) <= target


def test_accuracy_meets_the_closed_form_without_contact():
    """Checked against the exact solution, not against another run of the integrator."""
    scene = three_blade_paper(gap=1.0, q1=50.0)
    x0, v0 = linear_response(scene, [0.0])
    for target in (1e-4, 1e-7):
        sim = simulate(scene, 20, method=Accuracy(target=target), initial=(x0[0], v0[0]))
        x, _ = linear_response(scene, sim.t)
        assert np.abs(sim.x - x).max() <= target * np.abs(x).max()


def test_errors_shrink_as_each_knob_tightens(references):
    """Fixed-step RK4 converges at order 4 through impacts and stick; the adaptive error
    falls with rtol; the event location error with its tolerance; regularised friction
    approaches the exact law as v_ε → 0."""
    def error(**setting):
        return error_of("p3 (γ1 = 3.5)", Setting(family="", label="", **setting), references)

    fixed = [error(method=FixedStep(steps_per_period=n)) for n in (100, 200, 400)]
    assert fixed[0] / fixed[1] > 8.0 and fixed[1] / fixed[2] > 8.0
    adaptive = [error(method=Adaptive(rtol=r, atol=r * 1e-4)) for r in (1e-4, 1e-6, 1e-8)]
    # Measured: 1.1e-3, 2.9e-6, 1.8e-7 (and 1.3e-9 at rtol 1e-10): at least 10x per 100x.
    assert adaptive[0] / adaptive[1] > 10.0 and adaptive[1] / adaptive[2] > 10.0
    tight = Adaptive(rtol=1e-12, atol=1e-16)
    located = [error(method=tight, event_tolerance=tol) for tol in (1e-4, 1e-6, 1e-8)]
    assert all(e <= 10.0 * tol for e, tol in zip(located, (1e-4, 1e-6, 1e-8)))
    assert located[0] / located[2] > 100.0
    smoothed = [error(method=Adaptive(rtol=1e-10, atol=1e-14), regularisation=velocity)
                for velocity in (1e-2, 1e-3)]
    assert smoothed[0] / smoothed[1] > 3.0


def test_regularised_wraps_every_exact_friction_law_and_keeps_the_rest():
    scene = three_blade_paper(gamma1=3.5, friction=Coulomb(mu=0.3))
    smooth = regularised(scene, 1e-3)
    for (_, _, before), (_, _, after) in zip(scene.group.interfaces, smooth.group.interfaces):
        assert after.friction == Regularised(law=before.friction, velocity=1e-3)
        assert replace(after, friction=before.friction) == before
    assert regularised(smooth, 1e-5).group.interfaces[0][2].friction.velocity == 1e-3
    assert smooth.arrays.stiffness.tolist() == scene.arrays.stiffness.tolist()


def test_errors_are_zero_against_themselves_and_the_chaotic_floor_is_not():
    chaotic = next(r for r in paper_regimes(transient=100, chaotic_record=100) if r.chaotic)
    reference = outcome(run(chaotic, REFERENCE), chaotic)
    assert max(errors(reference, reference, chaotic=True).values()) == 0.0
    assert sampling_floor(chaotic, reference) > 1e-4   # records of one attractor differ
    periodic = SHORT["p1 (γ1 = 1)"]
    assert sampling_floor(periodic, None) == 0.0


def test_summary_takes_the_cheapest_setting_of_each_family_within_each_target():
    def measured(family, label, milliseconds, error):
        setting = Setting(family=family, label=label, method=Adaptive())
        return Measurement(regime="r", setting=setting, seconds_per_period=milliseconds / 1e3,
                           errors={"E_rho": error})

    study = Study(measurements=[
        measured("FixedStep", "slow and exact", 2.0, 1e-9),
        measured("FixedStep", "quick and rough", 0.5, 1e-3),
        measured("Adaptive", "middle", 1.0, 1e-5),
    ], floors={"r": 0.0})
    rows = summary(study, targets=(1e-2, 1e-6, 1e-12))
    assert [(row[1], row[3]) for row in rows] == [
        (1e-2, "quick and rough"), (1e-2, "middle"), (1e-6, "slow and exact"),
        (1e-12, "")]
    assert rows[-1][2] == "none"


def test_bad_accuracy_and_method_fail_before_any_work():
    with pytest.raises(ValueError, match=r"Accuracy\.target must be in \[1e-08, 0\.1\]"):
        Accuracy(target=1.0)
    with pytest.raises(TypeError, match=r"sweep\.method must be FixedStep"):
        sweep(lambda g: three_blade_paper(gamma1=g), [1.0], method="rk4", workers=1)


def test_paper_regimes_are_the_papers_group_at_three_stiffness_ratios():
    """§3.2: γ1 = k_c/k = 1 (p1), 3.5 (p3) and 8.8 (chaotic), at 6000 rpm with q1 = 50 N,
    each with the periods to skip and to record that were asked for."""
    regimes = paper_regimes(transient=7, record=9, chaotic_record=11)
    assert [(r.transient, r.record, r.chaotic) for r in regimes] == [
        (7, 9, False), (7, 9, False), (7, 11, True)]
    for regime, gamma1 in zip(regimes, (1.0, 3.5, 8.8)):
        scene = regime.scene
        k = scene.group.blade(scene.blades[0]).stiffness_at(6000.0)
        assert scene.speed_rpm == 6000.0 and scene.excitation.amplitudes == (0.0, 50.0)
        for _, _, interface in scene.group.interfaces:
            assert interface.normal.stiffness == pytest.approx(gamma1 * k, rel=1e-15)
