"""Plant known bugs one at a time and report which ones the tests miss.

Each mutation edits one line of a copy of the source tree, runs the tests meant to catch
that kind of bug against the copy, and counts as *killed* when a test fails, *hung* when
the tests run past the time limit, and *survived* when they all pass. A surviving
mutation is a bug the test suite cannot see::

    python tests/mutations.py                 # every mutation
    python tests/mutations.py stick-limit     # those whose name (or layer) holds a word
    python tests/mutations.py tangent         # every mutation of the tangent layer
    python tests/mutations.py --list
    python tests/mutations.py --check         # does every mutation plant? (no tests run)
    python tests/mutations.py --source DIR    # plant into another checkout's tree
    python tests/mutations.py laws --tests tests/test_contact_laws.py   # other tests

A mutation names the text it replaces, not the file: the one file under ``shroudnet/`` or
``contact_laws/`` that holds the text is found at each run, so the list survives code
moving between files. A mutation whose text is in no file, in several, or more than once
in its file cannot be planted: that fails the run before any test runs (a bug list that
quietly shrinks would report ever fewer survivors), and ``--check`` finds it in seconds.
It also checks that every layer in ``LAYERS`` has a mutation and that every test a
mutation aims at exists.

Each run first runs the tests on an unchanged copy (skip it with ``--no-control``): a
test that fails there would kill every mutation and prove nothing.

The copies keep their compiled kernels in one cache folder of their own
(``$SHROUDNET_MUTATION_CACHE``, else ``~/.cache/shroudnet-mutations``), so a second run
compiles only what changed. A mutation of the compiled loop compiles its kernels anew:
count on one to three minutes for each.
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, replace
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: The folders a mutation's text is looked for in.
SOURCE_FOLDERS = ("shroudnet", "contact_laws")

#: The parts of the code the mutations must reach, each by at least one: the contact laws,
#: the scene's model, the compiled loop (forces, events, modes), the energy ledger, the
#: tangent flow and its saltation matrices, periodic orbits (Newton on the stroboscopic
#: map), continuation (its bifurcation test functions), stick as constraints (the
#: substructures' multipliers and projection), the linear limits (the forced response
#: with the interfaces open or stuck) and harmonic balance (the contacts' forces in time,
#: the condensation onto them and Hill's matrix).
LAYERS = ("laws", "model", "loop", "ledger", "tangent", "orbits", "continuation",
          "constraints", "linear", "harmonic")

#: Tests that check the physics, run against every mutation unless it names its own.
PHYSICS_TESTS = (
    "tests/test_contact_laws.py",
    "tests/test_paper_equations.py",
    "tests/test_dynamics_properties.py",
    "tests/test_physics_references.py",
    "tests/test_simulation_errors.py",
    "tests/test_hard_cases.py",
    "tests/test_simulate.py",
    "tests/test_baseline_and_bench.py",
)

#: The tests aimed at the exact propagation of linear phases (``methods.Exponential``).
PROPAGATION = "tests/test_exponential.py"
#: The tests aimed at the tangent flow, the orbits and the continuation.
MONODROMY = "tests/test_tangent.py::test_monodromy_agrees_with_differences_of_the_trajectory"
#: Its cases, each run alone: a mutation of the engine compiles the kernels of those it
#: runs. Breakaway is seen only where the friction drops as it slips (μ(0⁺) < μ_s, a law of
#: the tests' own): elsewhere the vector field is continuous there, and its saltation P.
SLIP_REVERSAL, STICKING, DROPPING, SPRING_BREAKAWAY, DAMPED_IMPACT, STIFFENING = (
    f"{MONODROMY}[{case}]" for case in ("slip reversal", "stick and breakaway",
                                        "friction dropping at breakaway",
                                        "stick and breakaway on a spring pad",
                                        "damped impact", "stiffening impact"))
STUCK_CLUSTER = "tests/test_tangent.py::test_monodromy_of_an_all_stuck_cluster_moves_it_as_one_body"
APART = ("tests/test_tangent.py::"
         "test_apart_interfaces_switching_at_the_same_instant_multiply_their_saltations")
LINEAR_NEWTON = "tests/test_orbits.py::test_newton_solves_a_linear_scene_in_one_step"
UNSTABLE_ORBIT = "tests/test_orbits.py::test_newton_finds_an_unstable_orbit_that_transients_leave"
FOLDS = "tests/test_orbits.py::test_a_folded_branch_turns_back_at_its_folds"
DOUBLING = ("tests/test_orbits.py::"
            "test_a_period_doubling_starts_a_doubled_branch_that_a_transient_lands_on")
TORUS = ("tests/test_orbits.py::"
         "test_the_papers_resonance_loses_period_one_at_a_torus_bifurcation")


#: The tests of substructures: one-degree-of-freedom ones against the blades, and a
#: multi-degree-of-freedom orbit's monodromy against differences.
ONE_DOF = "tests/test_structures.py::test_one_dof_substructures_reproduce_the_blades"
MULTI_DOF_MONODROMY = ("tests/test_structures.py::test_monodromy_of_a_multi_dof_orbit_with_"
                       "impacts_stick_and_breakaway_agrees_with_differences")
#: Where the friction drops at breakaway: the saltation there has a jump term, so the
#: breakaway guard's gradient counts (with Coulomb friction it does not).
MULTI_DOF_DROPPING = ("tests/test_structures.py::"
                      "test_monodromy_where_friction_drops_at_breakaway_agrees_with_differences")
#: Two unreduced beams against the independent reference: masses that differ from 1.
BEAMS = ("tests/test_structures.py::"
         "test_two_unreduced_beams_with_a_shroud_contact_match_an_independent_reference")
#: The tangent carried by one exponential a phase, against scipy and against the steps.
EXPONENTIAL = "tests/test_phase_exponential.py"
#: Branches through kinks and up to a nonsmooth fold.
KINKS = "tests/test_continuation_kinks.py"
#: Hysteresis loops against the ledger's friction loss.
HYSTERESIS = "tests/test_hysteresis.py"
#: The linear forced response against closed forms and against runs.
LINEAR_RESPONSE = "tests/test_linear_response.py"
#: One cycle's harmonics, energy and equivalent damping against closed forms.
CYCLE = "tests/test_cycle.py"
#: Orbit extremes against Den Hartog's and the linear oscillator's closed forms.
EXTREMES = "tests/test_extremes.py"
#: Elastic contacts: their geometry and their stuck limit against closed forms.
ELASTIC = "tests/test_elastic_contacts.py"
#: Their tangent: the sliders' Jacobian and the monodromy through 2-D stick–slip–separation.
ELASTIC_TANGENT = "tests/test_elastic_tangent.py"
ELASTIC_MONODROMY = ("tests/test_elastic_tangent.py::"
                     "test_monodromy_through_stick_slip_and_separation_of_2d_elastic_faces")
ELASTIC_ORBIT = ("tests/test_elastic_tangent.py::"
                 "test_the_elastic_packets_orbit_carries_its_stretches_and_its_monodromy_agrees")
#: One tangent column through faces that open while they slip, against differences.
ONE_COLUMN = ("tests/test_elastic_tangent.py::"
              "test_one_tangent_column_passes_faces_that_open_while_they_slip")
#: Harmonic balance against closed forms, exact orbits and differences of its own forces.
HARMONIC = "tests/test_harmonic_balance.py"
#: A tuned ring's harmonic balance on one sector against the whole ring's balance.
HARMONIC_SECTORS = "tests/test_harmonic_sectors.py"
#: A patch solved on its directions against the balance on every contact coordinate.
HARMONIC_PATCHES = "tests/test_harmonic_patches.py"
#: Patches: four pairs on two beams against the independent reference, and coincident
#: pairs against one of their summed stiffnesses.
PATCH_REFERENCE = ("tests/test_patches.py::"
                   "test_a_patch_of_four_pairs_on_two_beams_matches_the_independent_reference")
PATCHES = "tests/test_patches.py"
#: Sector frames against the same ring turned by hand, and the reference's own reading.
FRAMES = "tests/test_frames.py"
#: Cyclic symmetry of FE sectors against the full shooting (3-D elastic faces: stretches).
CYCLIC_SECTORS = ("tests/test_cyclic_sectors.py::"
                  "test_the_symmetric_orbit_of_a_ring_of_fe_sectors_is_the_full_shootings")
#: Excitation at a frequency of its own against the linear oscillator's closed form.
FREQUENCY = ("tests/test_frequency_excitation.py::"
             "test_a_linear_oscillator_forced_apart_from_the_speed_meets_its_closed_form")


#: Matrix-free shooting: GMRES and Arnoldi on matrices of known spectrum, Krylov against
#: dense shooting, the exponential method's shooting and Lyapunov exponents, and the
#: neutral directions of a contact stuck through the whole orbit.
SHOOTING = "tests/test_shooting.py"
KRYLOV = tuple(f"{SHOOTING}::{name}" for name in (
    "test_arnoldi_finds_the_leading_eigenvalues_of_a_matrix_of_known_spectrum",
    "test_the_arnoldi_step_keeps_the_basis_orthonormal_and_the_relation_exact",
    "test_gmres_solves_to_its_tolerance_and_a_right_preconditioner_is_undone"))
SHOOTING_KRYLOV = (f"{SHOOTING}::test_krylov_and_dense_shooting_find_one_orbit_and_its_leading_"
                   "multipliers")
SHOOTING_EXPONENTIAL = (f"{SHOOTING}::test_the_exponential_methods_orbit_and_multipliers_are_the_"
                        "adaptive_ones",
                        f"{SHOOTING}::test_the_exponential_methods_monodromy_and_branch_are_the_"
                        "adaptive_ones")
NEUTRAL = (f"{SHOOTING}::test_a_contact_stuck_all_through_is_neutral_its_offset_pinned_at_the_"
           "starts")
NEUTRAL_CHAIN = (f"{SHOOTING}::test_the_chain_continued_from_the_fully_stuck_range_reaches_the_"
                 "far_end_without_a_fold")


@dataclass(frozen=True)
class Mutation:
    """Replace ``old`` by ``new`` in the one source file that holds ``old`` (once).

    ``layer``: the part of the code it reaches, one of ``LAYERS``. ``tests``: what to run
    against it, pytest paths or node ids; the tests aimed at the bug, so that its run is
    short, or by default ``PHYSICS_TESTS``.
    """

    name: str
    layer: str
    old: str
    new: str
    why: str
    tests: tuple[str, ...] = PHYSICS_TESTS


MUTATIONS = (
    # ---- laws ----------------------------------------------------------------------------
    Mutation("hertz-exponent", "laws",
             "    stiffness: float\n    exponent: float = 1.5\n\n    def __post_init__(self):\n"
             "        check_real(\"Hertz\"",
             "    stiffness: float\n    exponent: float = 1.4\n\n    def __post_init__(self):\n"
             "        check_real(\"Hertz\"",
             "Hertz contact with the wrong default exponent"),
    Mutation("exponential-friction-decay", "laws",
             "return mu_kinetic + (mu_static - mu_kinetic) * math.exp(-beta * slip_speed)",
             "return mu_kinetic + (mu_static - mu_kinetic) * math.exp(-beta * slip_speed * 0.5)",
             "the paper's eq. (4) decays at half the rate (its slope still at the full one)"),
    Mutation("kelvin-voigt-damping-sign", "laws",
             "return max(0.0, stiffness * penetration + damping * rate)",
             "return max(0.0, stiffness * penetration - damping * rate)",
             "the contact damper pushes with the closing rate's opposite sign"),
    Mutation("hunt-crossley-damping-dropped", "laws",
             "** exponent * (1.0 + damping * rate)", "** exponent * (1.0 + 0.0 * rate)",
             "Hunt–Crossley contact without its damping"),
    # ---- model ---------------------------------------------------------------------------
    Mutation("stick-limit-1.2", "model",
             "f.static_coefficient for f in frictions",
             "1.2 * f.static_coefficient for f in frictions",
             "stuck interfaces hold 20 % more than μ_s N"),
    # ---- loop ----------------------------------------------------------------------------
    Mutation("slider-load-rate-sign", "loop",
             "- s.static_mu[e] * normal_rate / s.tangential_stiffness[e]",
             "+ s.static_mu[e] * normal_rate / s.tangential_stiffness[e]",
             "a slipping slider outruns a falling friction limit instead of following it",
             ("tests/test_elastic_engine.py",)),
    Mutation("stuck-stretch-first-direction", "loop",
             "        return r1, r2, 0.0\n    return r1 - d1",
             "        return r1, 0.0, 0.0\n    return r1 - d1",
             "a stuck 2-D spring is loaded along its first tangent only: the slider creeps "
             "along the second",
             ("tests/test_elastic_engine.py",)),
    Mutation("slider-rk4-first-stage-dropped", "loop",
             "x_new[i] = x[i] + h / 6.0 * (a1[i] + 2.0 * a2[i]",
             "x_new[i] = x[i] + h / 6.0 * (a2[i] + 2.0 * a2[i]",
             "a fixed step weighs its sliders' first stage as its second: consistent, but "
             "no longer fourth order",
             ("tests/test_elastic_engine.py",)),
    Mutation("slider-second-friction-sign", "loop",
             "w.resultant[i] -= friction * s.second_tangent_rows[e, i]",
             "w.resultant[i] += friction * s.second_tangent_rows[e, i]",
             "the friction along the second tangent pushes the structure the wrong way",
             ("tests/test_elastic_engine.py",)),
    Mutation("slider-loss-first-direction", "ledger",
             "r2 - d2 * speed, size * speed",
             "r2 - d2 * speed, abs(w.friction[e]) * speed",
             "the ledger books a 2-D slider's loss along its first direction only",
             ("tests/test_elastic_engine.py",)),
    Mutation("elastic-energy-quarter", "ledger",
             "energy += 0.5 * stiffness[e] * float(stretch @ stretch)",
             "energy += 0.25 * stiffness[e] * float(stretch @ stretch)",
             "the stuck spring stores half its energy ½ k_t |u|²",
             ("tests/test_elastic_engine.py",)),
    Mutation("stick-rule-slack-0.05", "loop",
             "if candidates[e] else limit):", "if candidates[e] else 1.05 * limit):",
             "the mode rule keeps a stick the breakaway guard has released"),
    Mutation("friction-slack-0.05", "loop",
             "FRICTION_SLACK = 1e-9", "FRICTION_SLACK = 0.05",
             "a slip that reaches zero sticks while it needs up to 1.05 μ_s N"),
    Mutation("friction-sign-negative-slip", "loop",
             "            w.friction[e] = sign * normal * sliding_mu(",
             "            w.friction[e] = normal * sliding_mu(",
             "friction pushes along a negative slip instead of against it"),
    Mutation("breakaway-logged-as-reversal", "loop",
             "    if before == STICK:\n        return BREAKAWAY",
             "    if before == STICK:\n        return REVERSAL",
             "a breakaway is logged as a slip reversal"),
    Mutation("static-friction-normal-push-sign", "loop",
             "            imbalance[left[e]] -= push", "            imbalance[left[e]] += push",
             "the normal force's push is added, not taken, in the stuck equilibrium"),
    # ---- loop: the exact propagation of linear phases (``Exponential``) -------------------
    Mutation("propagation-harmonic-sine-sign", "loop",
             "        row[one + 2 * h] += factor * 2.0 / count * value * math.sin(angle)",
             "        row[one + 2 * h] -= factor * 2.0 / count * value * math.sin(angle)",
             "the excitation's sine parts enter the augmented matrix with the wrong sign: the "
             "forcing runs backwards in its phase", (PROPAGATION,)),
    Mutation("propagation-anchor-at-half-its-span", "loop",
             "            span = step * 0.5**k\n", "            span = step * 0.5**(k + 1)\n",
             "the levels computed by the exponential are those of half their step",
             (PROPAGATION,)),
    Mutation("propagation-remainder-dropped", "loop",
             "    if remaining <= step * WHOLE:\n        return\n    a = p.matrix[slot]",
             "    if remaining <= step * 1e-6:\n        return\n    a = p.matrix[slot]",
             "a span's remainder below the finest level is dropped: switches land up to "
             "h 2^{1-L} early", (PROPAGATION,)),
    Mutation("propagation-dips-unseen", "loop",
             "        theta = min(theta, exact_dip(t, h, state, topology, s, w))",
             "        theta = min(theta, 2.0 + 0.0 * h)",
             "an exponential step looks for switches at its ends only", (PROPAGATION,)),
    Mutation("propagation-work-doubled-untransposed", "ledger",
             "            product(levels[k].T, first, second)",
             "            product(levels[k], first, second)",
             "the works double as W + P W P instead of W + Pᵀ W P", (PROPAGATION,)),
    # ---- ledger --------------------------------------------------------------------------
    Mutation("contact-strain-energy-doubled", "ledger",
             "return 0.5 * penetration * sum(", "return penetration * sum(",
             "the ledger books twice the contact strain energy"),
    Mutation("projection-loss-dropped", "ledger",
             "    state.energy[PROJECTION] += lost\n    last = log_switches",
             "    last = log_switches",
             "the kinetic energy lost as blades lock together is not booked (expected to "
             "survive: at stick onset it is about m (a τ)², some 1e-20 J)"),
    Mutation("damping-power-halved", "ledger",
             "damping += s.damping[i] * v[i] * v[i]",
             "damping += 0.5 * s.damping[i] * v[i] * v[i]",
             "the ledger books half the viscous loss"),
    # ---- tangent: the saltation matrices S = P + (f⁺ − P f⁻) nᵀ / (nᵀ f⁻ + ∂g/∂t) --------
    Mutation("saltation-jump-dropped", "tangent",
             "            matrix[r, column] = g.f_minus[r] + jump[r] * along * along_scale",
             "            matrix[r, column] = g.f_minus[r]",
             "a switch multiplies the tangent by P alone, without (f⁺ − P f⁻) nᵀ / ġ",
             (SLIP_REVERSAL, STICKING)),
    Mutation("saltation-time-rate-sign", "tangent",
             "    rate = time_rate\n", "    rate = -time_rate\n",
             "ġ takes ∂g/∂t (the breakaway guard's, through the excitation) with the wrong "
             "sign", (DROPPING,)),
    Mutation("contact-normal-on-velocity", "tangent",
             "        g.guard_normal[s.left[e]] += s.sin_angle[e]",
             "        g.guard_normal[len(s.mass) + s.left[e]] += s.sin_angle[e]",
             "the contact guard's gradient ∂δ/∂y sits in the velocity rows (seen only where "
             "the force jumps as the contact closes: a damped contact)", (DAMPED_IMPACT,)),
    Mutation("slip-normal-on-position", "tangent",
             "        g.guard_normal[n + s.left[e]] += s.cos_angle[e]",
             "        g.guard_normal[s.left[e]] += s.cos_angle[e]",
             "the slip guard's gradient ∂(u̇ cos α)/∂y sits in the position rows",
             (SLIP_REVERSAL,)),
    Mutation("breakaway-normal-friction-sign", "tangent",
             "    return -sign * change", "    return sign * change",
             "the breakaway guard μ_s N − |f| changes with +sgn(f) δf, not −sgn(f) δf "
             "(under a constant load its whole gradient and ∂g/∂t flip, which S does not "
             "see: a spring pad's μ_s δN does not flip)", (SPRING_BREAKAWAY,)),
    Mutation("breakaway-normal-without-the-load", "tangent",
             "g.guard_normal[r] = s.static_mu[e] * normal_change \\",
             "g.guard_normal[r] = 0.0 * normal_change \\",
             "the breakaway guard μ_s N − |f| is differentiated as if N were constant (as it "
             "is for a constant load, not for a spring pad)", (SPRING_BREAKAWAY,)),
    Mutation("saltations-at-one-instant-drop-jumps", "tangent",
             "            matrix[r, column] = g.f_minus[r] + (jump[r] * along[k] if k >= 0 else "
             "0.0)",
             "            matrix[r, column] = g.f_minus[r]",
             "interfaces apart that switch at one instant multiply the tangent by P alone",
             (APART,)),
    Mutation("cluster-projection-by-velocity-not-momentum", "tangent",
             "        momentum[topology.labels[i]] += s.mass[i] * values[first + i]",
             "        momentum[topology.labels[i]] += values[first + i]",
             "velocities are projected onto a stick cluster (P of the saltations, and the "
             "state's at stick onset) by their sum over its mass, not by its momentum",
             (STUCK_CLUSTER,)),
    Mutation("phase-exponential-left-balanced", "tangent",
             "            jacobian[r, c] *= (weight if c >= n else 1.0) / (weight if r >= n else "
             "1.0)",
             "            jacobian[r, c] *= 1.0",
             "a phase's tangent e^{J Δt} is taken as D e^{J Δt} D⁻¹: the balancing of the "
             "velocity rows is not undone", (EXPONENTIAL, MULTI_DOF_MONODROMY)),
    Mutation("pade-odd-part-constant", "tangent",
             "        v[i, i] += b[1]\n", "        v[i, i] += b[0]\n",
             "the Padé approximant's odd part U takes b₀ for b₁: e^A is wrong at every scale",
             (EXPONENTIAL,)),
    Mutation("saltation-knock-on-support-ignored", "tangent",
             "    grown = True\n    while grown:",
             "    grown = False\n    while grown:",
             "a stuck neighbour released by a switch is left out of that switch's support: "
             "a ring's symmetric pairs of switches are called singular",
             ("tests/test_tangent.py::"
              "test_a_rings_interfaces_switching_together_by_its_symmetry_multiply_their_"
              "saltations",)),
    Mutation("slider-turn-dropped", "tangent",
             "    return (first - speed * turn1 + d1 * loading,",
             "    return (first + 0.0 * turn1 + d1 * loading,",
             "a slipping slider's direction û is held fixed in its variation: the term λ δû "
             "of δu̇ is dropped", (ELASTIC_TANGENT,)),
    Mutation("slider-breakaway-normal-without-the-stretch", "tangent",
             "        normal[k] = -s.tangential_stiffness[e] * w.friction[e] / size",
             "        normal[k] = 0.0 * w.friction[e] / size",
             "the elastic breakaway guard μN − k_t|u| is differentiated as if the stretch "
             "along t₁ did not load it", (ELASTIC_MONODROMY,)),
    Mutation("open-stretch-kept", "tangent",
             "        if k < 0 or modes[e] != OPEN:\n            continue\n        for column",
             "        if k >= 0 or modes[e] != OPEN:\n            continue\n        for column",
             "an opening contact keeps its stretch's variation, though its slider follows "
             "(u = 0) from then on", (ELASTIC_MONODROMY,)),
    Mutation("slipping-start-without-the-load", "tangent",
             "        matrix[k, column] = mu_over_k * change * d1 + scale",
             "        matrix[k, column] = 0.0 * change * d1 + scale",
             "a face that starts slipping has its stretch put on the friction limit μN/k_t, "
             "but its tangent forgets that the limit moves with the normal load",
             (ELASTIC_ORBIT,)),
    Mutation("unresolved-stretch-in-the-error", "tangent",
             "        if turning_length(stretch, w.slider_speed[e], g.resolution) > stretch:",
             "        if turning_length(stretch, w.slider_speed[e], g.resolution) < 0.0:",
             "the tangent's error keeps the rows of a slipping stretch too short for the run "
             "to resolve its direction: a face that opens while it slips stops the run",
             (ONE_COLUMN,)),
    Mutation("unresolved-stretch-turns-by-its-length", "tangent",
             "    length = turning_length(size / stiffness, speed, g.resolution)",
             "    length = size / stiffness",
             "a slipping stretch shorter than the run resolves turns by its own length: its "
             "direction's variation relaxes at λ/|u| → ∞ as its face opens",
             (ONE_COLUMN,)),
    Mutation("exponential-tangent-carried-from-the-start", "tangent",
             "    g.since[0] = t\n", "    g.since[0] = g.since[0]\n",
             "a tangent carried by phases forgets where it was last carried: every phase's "
             "e^{JΔt} spans the run from its start, not the phase",
             (EXPONENTIAL, *SHOOTING_EXPONENTIAL)),
    Mutation("stage-slopes-of-the-last-stage", "tangent",
             "    kept, forces = g.stage_forces[slot], g.work\n",
             "    kept, forces = g.stage_forces[DP_STAGES - 1], g.work\n",
             "the tangent's slopes at every kept stage of a step are read from the forces at "
             "the step's end: the step's derivative is off wherever the slopes vary",
             (STIFFENING, SLIP_REVERSAL)),
    Mutation("stage-stretch-rate-left-zero", "tangent",
             "                g.acceleration[k] = w.stage_v[j, k]\n",
             "                g.acceleration[k] = w.stage_a[j, k]\n",
             "a kept stage's stretch rate is read from its acceleration slot, which the "
             "sliders' first-order stage has zeroed: the slipping direction's turn is lost",
             (ELASTIC_TANGENT,)),
    # ---- orbits: matrix-free shooting (GMRES and Arnoldi on products) ----------------------
    Mutation("gmres-right-side-unscaled", "orbits",
             "    right[0] = beta\n", "    right[0] = 1.0\n",
             "GMRES's small least-squares problem forgets ‖b‖: its x is off by that factor, "
             "and the residual it reports is not the system's", KRYLOV),
    Mutation("arnoldi-step-adds-the-projection", "orbits",
             "            w = w - overlap * basis[:, j]",
             "            w = w + overlap * basis[:, j]",
             "the Arnoldi step adds the new product's projections on the basis instead of "
             "taking them out: the basis is not orthogonal, the Ritz values not eigenvalues",
             KRYLOV + (SHOOTING_KRYLOV,)),
    Mutation("neutral-offsets-left-free", "continuation",
             "            if _independent(rows, row):",
             "            if False and _independent(rows, row):",
             "a contact stuck through the whole orbit is not pinned: its offset's family "
             "makes Φ − I singular, and a branch from the stuck range turns at spurious folds",
             (NEUTRAL, NEUTRAL_CHAIN)),
    # ---- orbits: Newton's step (M − I) Δy = −(φ(y) − y) ----------------------------------
    Mutation("orbit-end-relaxes-the-sliders", "orbits",
             "end = np.concatenate([run.output.x[-1], run.output.v[-1], done.stretches[-1]])",
             "end = np.concatenate([run.output.x[-1], run.output.v[-1], "
             "0.0 * done.stretches[-1]])",
             "the map's end drops the elastic contacts' stretches: Newton seeks an orbit "
             "whose springs relax every period", (ELASTIC_ORBIT,)),
    Mutation("newton-without-monodromy", "orbits",
             "matrix = weights[:, None] * (linear.columns - np.eye(size)) / weights[None, :]",
             "matrix = weights[:, None] * (0.0 * linear.columns - np.eye(size)) "
             "/ weights[None, :]",
             "Newton's step is y ← φ(y), the plain iteration of the map, which finds only "
             "stable orbits, and those slowly", (LINEAR_NEWTON, UNSTABLE_ORBIT)),
    Mutation("newton-monodromy-transposed", "orbits",
             "matrix = weights[:, None] * (linear.columns - np.eye(size)) / weights[None, :]",
             "matrix = weights[:, None] * (linear.columns.T - np.eye(size)) "
             "/ weights[None, :]",
             "Newton's step solves with Mᵀ − I: the multipliers are right, the step is not",
             (LINEAR_NEWTON, UNSTABLE_ORBIT)),
    # ---- orbits: the extremes where the velocity crosses zero ----------------------------
    Mutation("extreme-without-its-vertex", "orbits",
             "            value -= slope * slope / (2.0 * curvature)\n        return value, "
             "float(time)",
             "            value -= 0.0\n        return value, float(time)",
             "a smooth extremum is read at the interpolated time, not at the vertex of the "
             "parabola through the state there", (EXTREMES,)),
    Mutation("extreme-at-a-switch-taken-smooth", "orbits",
             "    if not _has_switch(t, k, switches):\n        h = t[k + 1] - t[k]",
             "    if True:\n        h = t[k + 1] - t[k]",
             "an extremum at a switch (a friction force reversing) is read off the parabola "
             "of one side", (EXTREMES,)),
    Mutation("extreme-bracket-left-wide", "orbits",
             "ROOT_WIDTH = 1e-7", "ROOT_WIDTH = 1e-2",
             "the zero of the rate at a switch is bracketed to a hundredth of a period: the "
             "extremum is read 10⁻³ low", (EXTREMES,)),
    Mutation("sweep-peak-at-samples", "orbits",
             "                peaks[j] = max(peaks[j], found[0][1])",
             "                peaks[j] = max(peaks[j], 0.0)",
             "a sweep point's peak is its largest sample, up to 1 − cos(π/50) = 2e-3 low",
             ("tests/test_orbits.py::"
              "test_sweeps_and_branches_give_every_blades_peak_and_the_worst_blade",)),
    Mutation("harmonic-phase-of-a-cosine", "orbits",
             "phases = np.concatenate([[0.0], np.angle(2j * spectrum[1:])])",
             "phases = np.concatenate([[0.0], np.angle(2.0 * spectrum[1:])])",
             "the harmonics' phases are a cosine's, a quarter turn from the excitation's "
             "sines", (CYCLE,)),
    Mutation("equivalent-damping-over-2-pi", "orbits",
             "return energy.dissipated / (4.0 * math.pi * kinetic) if kinetic > 0.0 else 0.0",
             "return energy.dissipated / (2.0 * math.pi * kinetic) if kinetic > 0.0 else 0.0",
             "ζ_eq divides the loss by 2π T_max: twice the damping a linear oscillator "
             "needs", (CYCLE,)),
    Mutation("kinetic-peak-sampled", "orbits",
             "    if state_at is None:\n        return float(top)",
             "    if True:\n        return float(top)",
             "T_max is read off the samples' parabola, not the orbit's exact states",
             (CYCLE,)),
    Mutation("cyclic-monodromy-unshifted", "orbits",
             "return self.shifted(power, self.steps * self.repeats)", "return power",
             "a symmetric orbit's monodromy leaves out the shift S^{kN/g} the reduced maps "
             "add up to over a period",
             ("tests/test_cyclic.py",)),
    Mutation("cyclic-shift-backwards", "orbits",
             "                                            done.stretches[-1]]), -symmetry.steps)",
             "                                            done.stretches[-1]]), symmetry.steps)",
             "the reduced map shifts the state one way and its Jacobian the other",
             ("tests/test_cyclic.py",)),
    Mutation("repeating-velocities-misread", "orbits",
             "np.concatenate([np.arange(m), n + np.arange(m), 2 * n + stretches])",
             "np.concatenate([np.arange(m), m + np.arange(m), 2 * n + stretches])",
             "Newton's map on the repeating states reads the second sector's displacements "
             "for the first one's velocities",
             ("tests/test_cyclic.py",)),
    Mutation("second-friction-from-the-first-stretch", "ledger",
             "force[:, elastic] = stiffness[elastic] * stretches[:, 1::2]",
             "force[:, elastic] = stiffness[elastic] * stretches[:, 0::2]",
             "the friction along t₂ of a face is read off the spring's stretch along t₁",
             ("tests/test_elastic_engine.py",)),
    Mutation("whole-tangent-moved-the-wrong-way", "orbits",
             "moved = symmetry.shifted(block, -c * symmetry.repeats)",
             "moved = symmetry.shifted(block, c * symmetry.repeats)",
             "the first N/g sectors' tangent columns are moved round the ring the wrong way "
             "to stand for the others'",
             ("tests/test_cyclic.py",)),
    Mutation("orbit-state-unshifted", "orbits",
             "index = symmetry.positions(turns * symmetry.steps)",
             "index = symmetry.positions(0)",
             "the symmetric orbit's state at t = iτ + s is taken as its state at s, not "
             "moved on i sectors",
             ("tests/test_cyclic.py",)),
    # ---- continuation: the test functions of the smooth bifurcations ---------------------
    Mutation("kinks-not-crossed", "continuation",
             "                if sigma < KINK_STEP and crossing:",
             "                if sigma < KINK_STEP and crossing and False:",
             "where arclength steps stall at a kink, the branch ends there", (KINKS,)),
    Mutation("noise-floor-ignored", "continuation",
             "            stalled = NOISE_FLOOR * self.tolerance >= size > last / 2.0",
             "            stalled = False",
             "a corrector whose residual stalls at the map's integration noise, a few times "
             "the tolerance, never converges: the branch stops there", (KINKS,)),
    Mutation("kink-tangent-by-the-secant", "continuation",
             "        return new.with_tangent(tangent if tangent[-1] * direction >= 0.0 "
             "else -tangent)",
             "        return new.with_tangent(tangent)",
             "past a kink the branch's tangent follows the secant, which the orbit's jump "
             "may point back along the branch", (KINKS,)),
    Mutation("fold-test-on-a-state-component", "continuation",
             "    fold = a.tangent[-1] * b.tangent[-1] < 0.0",
             "    fold = a.tangent[0] * b.tangent[0] < 0.0",
             "a fold is looked for where a displacement, not the parameter, turns back",
             (FOLDS,)),
    Mutation("period-doubling-test-on-positive-multipliers", "continuation",
             "multipliers, lambda mu: _real(mu) & (mu.real < 0.0), min(doubling_a, doubling_b))",
             "multipliers, lambda mu: _real(mu) & (mu.real > 0.0), min(doubling_a, doubling_b))",
             "a period doubling is located on the real positive multipliers, among which "
             "none crosses −1", (DOUBLING,)),
    Mutation("torus-test-plus-one", "continuation",
             "return float(moduli[rank]) - 1.0 if rank < len(moduli) else -1.0",
             "return float(moduli[rank]) + 1.0 if rank < len(moduli) else -1.0",
             "a multiplier's crossing is located on |μ| + 1, which never vanishes",
             (TORUS,)),
    Mutation("torus-test-wrong-rank", "continuation",
             "~_real(mu) & (mu.imag > 0.0), min(torus_a, torus_b) // 2)",
             "~_real(mu) & (mu.imag > 0.0), max(torus_a, torus_b) // 2)",
             "a torus bifurcation is located on the pair inside the circle at both ends, "
             "not on the one that crossed", (TORUS,)),
    Mutation("symmetry-breaking-test-at-minus-one", "continuation",
             "multipliers, lambda mu: _real(mu) & (mu.real > 0.0), min(rising_a, rising_b))",
             "multipliers, lambda mu: _real(mu) & (mu.real < 0.0), min(rising_a, rising_b))",
             "a symmetry-breaking bifurcation is sought among the real negative multipliers, "
             "the period doubling's, not the positive ones",
             ("tests/test_cyclic.py",)),
    # ---- constraints: stick of substructures, λ = (G M⁻¹ Gᵀ)⁺ G M⁻¹ R ------------------
    Mutation("constraint-gram-without-inverse-mass", "constraints",
             "                value += rows[ea, i] * rows[eb, i] / s.mass[i]",
             "                value += rows[ea, i] * rows[eb, i]",
             "the constraint solve takes G Gᵀ for G M⁻¹ Gᵀ: the static friction of stuck "
             "substructures is wrong wherever the coordinates' masses differ from 1",
             (ONE_DOF, MULTI_DOF_MONODROMY)),
    Mutation("constraint-force-sign", "constraints",
             "            acceleration[i] -= rows[e, i] * value",
             "            acceleration[i] += rows[e, i] * value",
             "the multipliers push the coordinates the wrong way: stuck interfaces slide",
             (ONE_DOF,)),
    Mutation("constraint-projection-by-velocity", "constraints",
             "            weight = s.mass[i] if i < free else 1.0",
             "            weight = 1.0",
             "velocities are projected onto the constraints Euclidean-orthogonally, not "
             "M-orthogonally: stick onset does not conserve momentum (one-degree-of-"
             "freedom coordinates have mass 1, where the two are one)", (BEAMS,)),
    Mutation("structure-breakaway-gradient-sign", "constraints",
             "        g.guard_normal[r] = s.static_mu[e] * normal_change - sign * change",
             "        g.guard_normal[r] = s.static_mu[e] * normal_change + sign * change",
             "the breakaway guard's gradient of a stuck substructure interface takes +|λ|",
             (MULTI_DOF_DROPPING,)),
    Mutation("slip-rows-right-node-sign", "ledger",
             "                rows[e, j] -= weight[e]",
             "                rows[e, j] += weight[e]",
             "a blade interface's rows add its right node's motion: its slip displacement "
             "is not the relative one, the hysteresis loop's area not the friction loss",
             (HYSTERESIS,)),
    # ---- linear: the forced response in the open and stuck limits ------------------------
    Mutation("response-damping-sign", "linear",
             "dynamic = stiffness - omega * omega * mass + 1j * omega * damping",
             "dynamic = stiffness - omega * omega * mass - 1j * omega * damping",
             "the damping force leads the motion: every phase is mirrored", (LINEAR_RESPONSE,)),
    Mutation("response-phase-conjugated", "linear",
             "np.exp(1j * a.harmonic_phases[1, :n])", "np.exp(-1j * a.harmonic_phases[1, :n])",
             "the blades are forced with their phases' opposites: a forward engine-order "
             "wave travels backward", (LINEAR_RESPONSE,)),
    Mutation("stuck-contact-dashpot-dropped", "linear",
             "        dashpots += dashpot * np.outer(normal, normal)",
             "        dashpots += 0.0 * np.outer(normal, normal)",
             "the stuck limit leaves out the contacts' dashpots, which act along the normal "
             "that stick leaves free", (LINEAR_RESPONSE,)),
    Mutation("response-load-not-projected", "linear",
             "load = basis.T @ forcing", "load = forcing[:basis.shape[1]]",
             "the stuck limit takes the first coordinates' forces, not each constrained "
             "motion's work", (LINEAR_RESPONSE,)),
    Mutation("elastic-stick-second-tangent-dropped", "linear",
             "            for rows in (a.tangent_rows, a.second_tangent_rows):",
             "            for rows in (a.tangent_rows,):",
             "a stuck elastic contact holds along t₁ only: the face's plane slides free "
             "along t₂", (ELASTIC,)),
    Mutation("elastic-stick-of-blades-cos-once", "linear",
             "tangential = np.where(elastic, a.tangential_stiffness, 0.0) * a.cos_angle ** 2",
             "tangential = np.where(elastic, a.tangential_stiffness, 0.0) * a.cos_angle",
             "a blade pair's elastic contact pushes along x by k_t cos α: the tangential "
             "spring is projected once, not twice", (ELASTIC,)),
    # ---- patches, frames, FE sectors, frequency excitation ----------------------------
    Mutation("patch-pairs-all-first", "model",
             "    return tuple(zip(*(point if isinstance(point, tuple) else (point,) * size\n",
             "    return tuple(zip(*(point[:1] * size if isinstance(point, tuple)\n"
             "                       else (point,) * size\n",
             "every pair of a patch is lowered from its first pair's points",
             (PATCH_REFERENCE,)),
    Mutation("patch-stiffness-of-the-first-contact-only", "model",
             "    laws_of = [interfaces[contact.interface][2] for contact in contacts]",
             "    laws_of = [interfaces[contact.interface][2] for contact in contacts]\n"
             "    contacts = [c for c in contacts if c.contact == 0] + [c for c in contacts\n"
             "                                                         if c.contact != 0]",
             "a patch's contacts are lowered out of their order: the rows of one pair go "
             "with the laws and readings of another", (PATCHES,)),
    Mutation("patch-reader-first-contact", "model",
             "        return first + check_int(owner, \"contact\", k, low=0, high=pairs - 1)",
             "        return first + 0 * check_int(owner, \"contact\", k, low=0, high=pairs - 1)",
             "a reader given (interface, k) reads the patch's first contact whatever k",
             (PATCHES,)),
    Mutation("ring-faces-swapped", "model",
             "        edges = [(at[s][1], at[(s + 1) % len(at)][0]) for s in range(len(pairs))]",
             "        edges = [(at[s][0], at[(s + 1) % len(at)][1]) for s in range(len(pairs))]",
             "the builders join a blade's left face to the next blade's right face",
             (FRAMES,)),
    Mutation("frame-turned-forward", "model",
             "    return turn[0].T @ turn[1]", "    return turn[0] @ turn[1]",
             "the right node's points are turned by Q_a Q_b, not into the left node's frame "
             "by Q_aᵀ Q_b", (FRAMES,)),
    Mutation("sector-stretches-not-moved", "orbits",
             "            stretches = self.stretch_image[stretches]",
             "            stretches = stretches",
             "the symmetry moves each sector's coordinates, but leaves the elastic "
             "contacts' stretches where they were", (CYCLIC_SECTORS,)),
    Mutation("sector-frame-turned-twice", "model",
             "                    sector_frame(2.0 * math.pi * s / turns, components), body)",
             "                    sector_frame(4.0 * math.pi * s / turns, components), body)",
             "the ring turns sector s by 4πs/N", (FRAMES,)),
    Mutation("frequency-ignored-by-the-forcing", "model",
             "            return 2.0 * math.pi * self.excitation.frequency\n",
             "            return self.excitation.engine_order * self.omega\n",
             "the forcing keeps l Ω while the period is 1/f", (FREQUENCY,)),
    Mutation("elastic-contact-stuck-rigidly", "linear",
             "    constraints = a.tangent_rows[a.can_stick & ~elastic, :n]",
             "    constraints = a.tangent_rows[a.can_stick, :n]",
             "an elastic contact is a constraint as well as its springs: stuck frequencies "
             "ignore k_t", (ELASTIC,)),
    # ---- harmonic: the contacts' forces in time, the condensation, Hill's matrix ---------
    Mutation("aft-slider-limit-1.2", "harmonic",
             "        elif size <= bound:  # stuck: the slider stays",
             "        elif size <= 1.2 * bound:  # stuck: the slider stays",
             "the slider holds 20 % beyond μ_s N before it slips: the series converge to "
             "another orbit than the exact one", (HARMONIC,)),
    Mutation("aft-open-contact-pushes", "harmonic",
             "closed = np.flatnonzero((penetration > 0.0) | (not contact.opens))",
             "closed = np.flatnonzero((penetration > -1.0) | (not contact.opens))",
             "an open contact's law is read at its negative penetration: the stop pulls the "
             "mass back", (HARMONIC,)),
    Mutation("aft-slider-load-rate-dropped", "harmonic",
             "                df[n, 0, p] = u0 * dlimit[n, p] + bound * d_direction[0, p]",
             "                df[n, 0, p] = bound * d_direction[0, p]",
             "a slipping slider's force is differentiated as if its limit μ_s N did not "
             "move with the normal load: the Jacobian is not the forces' derivative",
             (HARMONIC,)),
    Mutation("aft-reversal-at-the-last-sample", "harmonic",
             "    if s == 0.0 or s == 1.0:  # g turned back at t_{n−1}, or still rises at t_n",
             "    if s <= 1.0:  # g turned back at t_{n−1}, or still rises at t_n",
             "a slip that ends between samples stops the slider at the sample before: "
             "O(h²) of the motion, the accuracy stalls near 1e-5", (HARMONIC,)),
    Mutation("aft-regularised-slope-sign", "harmonic",
             "rate = slope * np.sign(speed) * smooth + mu * (1.0 - smooth * smooth) / \\",
             "rate = -slope * np.sign(speed) * smooth + mu * (1.0 - smooth * smooth) / \\",
             "the friction's derivative in the slip velocity takes μ' with the wrong sign",
             (HARMONIC,)),
    Mutation("condensation-damping-sign", "harmonic",
             "return model.stiffness - rate * rate * model.mass + 1j * rate * model.damping",
             "return model.stiffness - rate * rate * model.mass - 1j * rate * model.damping",
             "the dynamic compliance's damping leads the motion: every phase is mirrored",
             (HARMONIC,)),
    Mutation("condensation-jacobian-conjugated", "harmonic",
             "product = np.matmul(self.compliance, complex_amplitudes(columns))",
             "product = np.matmul(self.compliance.conj(), complex_amplitudes(columns))",
             "W applied to the Jacobian's columns conjugates each harmonic's compliance: "
             "Newton's Jacobian is not the balance's", (HARMONIC,)),
    Mutation("condensation-recovery-sign", "harmonic",
             "        response = self.to_load - np.einsum(",
             "        response = self.to_load + np.einsum(",
             "the full response is recovered with the contacts pulling where they push",
             (HARMONIC,)),
    Mutation("sector-lag-reversed", "harmonic",
             "        turns = np.exp(1j * lag * np.arange(n_sectors))",
             "        turns = np.exp(-1j * lag * np.arange(n_sectors))",
             "the neighbours' harmonics lag the wrong way round the ring: the sector answers "
             "the wave travelling backwards", (HARMONIC_SECTORS,)),
    Mutation("sector-forces-unconjugated", "harmonic",
             "np.column_stack([reading.conj().T, load[k]])",
             "np.column_stack([reading.T, load[k]])",
             "the other sectors' contacts push sector 0 with R_θᵀ, not R_θᴴ: the forces of "
             "the neighbours' contacts arrive with the lag of the reading, not against it",
             (HARMONIC_SECTORS,)),
    Mutation("sector-spread-first-only", "harmonic",
             "turns = np.exp(1j * np.outer(self.lags, np.arange(self.sectors)))",
             "turns = np.ones((len(self.lags), self.sectors))",
             "every sector repeats sector 0 in phase: the ring's series is a standing copy, "
             "not the travelling wave", (HARMONIC_SECTORS,)),
    Mutation("sector-samples-not-on-the-lag", "harmonic",
             "    return -(-samples // step) * step",
             "    return samples",
             "the time samples are not moved onto samples by the lag: the sector's forces "
             "alias differently from the whole ring's, its orbit off by the aliasing",
             (HARMONIC_SECTORS,)),
    Mutation("patch-reading-scaled", "harmonic",
             "    return values[:, None] * right, left",
             "    return values[:, None] * right, left * values",
             "the patch's contact coordinates are read from its directions with their "
             "singular values twice: z is not G η", (HARMONIC_PATCHES,)),
    Mutation("patch-jacobian-one-side", "harmonic",
             "        left = local.reshape(count * rho, r).T @ right.reshape(count * rho, -1)",
             "        left = np.eye(rho, r).T @ right.reshape(count, rho, -1).sum(axis=0)",
             "the forces' Jacobian is taken to the directions on its columns alone: Newton's "
             "matrix is not the derivative of the balance on the directions",
             (HARMONIC_PATCHES,)),
    Mutation("hill-velocity-coupling-once", "harmonic",
             "second = (np.kron(identity, model.damping) + 2.0 * np.kron(derivative, model.mass)",
             "second = (np.kron(identity, model.damping) + 1.0 * np.kron(derivative, model.mass)",
             "Hill's λ-term takes ṗ once, not 2λṗ: the exponents are not the Floquet ones",
             (HARMONIC,)),
    Mutation("hill-contacts-left-out", "harmonic",
             "             + rows.T @ contact_jacobian @ rows)",
             "             + 0.0 * rows.T @ contact_jacobian @ rows)",
             "Hill's matrix leaves out the contacts' stiffness: the multipliers are the open "
             "structure's", (HARMONIC,)),
)


class NotPlanted(Exception):
    """A mutation's text is not once in exactly one source file."""


def locate(mutation: Mutation, tree: Path) -> Path:
    """The one file under ``SOURCE_FOLDERS`` of ``tree`` that holds ``mutation.old``,
    where it occurs once; else ``NotPlanted`` saying where it is (or that it is nowhere)."""
    holders = {}
    for folder in SOURCE_FOLDERS:
        for path in sorted((tree / folder).rglob("*.py")):
            count = path.read_text().count(mutation.old)
            if count:
                holders[path] = count
    if not holders:
        raise NotPlanted(f"its text is in no file under {', '.join(SOURCE_FOLDERS)}: the "
                         f"code it mutates changed; find the lines that now say the same")
    names = ", ".join(f"{path.relative_to(tree)} ({count}x)" for path, count in holders.items())
    if len(holders) > 1:
        raise NotPlanted(f"its text is in several files: {names}; give more of the line")
    (path, count), = holders.items()
    if count > 1:
        raise NotPlanted(f"its text is {count} times in {names}; give more of the line")
    return path


def where(mutation: Mutation, tree: Path) -> str:
    """``file:line`` of the mutation's text in ``tree`` (``locate`` must succeed)."""
    path = locate(mutation, tree)
    line = path.read_text().split(mutation.old)[0].count("\n") + 1
    return f"{path.relative_to(tree)}:{line}"


def plant(mutation: Mutation, tree: Path) -> None:
    """Apply ``mutation`` to ``tree``; ``NotPlanted`` when its text is not where it must be."""
    if mutation is CONTROL:
        return
    path = locate(mutation, tree)
    path.write_text(path.read_text().replace(mutation.old, mutation.new))


def missing_tests(mutation: Mutation, tree: Path) -> list[str]:
    """The tests ``mutation`` names that ``tree`` lacks: a file that is not there, a node
    id whose test function the file does not define, or whose parameters it never names."""
    missing = []
    for test in mutation.tests:
        file, _, node = test.partition("::")
        path = tree / file
        function, _, case = node.partition("[")
        text = path.read_text() if path.is_file() else ""
        if not text or (function and not re.search(rf"^def {re.escape(function)}\(", text,
                                                    flags=re.MULTILINE)) \
                or case.removesuffix("]") not in text:
            missing.append(test)
    return missing


def problems(mutations, tree: Path, every_layer: bool) -> dict[str, str]:
    """By mutation name (or "layers"), what stops a mutation from meaning anything."""
    found = {}
    for m in mutations:
        reasons = []
        if m.layer not in LAYERS:
            reasons.append(f"layer {m.layer!r} is not one of {', '.join(LAYERS)}")
        if m.old == m.new:
            reasons.append("it changes nothing")
        try:
            locate(m, tree)
        except NotPlanted as error:
            reasons.append(f"cannot be planted: {error}")
        missing = missing_tests(m, tree)
        if missing:
            reasons.append(f"its tests are not there: {', '.join(missing)}")
        if reasons:
            found[m.name] = "; ".join(reasons)
    names = [m.name for m in mutations]
    for name in sorted({n for n in names if names.count(n) > 1}):
        found[name] = "the name is given to several mutations"
    uncovered = [layer for layer in LAYERS if every_layer
                 and not any(m.layer == layer for m in mutations)]
    if uncovered:
        found["layers"] = f"no mutation reaches {', '.join(uncovered)}"
    return found


def check(mutations, tree: Path, every_layer: bool) -> int:
    """Print where each mutation plants, or why it cannot; 0 when all is well, else 1."""
    found = problems(mutations, tree, every_layer)
    for m in mutations:
        place = "-" if m.name in found else where(m, tree)
        verdict = found.get(m.name, "plants")
        print(f"{m.name:44s} {m.layer:12s} {place:40s} {verdict}")
    if "layers" in found:
        print(found["layers"])
    counts = ", ".join(f"{layer} {sum(m.layer == layer for m in mutations)}"
                       for layer in LAYERS)
    print(f"{len(mutations)} mutations by layer: {counts}")
    if found:
        print(f"{len(found)} problem(s): fix them before any run means anything")
        return 1
    return 0


def _copy_tree(source: Path, target: Path) -> None:
    """The files git tracks, plus untracked ones it does not ignore, as they are now."""
    listed = subprocess.run(["git", "ls-files", "-co", "--exclude-standard", "-z"],
                            cwd=source, check=True, capture_output=True).stdout
    for name in filter(None, listed.decode().split("\0")):
        origin = source / name
        if origin.is_file():
            (target / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(origin, target / name)


#: No change at all: the tests must pass on the copy, or no verdict below means anything.
CONTROL = Mutation("control", "", "", "", "the unchanged source")


def run(mutation: Mutation, source: Path, tests, limit: float, cache: Path) -> tuple[str, str]:
    """(verdict, the first failing test or a note) for one mutation."""
    with tempfile.TemporaryDirectory(prefix="shroudnet-mutant-") as folder:
        tree = Path(folder)
        _copy_tree(source, tree)
        try:
            plant(mutation, tree)
        except NotPlanted as error:
            return "not planted", str(error)
        environment = {**os.environ, "PYTHONPATH": str(tree), "SHROUDNET_CACHE": str(cache),
                       "PYTHONDONTWRITEBYTECODE": "1"}
        command = [sys.executable, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider",
                   "-o", "addopts=", "-o", f"timeout={int(limit)}", *tests]
        try:
            done = subprocess.run(command, cwd=tree, env=environment, capture_output=True,
                                  text=True, timeout=limit)
        except subprocess.TimeoutExpired:
            return "hung", f"tests still running after {limit:.0f} s"
    if done.returncode == 0:
        return "survived", ""
    failed = [line for line in done.stdout.splitlines() if line.startswith("FAILED")]
    return "killed", failed[0].removeprefix("FAILED ") if failed else done.stdout[-300:]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("words", nargs="*",
                        help="run the mutations whose name or layer holds a word")
    parser.add_argument("--list", action="store_true", help="list the mutations and stop")
    parser.add_argument("--check", action="store_true",
                        help="check that every mutation plants and its tests exist; run none")
    parser.add_argument("--source", type=Path, default=ROOT,
                        help="the tree to plant into (default: this checkout)")
    parser.add_argument("--limit", type=float, default=900.0,
                        help="seconds the tests of one mutation may take (default 900)")
    parser.add_argument("--no-control", action="store_true",
                        help="skip the first run on the unchanged source")
    parser.add_argument("--tests", nargs="+", metavar="TEST",
                        help="run these tests (paths or node ids) against every chosen "
                             "mutation instead of its own")
    args = parser.parse_args(argv)
    source = args.source.resolve()
    chosen = [m for m in MUTATIONS
              if not args.words or any(w in m.name or w == m.layer for w in args.words)]
    if args.tests:
        chosen = [replace(m, tests=tuple(args.tests)) for m in chosen]
    if not chosen:
        print(f"no mutation's name or layer holds {' or '.join(args.words)} (see --list)")
        return 2
    if args.list:
        for m in chosen:
            print(f"{m.name:44s} {m.layer:12s} {m.why}")
        return 0
    if args.check:
        return check(chosen, source, every_layer=not args.words)
    found = problems(chosen, source, every_layer=False)
    if found:
        for name, reason in found.items():
            print(f"{name}: {reason}")
        print(f"{len(found)} of {len(chosen)} mutations cannot mean anything as they stand; "
              f"nothing was run (python tests/mutations.py --check lists them all)")
        return 2
    cache = Path(os.environ.get("SHROUDNET_MUTATION_CACHE")
                 or Path.home() / ".cache" / "shroudnet-mutations")
    if not args.no_control:
        tests = list(dict.fromkeys(t for m in chosen for t in m.tests))
        began = time.perf_counter()
        verdict, note = run(CONTROL, source, tests, args.limit, cache)
        if verdict != "survived":
            print(f"the tests fail on the unchanged source ({verdict}: {note}); fix that first")
            return 2
        print(f"control: the unchanged source passes ({time.perf_counter() - began:.0f} s)",
              flush=True)
    verdicts = []
    for m in chosen:
        began = time.perf_counter()
        verdict, note = run(m, source, m.tests, args.limit, cache)
        verdicts.append(verdict)
        print(f"{m.name:44s} {verdict:11s} {time.perf_counter() - began:6.0f} s  {note}",
              flush=True)
    survivors = sum(v in ("survived", "hung") for v in verdicts)
    unplanted = verdicts.count("not planted")
    print(f"{survivors} of {len(chosen)} mutations survived or hung"
          + (f"; {unplanted} could not be planted, so this run proves less than it "
             f"lists" if unplanted else ""))
    return 1 if survivors or unplanted else 0


if __name__ == "__main__":
    sys.exit(main())
