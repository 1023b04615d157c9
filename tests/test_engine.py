"""The engine's parts that do not depend on the laws, and the kernel generator."""

import functools
import importlib
import math
import os
import re
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numba import njit
from scipy.integrate._ivp.rk import RK45

from contact_laws import (
    ConstantLoad,
    Coulomb,
    ExponentialFriction,
    Hertz,
    LinearSpring,
    NormalLaw,
    Regularised,
    Stribeck,
    check_real,
)
from shroudnet import Mode, Simulation, atomic, simulate
from shroudnet.engine import cache, codes, generate, locate, tableau
from shroudnet.engine.cache import cache_size, clear_cache
from shroudnet.engine.clusters import cluster_labels
from shroudnet.engine.detect import crossed, depth, parabola_low, predicted_low
from shroudnet.engine.records import new_switching
from shroudnet.engine.regroup import fill_groups, static_friction_operator
from shroudnet.scenes import block_on_belt as belt
from shroudnet.scenes import three_blade_paper
from tests.laws import CubicSpring

# ---- the Runge–Kutta tableau --------------------------------------------------------------


def test_the_dormand_prince_tableau_is_scipys_rk45():
    """Checked against scipy's own coefficients, typed in independently."""
    t = tableau.DORMAND_PRINCE
    assert np.array_equal(t.c, RK45.C)
    assert np.array_equal(t.a, RK45.A)
    assert np.array_equal(t.b[:-1], RK45.B) and t.b[-1] == 0.0
    assert np.array_equal(t.e, RK45.E)
    assert np.array_equal(t.p, RK45.P)


@pytest.mark.parametrize("field, where", [("a", (3, 1)), ("b", 2), ("e", 0), ("p", (4, 2)),
                                          ("c", 2)])
def test_a_mistyped_coefficient_fails_the_tableaus_check(field, where):
    broken = getattr(tableau.DORMAND_PRINCE, field).copy()
    broken[where] *= 1.0 + 1e-9
    with pytest.raises(ValueError, match="Runge–Kutta tableau"):
        tableau.DORMAND_PRINCE._replace(**{field: broken}).check()


# ---- codes, defined once -------------------------------------------------------------------

def test_the_compiled_codes_are_the_enums():
    assert (codes.OPEN, codes.STICK, codes.SLIP_POSITIVE, codes.SLIP_NEGATIVE) == tuple(Mode)
    assert (codes.CLOSING, codes.SEPARATION, codes.STICKING, codes.REVERSAL,
            codes.BREAKAWAY) == tuple(codes.EventKind)
    assert codes.N_WORK == len(codes.WorkColumn) and codes.N_POWERS == codes.PROJECTION
    assert codes.FINISHED == codes.Status.FINISHED == 0


def test_every_stopping_status_has_a_message_naming_time_and_place():
    for status in codes.Status:
        text = status.message("at t = 1 s", " on interface 0", zeno_events=200,
                              zeno_window=1e-4, smallest_step=1e-14)
        assert "at t = 1 s" in text and "on interface 0" in text and "{" not in text


def _relative_velocity(v, left, right):
    """u̇_e = ẋ_left − ẋ_right by sample, a fixed end (−1) standing still."""
    def at(ends):
        return np.where(ends >= 0, v[:, np.maximum(ends, 0)], 0.0)
    return at(left) - at(right)


def test_each_work_column_integrates_the_power_it_is_named_after():
    """Each column of ``Simulation.work`` against the trapezoidal integral of its power,
    computed here from the samples alone: Σ Q_i ẋ_i with Q_i(t) = q0 + Σ_n q_n sin(n lΩt +
    n φ_i), Σ c_i ẋ_i², Σ f_e u̇_e cos α_e and Σ N_e u̇_e sin α_e; the kinetic energy
    removed at stick onsets is the last column. Impacts and slip on both shrouds: every
    power is at work."""
    scene = three_blade_paper()
    began = time.perf_counter()
    sim = simulate(scene, 2, samples_per_period=2000)
    wall = time.perf_counter() - began
    a = scene.arrays
    t, v = sim.t, sim.v
    amplitudes, phases = a.harmonic_amplitudes, a.harmonic_phases
    q = amplitudes[0] + sum(amplitudes[n] * np.sin(n * a.excitation_frequency * t[:, None]
                                                   + phases[n])
                            for n in range(1, len(amplitudes)))
    relative = _relative_velocity(v, a.left, a.right)
    powers = {
        codes.WorkColumn.EXCITATION: np.sum(q * v, axis=1),
        codes.WorkColumn.DAMPING: np.sum(a.damping * v * v, axis=1),
        codes.WorkColumn.FRICTION: np.sum(sim.friction_force * relative * a.cos_angle, axis=1),
        codes.WorkColumn.CONTACT: np.sum(sim.normal_force * relative * a.sin_angle, axis=1),
    }
    for column, power in powers.items():
        integral = np.concatenate([[0.0], np.cumsum(0.5 * (power[1:] + power[:-1])
                                                    * np.diff(t))])
        assert np.abs(integral).max() > 0.0, column.name
        np.testing.assert_allclose(sim.work[:, column] - sim.work[0, column], integral,
                                   atol=1e-5 * np.abs(integral).max(), err_msg=column.name)
    # no blade sticks here: what the velocity projections remove is rounding
    assert sim.events.counts["sticking"] == 0
    assert np.abs(sim.work[:, codes.WorkColumn.PROJECTION]).max() \
        <= 1e-12 * sim.work[-1, codes.WorkColumn.EXCITATION]
    assert sim.work.shape[1] == len(powers) + 1
    assert isinstance(sim, Simulation) and 0.0 <= sim.compile_seconds <= wall


# ---- detect and locate --------------------------------------------------------------------

@given(before=st.floats(-1.0, 1.0), after=st.floats(-1.0, 1.0))
def test_a_guard_is_past_its_crossing_exactly_when_its_depth_is_negative(before, after):
    assert (depth(before, after) < 0.0) == crossed(before, after)


@given(a=st.floats(-1.0, 1.0), b=st.floats(-1.0, 1.0), c=st.floats(-1.0, 1.0))
def test_the_parabolas_low_point_is_the_lowest_on_a_fine_grid(a, b, c):
    s = np.linspace(-1.0, 1.0, 2001)
    values = b + 0.5 * (c - a) * s + 0.5 * (a - 2.0 * b + c) * s * s
    offset, value = parabola_low(a, b, c)
    assert value <= values.min() + 1e-12
    assert value == pytest.approx(b + 0.5 * (c - a) * offset
                                  + 0.5 * (a - 2.0 * b + c) * offset ** 2, abs=1e-12)


def test_the_predicted_low_of_samples_of_a_parabola_is_its_vertex():
    theta = np.linspace(0.0, 1.0, 5)
    at, value = predicted_low(tuple((theta - 0.6) ** 2 - 0.01))
    assert at == pytest.approx(0.6) and value == pytest.approx(-0.01)


def _illinois(function, width):
    """Locate the root of ``function`` on (0, 1] the way the kernel's locate does."""
    lo, f_lo, hi, f_hi, side = 0.0, function(0.0), 1.0, function(1.0), 0
    previous, slow, evaluations = hi, 0, 0
    while hi - lo > width:
        trial, slow = locate.next_trial(lo, f_lo, hi, f_hi, width, previous, slow)
        previous = hi - lo
        evaluations += 1
        lo, f_lo, hi, f_hi, side = locate.narrow(lo, f_lo, hi, f_hi, trial,
                                                         function(trial), side)
    return lo, hi, evaluations


@pytest.mark.parametrize("root", [1e-7, 0.013, 0.37, 0.5, 0.9, 1.0 - 1e-9])
@pytest.mark.parametrize("shape", ["linear", "convex", "concave", "sine"])
def test_illinois_brackets_the_root_to_the_width_in_far_fewer_evaluations_than_bisection(
        root, shape):
    g = {"linear": lambda x: root - x,
         "convex": lambda x: math.exp(-3.0 * x) - math.exp(-3.0 * root),
         "concave": lambda x: root ** 0.5 - x ** 0.5,
         "sine": lambda x: math.sin(3.0 * (root - x))}[shape]
    width = 1e-10
    lo, hi, evaluations = _illinois(g, width)
    assert g(lo) >= 0.0 > g(hi) and hi - lo <= width and abs(lo - root) < 2 * width
    assert evaluations <= 12  # bisection: log2(1/width) = 34


def test_a_root_where_the_guard_is_flat_takes_little_more_than_bisection():
    """(1 − x)³ − (1 − r)³ with r → 1: a near-triple root, where secants crawl."""
    root = 1.0 - 1e-9
    lo, hi, evaluations = _illinois(lambda x: (1.0 - x) ** 3 - (1.0 - root) ** 3, 1e-10)
    assert lo <= root <= hi
    assert evaluations <= math.ceil(math.log2(1e10)) + locate.SLOW_NARROWING


@pytest.mark.parametrize("root", [1e-7, 0.3, 0.9])
def test_a_kink_still_ends_in_a_bracket_by_halving(root):
    """A guard that is flat, then falls: the secant is poor, halving takes over after
    ``SLOW_NARROWING`` evaluations that fail to halve the bracket."""
    lo, hi, evaluations = _illinois(lambda x: 1.0 if x < root else root - x, 1e-10)
    assert lo <= root <= hi and hi - lo <= 1e-10
    assert evaluations <= math.ceil(math.log2(1e10)) + locate.SLOW_NARROWING


# ---- regroup: static friction without LAPACK ------------------------------------------------

def _incidence(n_blades, left, right, cos_angle, stuck):
    edges = np.flatnonzero(stuck)
    g = np.zeros((n_blades, len(edges)))
    for k, e in enumerate(edges):
        if left[e] >= 0:
            g[left[e], k] += cos_angle[e]
        if right[e] >= 0:
            g[right[e], k] -= cos_angle[e]
    return g


@settings(max_examples=150, deadline=None)
@given(data=st.data())
def test_the_static_friction_operator_is_the_pseudo_inverse_on_consistent_forces(data):
    """Trees (exact), cycles (minimum norm), grounded and free clusters: the closed form
    against numpy's pseudo-inverse, on imbalances a set of friction forces can balance."""
    n = data.draw(st.integers(1, 6))
    m = data.draw(st.integers(1, 9))
    ends = st.integers(-1, n - 1)
    left = np.array(data.draw(st.lists(ends, min_size=m, max_size=m)))
    right = np.array(data.draw(st.lists(ends, min_size=m, max_size=m)))
    keep = left != right
    left, right = left[keep], right[keep]
    if not len(left):
        return
    cos_angle = np.array(data.draw(st.lists(st.floats(0.2, 1.0), min_size=len(left),
                                            max_size=len(left))))
    stuck = np.array(data.draw(st.lists(st.booleans(), min_size=len(left),
                                        max_size=len(left))))
    labels, grounded, _ = cluster_labels(n, n, left, right, stuck)
    operator, stuck_interfaces = static_friction_operator(n, n, left, right, cos_angle, stuck,
                                                          labels, grounded)
    g = _incidence(n, left, right, cos_angle, stuck)
    assert np.array_equal(stuck_interfaces, np.flatnonzero(stuck))
    b = g @ np.array(data.draw(st.lists(st.floats(-1.0, 1.0), min_size=g.shape[1],
                                        max_size=g.shape[1])))
    assert np.allclose(operator @ b, np.linalg.pinv(g) @ b, atol=1e-10)


def _modes(stuck):
    return np.where(stuck, Mode.STICK, Mode.SLIP_POSITIVE).astype(np.int64)


@njit
def _regrouped_after(nodes, modes_before, modes):
    """Regroup ``modes`` into storage that held the grouping of ``modes_before``."""
    store = new_switching(len(nodes.mass), len(modes), len(nodes.mass))
    fill_groups(nodes, modes_before, store)
    n_clusters, n_stuck = fill_groups(nodes, modes, store)
    return (store.labels.copy(), store.grounded[:n_clusters].copy(),
            store.driver[:n_clusters].copy(), store.masses[:n_clusters].copy(),
            store.operator[:n_stuck].copy(), store.stuck_interfaces[:n_stuck].copy())


@settings(max_examples=100, deadline=None)
@given(data=st.data())
def test_regrouping_into_used_storage_gives_what_fresh_arrays_give(data):
    """A switch regroups into storage allocated once per run; whatever grouping it held
    before, the clusters, masses and static friction operator are those computed in fresh
    arrays, bit for bit. Blades, a prescribed-motion node, fixed ends, trees and cycles."""
    n_blades = data.draw(st.integers(1, 6))
    n_nodes = n_blades + data.draw(st.integers(0, 1))
    m = data.draw(st.integers(1, 9))
    ends = st.integers(-1, n_nodes - 1)
    left = np.array(data.draw(st.lists(ends, min_size=m, max_size=m)))
    right = np.array(data.draw(st.lists(ends, min_size=m, max_size=m)))
    keep = (left != right) & ((left >= 0) | (right >= 0))
    left, right = left[keep], right[keep]
    if not len(left):
        return
    m = len(left)
    # a kernel's scene with the fields regrouping reads replaced: the compiled code sees
    # the types it always sees (a type of the tests' own would enter the engine's cache)
    nodes = generate.kernel_scene(three_blade_paper())._replace(
        mass=np.array(data.draw(st.lists(st.floats(0.1, 10.0), min_size=n_nodes,
                                         max_size=n_nodes))),
        motion_amplitude=np.ones(n_nodes - n_blades), left=left, right=right,
        cos_angle=np.array(data.draw(st.lists(st.floats(0.2, 1.0), min_size=m, max_size=m))))
    stuck_sets = st.lists(st.booleans(), min_size=m, max_size=m)
    before, stuck = (np.array(data.draw(stuck_sets)) for _ in range(2))
    labels, grounded, driver = cluster_labels(n_nodes, n_blades, left, right, stuck)
    operator, stuck_interfaces = static_friction_operator(n_nodes, n_blades, left, right,
                                                          nodes.cos_angle, stuck, labels,
                                                          grounded)
    masses = np.zeros(len(grounded))
    np.add.at(masses, labels, nodes.mass)
    refilled = _regrouped_after(nodes, _modes(before), _modes(stuck))
    for got, fresh in zip(refilled, (labels, grounded, driver, masses, operator,
                                     stuck_interfaces), strict=True):
        assert np.array_equal(got, fresh)


# ---- the generator --------------------------------------------------------------------------

def _paper(alpha):
    return three_blade_paper(alpha=alpha)


def test_no_parameter_value_chooses_another_kernel():
    """α = π/2 exactly rules stick out on both interfaces; it used to compile a kernel of
    its own. The kernel now depends on the law classes only."""
    kernels = {generate.load_kernel(_paper(a)).__name__ for a in (math.pi / 2,
                                                                 math.pi / 2 - 1e-12, 0.3)}
    assert len(kernels) == 1


def test_the_effect_flags_follow_the_law_classes():
    arrays = three_blade_paper().arrays
    assert generate.flags(arrays) == {"HAS_CONTACT_EVENTS": True, "HAS_STICK": True,
                                      "HAS_FRICTION": True, "HAS_REGULARISED": False,
                                      "HAS_COUPLINGS": False, "HAS_PRESCRIBED": False,
                                      "HAS_STRUCTURES": False, "HAS_SLIDERS": False,
                                      "HAS_TANGENT": False}
    assert generate.flags(arrays, tangent=True)["HAS_TANGENT"]


def test_the_header_differences_a_law_that_gives_no_derivative():
    """A law without its own derivative is differentiated in the kernel by central
    differences with the steps ``contact_laws`` takes; one with it calls its own."""
    text = generate.header([LinearSpring, CubicSpring], [ExponentialFriction], {})
    assert "return _normal_derivative_0(penetration, rate, params[0])" in text
    assert "_normal_1(penetration + step, rate, params[0], params[1])" in text
    assert "_normal_1(penetration, rate - step, params[0], params[1])" in text
    assert "return _friction_derivative_0(slip_speed, params[0], params[1], params[2])" \
        in text
    compile(text, "header", "exec")


def test_the_header_dispatches_on_each_law_class_with_its_parameters():
    text = generate.header([LinearSpring], [ExponentialFriction], {"HAS_STICK": True})
    assert "HAS_STICK = True" in text
    assert "return _normal_0(penetration, rate, params[0])" in text
    assert "return _friction_0(slip_speed, params[0], params[1], params[2])" in text
    compile(text, "header", "exec")  # valid Python


_LAW_MODULE = '''
from dataclasses import dataclass
from contact_laws import NormalLaw
from lawhelper import spring

@dataclass(frozen=True)
class HelpedSpring(NormalLaw):
    stiffness: float

    @staticmethod
    def normal_force(penetration, rate, stiffness):
        return spring(penetration, stiffness)
'''


def test_a_change_in_a_laws_helper_module_gives_a_new_kernel(tmp_path, monkeypatch):
    """The cache key covers the modules a law's function reaches, not only its own text."""
    monkeypatch.setenv("SHROUDNET_CACHE", str(tmp_path / "cache"))
    monkeypatch.syspath_prepend(str(tmp_path))
    (tmp_path / "lawmodule.py").write_text(_LAW_MODULE)
    names = []
    for exponent in ("1.0", "1.5"):
        (tmp_path / "lawhelper.py").write_text(
            f"def spring(penetration, stiffness):\n"
            f"    return stiffness * max(penetration, 0.0) ** {exponent}\n")
        for module in ("lawhelper", "lawmodule"):
            sys.modules.pop(module, None)
        law = importlib.import_module("lawmodule").HelpedSpring(stiffness=3e5)
        names.append(generate.load_kernel(three_blade_paper(normal=law)).__name__)
        assert f"** {exponent}" in generate.law_sources(type(law), "normal")
    assert names[0] != names[1]


def test_the_cache_key_covers_every_module_the_phases_import():
    """A constant a phase module takes from another module is compiled into the kernel, so
    that module's source is part of the key."""
    phases, sources = generate.phase_sources()
    imported = re.findall(r"^from ([\w.]+) import", "\n".join(phases), flags=re.MULTILINE)
    ours = [name for name in imported if name.split(".")[0] in ("shroudnet", "contact_laws")]
    assert "contact_laws.base" in ours and "shroudnet.engine.controller" in ours
    for name in ours:
        assert Path(importlib.import_module(name).__file__).read_text() in sources, name


def test_every_combination_of_built_in_laws_shares_one_kernel():
    """A new combination of built-in laws, or a scene that rules effects out, compiles
    nothing; a law of the user's own gets a kernel of its own."""
    scenes = [three_blade_paper(), three_blade_paper(friction=None),
              three_blade_paper(normal=Hertz(stiffness=3e7), friction=Coulomb(mu=0.3)),
              three_blade_paper(normal=ConstantLoad(force=5.0),
                                friction=Regularised(law=Stribeck(mu_static=0.4,
                                                                  mu_kinetic=0.2,
                                                                  stribeck_velocity=0.01),
                                                     velocity=1e-3)),
              three_blade_paper(gap=1.0), belt()]
    kernels = {generate.load_kernel(scene).__name__ for scene in scenes}
    assert len(kernels) == 1
    shared = generate.load_kernel(scenes[0])
    assert shared.SHARED and shared.HAS_CONTACT_EVENTS and shared.HAS_REGULARISED
    assert not shared.HAS_TANGENT and generate.load_kernel(scenes[0], tangent=True).TANGENT
    own = generate.load_kernel(three_blade_paper(normal=CubicSpring(linear=1e5, cubic=1e13)))
    assert own.__name__ not in kernels and not own.SHARED and own.LAWS == ("CubicSpring",
                                                                          "ExponentialFriction")


@dataclass(frozen=True, kw_only=True)
class SquareSpring(NormalLaw):
    """A user's own normal law, written in this module and calling nothing: N = k δ²."""

    stiffness: float

    def __post_init__(self):
        check_real("SquareSpring", "stiffness", self.stiffness, low=0.0, low_open=True,
                   unit="N/m²")

    @staticmethod
    def normal_force(penetration, rate, stiffness):
        return stiffness * max(penetration, 0.0) ** 2


def test_a_user_law_without_a_helper_keeps_one_kernel():
    """A law class of the user's own gets a kernel of its own, one whatever the values of
    its parameters, and its key covers the one module the class is written in."""
    kernel, other = (generate.load_kernel(three_blade_paper(normal=SquareSpring(stiffness=k)))
                     for k in (1e9, 3e9))
    assert kernel.__name__ == other.__name__
    assert kernel.__name__ != generate.load_kernel(three_blade_paper()).__name__
    assert not kernel.SHARED and kernel.LAWS == ("SquareSpring", "ExponentialFriction")
    assert re.findall(r"^# (\S+)$", generate.law_sources(SquareSpring, "normal"),
                      flags=re.MULTILINE) == [__name__]


# ---- the cache ------------------------------------------------------------------------------

def test_the_cache_reports_its_size_and_clears(tmp_path, monkeypatch):
    monkeypatch.setenv("SHROUDNET_CACHE", str(tmp_path))
    monkeypatch.setattr("shroudnet.engine.cache._engine_files", lambda: [])
    (tmp_path / "kernel_x.py").write_text("x" * 1000)
    assert cache_size() == (1000, 1)
    assert clear_cache() == 1000
    assert cache_size() == (0, 0) and not tmp_path.exists()


@pytest.fixture
def fresh_kernels(monkeypatch):
    """Kernel builds that remember nothing of this process's kernels (and leave them be)."""
    monkeypatch.setattr(generate, "_kernel", functools.cache(generate._kernel.__wrapped__))
    monkeypatch.setattr(generate, "_method_free",
                        functools.cache(generate._method_free.__wrapped__))


@pytest.mark.parametrize("where, why", [
    (lambda f: f, "is a file, not a folder"),
    (lambda f: f / "kernels", "a_file is a file, not a folder"),
])
def test_a_cache_at_a_file_is_refused_before_any_kernel_is_built(
        tmp_path, monkeypatch, fresh_kernels, where, why):
    (tmp_path / "a_file").write_text("not a folder")
    folder = where(tmp_path / "a_file")
    monkeypatch.setenv("SHROUDNET_CACHE", str(folder))
    monkeypatch.setattr(generate, "_run_phases", _no_compile)
    with pytest.raises(ValueError, match=rf"^SHROUDNET_CACHE={re.escape(str(folder))}: "
                                         rf".*{why}; set SHROUDNET_CACHE to a folder"):
        simulate(three_blade_paper(), 1)


def test_a_cache_folder_that_cannot_be_written_is_refused(tmp_path, monkeypatch,
                                                          fresh_kernels):
    """(``os.access`` answers as for a user without the right: root writes anywhere.)"""
    monkeypatch.setenv("SHROUDNET_CACHE", str(tmp_path))
    monkeypatch.setattr(os, "access", lambda path, mode: False)
    monkeypatch.setattr(generate, "_run_phases", _no_compile)
    with pytest.raises(ValueError, match=rf"^SHROUDNET_CACHE={re.escape(str(tmp_path))}: "
                                         r"cannot write in .*\(permission denied\)"):
        simulate(three_blade_paper(), 1)
    with pytest.raises(ValueError, match="cannot write in"):
        cache_size()


def test_a_write_the_system_refuses_is_told_as_the_cache_folders(tmp_path, monkeypatch):
    """A read-only file system or a full disc passes ``os.access`` and fails the write."""
    def refuse(*args, **kwargs):
        raise OSError(30, "Read-only file system")
    monkeypatch.setenv("SHROUDNET_CACHE", str(tmp_path))
    monkeypatch.setattr(atomic.tempfile, "mkstemp", refuse)
    with pytest.raises(ValueError, match=r"SHROUDNET_CACHE=.*: cannot write there "
                                         r"\(Read-only file system\)"):
        cache.keep("kernel_x.py", "x = 1")


def test_a_cache_folder_that_holds_the_kernel_serves_it_unwritable(tmp_path, monkeypatch):
    monkeypatch.setenv("SHROUDNET_CACHE", str(tmp_path))
    path = cache.keep("kernel_x.py", "x = 1")
    monkeypatch.setattr(os, "access", lambda path, mode: False)
    assert cache.keep("kernel_x.py", "x = 1") == path and path.read_text() == "x = 1"


def test_an_unset_cache_names_its_default_and_the_variable(tmp_path, monkeypatch):
    monkeypatch.delenv("SHROUDNET_CACHE", raising=False)
    monkeypatch.setattr(Path, "home", lambda: tmp_path)
    (tmp_path / ".cache").write_text("not a folder")
    with pytest.raises(ValueError, match=r"^the kernel cache .*shroudnet \(SHROUDNET_CACHE "
                                         r"is not set\): .*\.cache is a file, not a folder; "
                                         r"set SHROUDNET_CACHE"):
        cache.keep("kernel_x.py", "x = 1")


def _no_compile(*args, **kwargs):
    raise AssertionError("a kernel was built in a cache folder that cannot hold it")


@pytest.mark.slow  # compiles a kernel in a cache of its own
def test_a_compile_is_announced_once_and_timed_apart(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("SHROUDNET_CACHE", str(tmp_path))
    generate.forget_kernels()
    scene = three_blade_paper(normal=LinearSpring(stiffness=3e5))
    try:
        first = simulate(scene, 1)
        announced = capsys.readouterr().err
        second = simulate(scene, 1)
        again = capsys.readouterr().err
    finally:
        generate.forget_kernels()
    assert "compiling the adaptive integrator for every built-in contact law" in \
        announced and "once" in announced
    assert again == ""
    assert first.compile_seconds > second.compile_seconds == 0.0

