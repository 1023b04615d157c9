"""Figures compose: every plotting function of ``front.figures`` draws on the Axes it is
given (``ax=``, or ``axes=`` for several panels) and returns them, and without them draws
on a new figure of its own and returns that.

The results drawn are small (short runs of scenes whose kernels the suite compiles
anyway); what is checked is where the drawing lands, not what it looks like.
"""

import numpy as np
import pytest
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from shroudnet import (
    Adaptive,
    Blade,
    BladeGroup,
    Coupling,
    EngineOrderWave,
    Excitation,
    Mode,
    PatchHistory,
    Scene,
    Sweep,
    SweepMap,
    campbell,
    continuation,
    group_campbell,
    hysteresis_loop,
    linear_modes,
    mistuning_study,
    periodic_orbit,
    simulate,
    sweep,
)
from shroudnet.front import figures
from shroudnet.scenes import (
    bladed_disc_24,
    block_on_belt,
    paper_frequency_model,
    three_blade_paper,
)
from shroudnet.studies.harmonic_precision import HarmonicPrecision
from shroudnet.studies.hill_floquet import hill_against_floquet
from shroudnet.studies.precision import Measurement, Setting, Study
from tests.test_harmonic_balance import open_pair


def coupled_ring(speed_rpm: float = 6000.0) -> Scene:
    """Six blades on springs joined by springs, forced by the
    engine-order wave of l = 2: a ring of sectors, cheap to solve."""
    blade = Blade(mass=0.1, damping=2.0, stiffness=1e5)
    group = BladeGroup.ring(6, blade, Coupling(stiffness=5e3))
    return Scene(group=group, speed_rpm=speed_rpm,
                 excitation=Excitation(engine_order=2, amplitudes=(0.0, 1.0),
                                       phases=EngineOrderWave()))


@pytest.fixture(scope="module")
def drawn():
    """One result of each kind the figures draw, by the name of the function drawing it."""
    sim = simulate(three_blade_paper(), 40)
    belt = simulate(block_on_belt(), 20)
    swept = sweep(lambda g: three_blade_paper(gamma1=g), [1.0, 8.8], parameter="gamma1",
                  transient=10, record=12, workers=1, progress=False, lyapunov=True)
    branch = continuation(lambda rpm: three_blade_paper(speed_rpm=rpm), 5800.0, 5900.0,
                          max_points=3)
    ring = coupled_ring()
    modes = {contacts: linear_modes(bladed_disc_24(), contacts)
             for contacts in ("open", "stuck")}
    setting = Setting(family="Adaptive", label="rtol = 1e-6", method=Adaptive(rtol=1e-6))
    study = Study(measurements=[Measurement(regime=regime, setting=setting,
                                            seconds_per_period=1e-4,
                                            errors={"E_rho": 1e-6})
                                for regime in ("p1", "chaos")],
                  floors={"p1": 0.0, "chaos": 1e-3})
    wave = periodic_orbit(ring)
    mistuned = mistuning_study(ring, spread=0.03, samples=2, speeds_rpm=[5900.0, 6000.0],
                               transient=20, record=5, workers=1, progress=False)
    return {
        "response_panel": ((sim, "blade2", 20), {}, 5),
        "bifurcation_diagram": ((swept,), {}, 2),
        "curves": (([1.0, 2.0, 3.0], {"a": [1.0, 4.0, 9.0], "b": [1.0, 2.0, 3.0]}),
                   {"xlabel": "x", "ylabel": "y"}, None),
        "campbell_diagram": ((campbell(paper_frequency_model(), np.linspace(0, 9000, 31)),),
                             {}, None),
        "group_campbell_diagram": ((group_campbell(ring, [3000.0, 6000.0, 9000.0]),), {},
                                   None),
        "work_precision_diagram": ((study,), {}, 2),
        "forced_response": (({"up": branch}, "blade2"), {}, 2),
        "branch_content": (({"up": branch}, "blade2"), {}, 3),
        "zzenf_diagram": ((modes,), {"speed_rpm": 3000.0, "engine_orders": (5, 6)}, None),
        "sector_amplitudes": (({"wave": wave},), {}, None),
        "harmonic_precision_diagram": ((HarmonicPrecision(
            scene=ring, harmonics=np.array([1, 3, 5]), samples=np.array([32, 42, 90]),
            seconds=np.array([1e-3, 2e-3, 4e-3]), amplitude_error=np.array([1e-2, 1e-3, 1e-4]),
            energy_error=np.array([2e-2, 2e-3, 2e-4]), state_error=np.array([1e-2, 1e-3, 1e-4]),
            exact=wave, exact_seconds=0.5),), {"against": "time"}, None),
        "hill_floquet_diagram": ((hill_against_floquet(open_pair(), (1, 2)),),
                                 {"label": "pair"}, 2),
        "mistuning_histogram": ((mistuned,), {}, None),
        "stick_slip_cycle": ((belt, 0, 10), {}, 3),
        "hysteresis_loops": (({"blade1–blade2": hysteresis_loop(sim, 0, 20)},), {}, None),
        "sweep_map_figure": ((SweepMap(parameters=("gamma1", "q1"), first=np.array([1.0, 8.8]),
                                       second=np.array([50.0]),
                                       rows=tuple(Sweep(parameter="q1", blade=swept.blade,
                                                        points=(point,), settings={})
                                                  for point in swept.points)),), {}, None),
        "patch_map": ((patch_of_four(),), {}, None),
    }


def patch_of_four() -> PatchHistory:
    """A patch of four point pairs over one period of 10 ms: the first pair open, the
    second stuck, the others slipping one way then the other."""
    time = np.linspace(0.0, 0.01, 41)
    modes = np.empty((41, 4), dtype=np.int64)
    modes[:, 0], modes[:, 1] = Mode.OPEN, Mode.STICK
    modes[:, 2:] = np.where(time < 0.005, Mode.SLIP_POSITIVE, Mode.SLIP_NEGATIVE)[:, None]
    normal = np.where(modes == Mode.OPEN, 0.0, 1.0 + np.arange(4.0))
    return PatchHistory(interface=0, time=time, modes=modes, normal=normal,
                        friction=0.3 * normal, period=0.01)


FUNCTIONS = ["response_panel", "bifurcation_diagram", "curves", "campbell_diagram",
             "group_campbell_diagram", "work_precision_diagram", "forced_response",
             "branch_content", "zzenf_diagram", "sector_amplitudes", "mistuning_histogram",
             "stick_slip_cycle", "hysteresis_loops", "harmonic_precision_diagram",
             "hill_floquet_diagram", "sweep_map_figure", "patch_map"]


def has_drawing(axes: Axes) -> bool:
    """Whether anything of the data was drawn on ``axes`` (a line, a patch, markers)."""
    return bool(axes.lines or axes.patches or axes.collections)


#: What the module offers beside its figures: the one way to write a figure to a file, and
#: the classes a map's legend lists, in order.
NOT_DRAWING = {"save_figure", "map_classes"}


def test_every_plotting_function_is_listed_here():
    public = {name for name, value in vars(figures).items()
              if callable(value) and not name.startswith("_")
              and getattr(value, "__module__", None) == figures.__name__}
    assert public == set(FUNCTIONS) | NOT_DRAWING


@pytest.mark.slow  # a sweep with exponents, a continuation and a mistuning study
@pytest.mark.parametrize("name", FUNCTIONS)
def test_a_figure_function_draws_on_the_axes_given_and_returns_them(name, drawn):
    arguments, options, panels = drawn[name]
    function = getattr(figures, name)
    figure = Figure(layout="constrained")
    if panels is None:
        ax = figure.add_subplot()
        assert function(*arguments, **options, ax=ax) is ax
        assert has_drawing(ax)
        assert figure.axes == [ax]   # no other Axes made
    else:
        given = list(figure.subplots(1, panels))
        assert function(*arguments, **options, axes=given) is given
        assert all(has_drawing(panel) for panel in given)
        assert figure.axes == given
        assert not figure.get_suptitle()  # the figure's title is its owner's to give


@pytest.mark.slow  # shares the results of the test above
@pytest.mark.parametrize("name", FUNCTIONS)
def test_without_axes_a_figure_function_draws_a_new_figure_and_returns_it(name, drawn):
    arguments, options, _ = drawn[name]
    figure = getattr(figures, name)(*arguments, **options)
    assert isinstance(figure, Figure)
    assert figure.axes and all(has_drawing(axes) for axes in figure.axes
                               if axes.get_label() != "<colorbar>")


def test_wrong_axes_are_refused_by_name():
    x, series = [1.0, 2.0], {"a": [1.0, 2.0]}
    with pytest.raises(TypeError, match=r"curves\.ax must be a matplotlib Axes"):
        figures.curves(x, series, xlabel="x", ylabel="y", ax=Figure())
    study = Study(measurements=[], floors={"p1": 0.0, "p3": 0.0})
    two = list(Figure().subplots(1, 2))
    with pytest.raises(ValueError, match=r"work_precision_diagram\.axes needs 2 Axes"):
        figures.work_precision_diagram(study, axes=two[:1])
    with pytest.raises(TypeError, match=r"work_precision_diagram\.axes\[1\] must be"):
        figures.work_precision_diagram(study, axes=[two[0], "panel"])
    with pytest.raises(TypeError, match=r"work_precision_diagram\.axes must be a sequence"):
        figures.work_precision_diagram(study, axes=two[0])
