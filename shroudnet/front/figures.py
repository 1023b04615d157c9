"""Figures in the paper's style, drawn with matplotlib from computed results.

Nothing in the computation imports this module. Each function draws on the Axes it is
given, ``ax=`` (or ``axes=``, a sequence of them in the order its docstring lists, for a
figure of several panels), and returns what it drew on, so that figures compose::

    sim = simulate(three_blade_paper(), 100)
    figure = Figure(figsize=(12, 4.5), layout="constrained")
    left, right = figure.subplots(1, 2)
    campbell_diagram(campbell(paper_frequency_model(), range(0, 9001, 100)), ax=left)
    hysteresis_loops({"blade1–blade2": hysteresis_loop(sim, 0, skip=50)}, ax=right)
    save_figure(figure, "composed.png")

Given no Axes, a function draws on a new ``Figure`` of its own size and returns that, as
it always has, leaving saving to the caller: ``save_figure(fig, path)`` writes it whole or
not at all (``fig.savefig(path)`` would leave half an image where it is interrupted).
"""

from __future__ import annotations

import math
from collections.abc import Hashable, Mapping, Sequence
from pathlib import Path

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.ticker import NullFormatter

from contact_laws import check_choice, check_instance, check_sequence

from .. import atomic
from ..analysis.readings import Campbell, HysteresisLoop, PatchHistory, classify, spectrum
from ..engine.codes import Mode
from ..linear.modes import GroupCampbell, LinearModes, excited_diameter
from ..run.simulation import Simulation
from ..steady.continuation import Branch
from ..steady.orbits import PeriodicOrbit
from ..studies.harmonic_precision import HarmonicPrecision
from ..studies.hill_floquet import HillFloquet
from ..studies.mistuning import MistuningStudy
from ..studies.precision import Study
from ..run.classification import CHAOTIC, FAILED, QUASI_PERIODIC, UNDETERMINED
from ..run.simulation import SweepMap
from ..studies.sweep import Sweep


def save_figure(figure: Figure, path, *, dpi: float = 110) -> Path:
    """Write ``figure`` to the image file ``path`` (its format from the suffix: ``.png``,
    ``.pdf``, ``.svg``, ...) whole or not at all (``atomic.write``); returns the path."""
    path = Path(path)
    kind = path.suffix[1:].lower() or None  # None: matplotlib's default format
    return atomic.write(path, lambda file: figure.savefig(file, format=kind, dpi=dpi))


def response_panel(sim: Simulation, blade: Hashable | int, skip: int, *, title: str = "",
                   max_ratio: float = 6.0, shown_periods: int = 30,
                   axes: Sequence[Axes] | None = None) -> Figure | Sequence[Axes]:
    """The panel of the paper's Figs. 7–19 for one blade after ``skip`` periods.

    Displacement history, phase portrait with Poincaré points, amplitude spectrum against
    f/f_e, and the impact (normal) and friction forces of the blade's interfaces: five
    panels, on ``axes`` in that order when given (the title and the motion's
    classification then head the first), else on a new figure, which is returned.
    """
    rows = slice(skip * sim.samples_per_period, None)
    t = sim.t[rows]
    x, v = (sim.scene.response_of(values[rows], blade) for values in (sim.x, sim.v))
    shown = slice(None, shown_periods * sim.samples_per_period + 1)
    label = sim.scene.responses[sim.scene.response_position(blade)]
    node = label[0] if sim.scene.arrays.is_structure else label
    own = np.array([e for e, contact in enumerate(sim.scene.contacts)
                    if node in (contact.left, contact.right)], dtype=int)
    given = axes
    figure, axes = _mosaic(given, "response_panel", (11, 8),
                           [["history", "history"], ["phase", "spectrum"],
                            ["impact", "friction"]])
    axes["history"].plot(t[shown] * 1e3, x[shown] * 1e3, lw=0.8)
    axes["history"].set(xlabel="t [ms]", ylabel="x [mm]", title="displacement")
    section = sim.poincare(blade, skip=skip)
    axes["phase"].plot(x * 1e3, v, lw=0.4, color="0.6")
    axes["phase"].plot(section[:, 0] * 1e3, section[:, 1], "o", ms=3, color="C3",
                       label="Poincaré points")
    axes["phase"].set(xlabel="x [mm]", ylabel="ẋ [m/s]", title="phase portrait")
    axes["phase"].legend(loc="upper right", fontsize="small")
    spec = spectrum(sim, blade, skip)
    keep = spec.frequency_ratio <= max_ratio
    axes["spectrum"].semilogy(spec.frequency_ratio[keep], spec.amplitude[keep] * 1e3, lw=0.8)
    axes["spectrum"].set(xlabel="f / f_e", ylabel="amplitude [mm]",
                         title=f"spectrum (resolution {spec.resolution:.3g} f_e)")
    for name, forces, label in (("impact", sim.normal_force, "N [N]"),
                                ("friction", sim.friction_force, "f [N]")):
        for e in own:
            contact = sim.scene.contacts[e]
            which = f" ({contact.contact})" if contact.pairs > 1 else ""
            axes[name].plot(t[shown] * 1e3, forces[rows][shown, e], lw=0.8,
                            label=f"{contact.left}–{contact.right}{which}")
        axes[name].set(xlabel="t [ms]", ylabel=label, title=f"{name} force")
        if len(own):
            axes[name].legend(loc="upper right", fontsize="small")
    kind = classify(sim, blade, skip)
    _headed(figure, axes, f"{title}  [{kind.label}]" if title else kind.label)
    return _drawn(figure, given)


def bifurcation_diagram(result: Sweep, *, xlabel: str = "", title: str = "",
                        scale: float = 1e3, unit: str = "mm",
                        axes: Sequence[Axes] | None = None) -> Figure | Sequence[Axes]:
    """Poincaré displacements of the swept blade against the parameter (Figs. 6, 12, 16);
    below them, where the sweep kept it (``sweep(..., lyapunov=True)``), the largest
    Lyapunov exponent of each point that does not repeat, with its error.

    Given ``axes``, one or two of them, the diagram is drawn on the first and the
    exponents on the second; without them, on a new figure (with a second panel only
    where there are exponents), which is returned.
    """
    values, section = result.diagram(0)
    exponents = [(p.value, p.classification.lyapunov, p.classification.lyapunov_error)
                 for p in result.points
                 if not p.failed and math.isfinite(p.classification.lyapunov)]
    given = axes
    if given is None:
        figure = Figure(figsize=(8, 7 if exponents else 5), layout="constrained")
        panels = (figure.subplots(2, 1, sharex=True, height_ratios=(3, 1.4)) if exponents
                  else (figure.add_subplot(),))
    else:
        figure, panels = None, _given_panels(given, "bifurcation_diagram", (1, 2))
    axes, below = panels[0], (panels[1] if len(panels) > 1 else None)
    axes.plot(values, section * scale, ",", color="k")
    if len(result.points) < 40:
        axes.plot(values, section * scale, ".", ms=2, color="k")
    axes.set(ylabel=f"x at t = k T_e [{unit}]", title=title)
    label = xlabel or result.parameter
    if below is None:
        axes.set(xlabel=label)
        return _drawn(figure, given)
    below.axhline(0.0, color="0.6", lw=0.8)
    if exponents:
        where, largest, error = (np.array(column) for column in zip(*exponents))
        below.errorbar(where, largest, yerr=2.0 * error, fmt=".", ms=3, color="C3", lw=0.6)
    below.set(xlabel=label, ylabel="λ_max per period")
    return _drawn(figure, given)


#: The colours of a map's classes: periods in order, then the motions that do not repeat.
PERIOD_COLOURS = ("#4477aa", "#66ccee", "#228833", "#ccbb44", "#aa3377", "#88ccaa",
                  "#332288", "#999933")
OTHER_COLOURS = {QUASI_PERIODIC: "#ee7733", CHAOTIC: "#cc3311", UNDETERMINED: "#bbbbbb",
                 FAILED: "#ffffff"}


def map_classes(labels) -> list[str]:
    """The classes that ``labels`` hold, in the order a map's legend lists them: periods
    by their number, then quasi-periodic, chaotic, undetermined and failed."""
    found = set(np.asarray(labels, dtype=object).ravel())
    periods = sorted((label for label in found if label not in OTHER_COLOURS),
                     key=lambda label: int(label[1:]))
    return periods + [label for label in OTHER_COLOURS if label in found]


def _legend_classes(classes: Sequence[str]) -> list[tuple[tuple[str, ...], str]]:
    """The entries of a map's legend from its ``classes`` (``map_classes``' order), each
    (the labels it colours, its name): one a class, but the longest periods share the
    last period colour, named by their labels, once more periods are found than
    ``PERIOD_COLOURS`` holds (no two classes ever drawn in one colour)."""
    periods = [label for label in classes if label not in OTHER_COLOURS]
    others = [((label,), label) for label in classes if label in OTHER_COLOURS]
    if len(periods) <= len(PERIOD_COLOURS):
        return [((label,), label) for label in periods] + others
    own, shared = periods[:len(PERIOD_COLOURS) - 1], tuple(periods[len(PERIOD_COLOURS) - 1:])
    name = ", ".join(shared) if len(shared) <= 3 else f"{shared[0]} … {shared[-1]}"
    return [((label,), label) for label in own] + [(shared, name)] + others


def sweep_map_figure(result: SweepMap, *, ax=None, title: str = "", xlabel: str = "",
                     ylabel: str = ""):
    """A two-parameter map (``sweep_map``) coloured by each cell's classification
    (period-k, quasi-periodic, chaotic, undetermined, failed; beyond eight periods the
    longest share one colour and one legend entry), the first parameter along x, the
    second along y, as the paper's diagrams but in two parameters, on ``ax``;
    returns ``ax``, or the new figure drawn when none is given."""
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    figure, ax = _canvas(ax, "sweep_map_figure", (7, 5.5))
    labels = result.labels
    shown = _legend_classes(map_classes(labels))
    code = {label: index for index, (members, _) in enumerate(shown) for label in members}
    cells = np.vectorize(code.__getitem__, otypes=[float])(labels)
    classes = [name for _, name in shown]
    colours = [OTHER_COLOURS.get(name) or PERIOD_COLOURS[index]
               for index, name in enumerate(classes)]
    ax.pcolormesh(result.first, result.second, cells.T, shading="nearest",
                  cmap=ListedColormap(colours), vmin=-0.5, vmax=len(classes) - 0.5)
    ax.set(xlabel=xlabel or result.parameters[0], ylabel=ylabel or result.parameters[1],
           title=title)
    ax.legend(handles=[Patch(facecolor=colour, edgecolor="0.5", label=label)
                       for label, colour in zip(classes, colours)],
              loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small", frameon=False)
    return _drawn(figure, ax)


def curves(x: Sequence[float], series: Mapping[str, Sequence[float]], *, xlabel: str,
           ylabel: str, title: str = "", logy: bool = False,
           ax: Axes | None = None) -> Figure | Axes:
    """Labelled curves over one axis (the E_ρ curves of Figs. 21–23), on ``ax`` when given
    (returned), else on a new figure (returned)."""
    figure, axes = _canvas(ax, "curves", (7, 4.5))
    for label, values in series.items():
        axes.plot(x, values, "o-", ms=3, label=label)
    if logy:
        axes.set_yscale("log")
    axes.set(xlabel=xlabel, ylabel=ylabel, title=title)
    if len(series) > 1:
        axes.legend()
    return _drawn(figure, ax)


def campbell_diagram(diagram: Campbell, *, title: str = "Campbell diagram",
                     ax: Axes | None = None) -> Figure | Axes:
    """f_d1 against speed with the engine-order lines and the resonances (Fig. 20), on
    ``ax`` when given (returned), else on a new figure (returned)."""
    figure, axes = _canvas(ax, "campbell_diagram", (7, 5))
    axes.plot(diagram.speeds_rpm, diagram.frequency, lw=2, label="f_d1")
    for order in diagram.engine_orders:
        axes.plot(diagram.speeds_rpm, diagram.line(order), "--", lw=0.8, label=f"l = {order}")
    for order, speed, frequency in diagram.crossings:
        axes.plot(speed, frequency, "o", color="C3")
        axes.annotate(f"{speed:.0f} rpm", (speed, frequency), textcoords="offset points",
                      xytext=(5, -12), fontsize="small")
    top = 1.3 * diagram.frequency.max()
    axes.set(xlabel="Ω [rev/min]", ylabel="frequency [Hz]", ylim=(0, top), title=title)
    axes.legend(loc="upper left")
    return _drawn(figure, ax)


def group_campbell_diagram(diagram: GroupCampbell, *, modes: int | None = None,
                           title: str = "Campbell diagram of the group",
                           ax: Axes | None = None) -> Figure | Axes:
    """The group's natural frequencies against speed (the lowest ``modes``; by default
    all), the engine-order lines, and the crossings where an order meets a mode it
    excites (its nodal diameter, on a ring); on ``ax`` when given (returned), else on a
    new figure (returned)."""
    figure, axes = _canvas(ax, "group_campbell_diagram", (7, 5))
    shown = diagram.frequencies[:, :modes]
    axes.plot(diagram.speeds_rpm, shown, color="C0", lw=1.0)
    axes.plot([], [], color="C0", lw=1.0, label=f"modes, interfaces {diagram.contacts}")
    for k, order in enumerate(diagram.engine_orders):
        axes.plot(diagram.speeds_rpm, diagram.line(order), "--", lw=0.8, color=f"C{k + 1}",
                  label=f"l = {order}")
    for order, mode, speed, frequency in diagram.crossings:
        if modes is None or mode < modes:
            axes.plot(speed, frequency, "o", color="C3", ms=4)
    axes.set(xlabel="Ω [rev/min]", ylabel="frequency [Hz]", ylim=(0, 1.1 * shown.max()),
             title=title)
    axes.legend(loc="upper left", fontsize="small")
    return _drawn(figure, ax)


def work_precision_diagram(study: Study, *, title: str = "What accuracy costs",
                           axes: Sequence[Axes] | None = None) -> Figure | Sequence[Axes]:
    """Relative error against CPU time per period, one panel per regime, one line per family
    of settings; in chaos, the sampling floor of the record as a dashed line.

    On ``axes`` when given, one per regime in the study's order (the title then heads the
    first), else on a new figure, which is returned.
    """
    regimes = list(study.floors)
    given = axes
    if given is None:
        figure = Figure(figsize=(5 * len(regimes), 4.5), layout="constrained")
        panels = figure.subplots(1, len(regimes), squeeze=False)[0]
    else:
        figure = None
        panels = _given_panels(given, "work_precision_diagram", (len(regimes),))
    styles = {"FixedStep": "o-", "Adaptive": "s-", "event tolerance": "^-",
              "Regularised": "v-", "Accuracy": "x:"}
    for ax, regime in zip(panels, regimes):
        rows = [m for m in study.measurements if m.regime == regime]
        for family, style in styles.items():
            chosen = [m for m in rows if m.setting.family == family]
            if chosen:
                ax.loglog([m.seconds_per_period * 1e3 for m in chosen],
                          [max(m.error, 1e-16) for m in chosen], style, ms=4, label=family)
        if study.floors[regime] > 0.0:
            ax.axhline(study.floors[regime], ls="--", color="0.5",
                       label="sampling floor of the record")
            ax.legend(handles=ax.get_lines()[-1:], fontsize="small", loc="lower right")
        ax.set(xlabel="CPU time per period [ms]", ylabel="relative error", title=regime)
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.grid(True, which="major", lw=0.3)
    panels[0].legend(fontsize="small")
    _headed(figure, panels, title)
    return _drawn(figure, given)


#: Markers of bifurcation points by kind.
BIFURCATION_MARKERS = {"fold": ("o", "C3"), "period-doubling": ("s", "C2"),
                       "torus": ("D", "C4"), "symmetry-breaking": ("*", "C1"),
                       "grazing": ("^", "0.4"), "stick-slip": ("v", "0.4")}


#: What ``forced_response`` may draw on its upper panel: (the value of an orbit for a
#: blade, its label, whether it is a length drawn in ``unit``).
QUANTITIES = {
    "amplitude": (lambda orbit, blade: orbit.amplitude(blade),
                  "amplitude, ½ peak-to-peak", True),
    "peak": (lambda orbit, blade: orbit.peak[orbit.scene.response_position(blade)],
             "peak, max |x|", True),
    "equivalent damping": (lambda orbit, blade: orbit.equivalent_damping,
                           "equivalent damping ratio ζ_eq [-]", False),
    "friction loss": (lambda orbit, blade: orbit.energy_per_cycle.friction,
                      "friction loss per cycle [J]", False),
    "phase": (lambda orbit, blade: orbit.harmonics(blade, 1).phases[1],
              "phase of the first harmonic [rad]", False),
}


def forced_response(branches: Mapping[str, Branch], blade: Hashable | int, *,
                    sweeps: Mapping[str, Sweep] | None = None,
                    limits: Mapping[str, tuple[np.ndarray, np.ndarray]] | None = None,
                    xlabel: str = "", title: str = "", scale: float = 1e3,
                    unit: str = "mm", quantity: str = "amplitude",
                    axes: Sequence[Axes] | None = None) -> Figure | Sequence[Axes]:
    """Forced-response curves: the amplitude of ``blade`` (half its peak-to-peak,
    ``PeriodicOrbit.amplitude``), or another ``quantity`` of ``QUANTITIES`` (its peak
    |x|, the orbit's equivalent damping ratio, its friction loss per cycle, the phase of
    its first harmonic), and its E_ρ along each branch, stable orbits solid and unstable
    ones dashed, bifurcation points marked by kind; on the E_ρ panel, the E_ρ of
    transient ``sweeps`` (e.g. up and down) as points. ``limits`` are labelled curves
    (parameter, amplitude [m]) drawn thin and grey on the amplitude panel: the linear
    responses with the interfaces open and stuck (``frequency_response``), between which
    friction moves the branches.

    Two panels, the quantity above and E_ρ below: on ``axes`` when given, two of them in
    that order, else on a new figure, which is returned.
    """
    if quantity not in QUANTITIES:
        raise ValueError(f"forced_response: quantity must be one of {list(QUANTITIES)}, "
                         f"got {quantity!r}")
    value_of, quantity_label, length = QUANTITIES[quantity]
    if limits and not length:
        raise ValueError("forced_response: linear limits are amplitudes; draw them with "
                         "quantity='amplitude' or 'peak'")
    given = axes
    if given is None:
        figure = Figure(figsize=(8, 7), layout="constrained")
        peak_axes, energy_axes = figure.subplots(2, 1, sharex=True)
    else:
        figure = None
        peak_axes, energy_axes = _given_panels(given, "forced_response", (2,))
    for k, (label, (parameter, amplitude)) in enumerate((limits or {}).items()):
        peak_axes.plot(parameter, np.asarray(amplitude) * scale, color="0.45", lw=0.9,
                       ls=("-", ":", "-.", (0, (5, 2, 1, 2)))[k % 4], label=label)
    for k, (label, branch) in enumerate(branches.items()):
        color = f"C{k}"
        factor = scale if length else 1.0
        peak = np.array([value_of(orbit, blade) for orbit in branch.orbits]) * factor
        energy = branch.energy_density(blade) * scale**2
        stable = branch.stable
        for panel, values in ((peak_axes, peak), (energy_axes, energy)):
            for start, stop, is_stable in _runs(stable):
                piece = slice(start, min(stop + 1, len(stable)))
                panel.plot(branch.parameter[piece], values[piece], color=color,
                           ls="-" if is_stable else "--", lw=1.2,
                           label=label if start == 0 and panel is peak_axes else None)
        for bifurcation in branch.bifurcations:
            marker, marker_color = BIFURCATION_MARKERS[bifurcation.kind]
            orbit = bifurcation.orbit
            for panel, value in ((peak_axes, value_of(orbit, blade) * factor),
                                 (energy_axes, orbit.energy_density(blade) * scale**2)):
                panel.plot(bifurcation.parameter, value, marker, color=marker_color, ms=5,
                           mfc="none")
    for k, (label, result) in enumerate((sweeps or {}).items()):
        kept = [p for p in result.points if not p.failed]
        energy_axes.plot([p.value for p in kept], [p.energy_density * scale**2 for p in kept],
                         "^v<>"[k % 4], color="k", ms=3, mfc="none", lw=0, label=label)
    for kind, (marker, color) in BIFURCATION_MARKERS.items():
        if any(b.kind == kind for branch in branches.values() for b in branch.bifurcations):
            peak_axes.plot([], [], marker, color=color, mfc="none", lw=0, label=kind)
    if not all(np.all(branch.stable) for branch in branches.values()):
        peak_axes.plot([], [], "k--", lw=1.2, label="unstable")
    peak_axes.set(ylabel=f"{quantity_label} [{unit}]" if length else quantity_label,
                  title=title)
    peak_axes.legend(fontsize="small")
    energy_axes.set(xlabel=xlabel or next(iter(branches.values())).name,
                    ylabel=f"E_ρ [{unit}²]")
    if sweeps:
        energy_axes.legend(fontsize="small")
    return _drawn(figure, given)


def branch_content(branches: Mapping[str, Branch], blade: Hashable | int, *,
                   xlabel: str = "", title: str = "", scale: float = 1e3,
                   unit: str = "mm",
                   axes: Sequence[Axes] | None = None) -> Figure | Sequence[Axes]:
    """A branch's response in an engineer's terms, one panel each along the branches: the
    amplitude of ``blade`` (half its peak-to-peak), the phase of its first harmonic
    against the excitation's sine, unwrapped along each branch, and the orbit's
    equivalent damping ratio ζ_eq; stable orbits solid, unstable ones dashed.

    On ``axes`` when given, three of them in that order, else on a new figure, which is
    returned.
    """
    if axes is None:
        figure = Figure(figsize=(8, 8), layout="constrained")
        panels = figure.subplots(3, 1, sharex=True)
    else:
        figure, panels = None, _given_panels(axes, "branch_content", (3,))
    for k, (label, branch) in enumerate(branches.items()):
        phases = np.unwrap(branch.harmonics(blade, order=1)[1][:, 1])
        curves = (branch.amplitude(blade) * scale, phases, branch.equivalent_damping)
        for panel, values in zip(panels, curves):
            for start, stop, stable in _runs(branch.stable):
                piece = slice(start, min(stop + 1, len(branch)))
                panel.plot(branch.parameter[piece], values[piece], color=f"C{k}",
                           ls="-" if stable else "--", lw=1.2,
                           label=label if start == 0 and panel is panels[0] else None)
    panels[0].set(ylabel=f"amplitude, ½ peak-to-peak [{unit}]", title=title)
    panels[0].legend(fontsize="small")
    panels[1].set(ylabel="phase of the 1st harmonic [rad]")
    panels[2].set(ylabel="equivalent damping ratio ζ_eq [-]",
                  xlabel=xlabel or next(iter(branches.values())).name)
    return _drawn(figure, axes)


def _runs(flags):
    """(start, stop, flag) of each run of equal ``flags``: stop is the run's last index + 1."""
    edges = np.flatnonzero(np.diff(np.asarray(flags, dtype=int))) + 1
    starts = np.concatenate([[0], edges])
    stops = np.concatenate([edges, [len(flags)]])
    return [(int(a), int(b), bool(flags[a])) for a, b in zip(starts, stops)]


def zzenf_diagram(modes: Mapping[str, LinearModes], *, speed_rpm: float,
                  engine_orders: Sequence[int] = (), families: int = 3,
                  title: str = "Frequency against nodal diameter",
                  ax: Axes | None = None) -> Figure | Axes:
    """The ZZENF (SAFE) diagram: each family's frequency against the nodal diameter, for
    each set of modes (e.g. contacts open and stuck), and the zig-zag of the engine orders
    at ``speed_rpm``: order l excites diameter ``excited_diameter(l, N)`` at l Ω/60. On
    ``ax`` when given (returned), else on a new figure (returned)."""
    figure, axes = _canvas(ax, "zzenf_diagram", (7, 5))
    sectors = None
    for k, (label, result) in enumerate(modes.items()):
        table = result.families()[:, :families]
        sectors = result.sectors
        diameters = np.arange(table.shape[0])
        # A family is a line only where every diameter has it: when stuck contacts remove
        # a family from some diameters, the k-th mode is not one family across them.
        style = "-" if np.isfinite(table).all() else ""
        for family in range(table.shape[1]):
            axes.plot(diameters, table[:, family], "os^"[k % 3] + style, color=f"C{k}",
                      ms=4, lw=0.8, mfc="none", label=label if family == 0 else None)
    orders = list(engine_orders)
    if orders and sectors:
        points = [(excited_diameter(order, sectors), order * speed_rpm / 60.0)
                  for order in orders]
        axes.plot(*zip(*points), "k:", lw=0.8, label=f"engine orders at {speed_rpm:g} rpm")
        for order, (nd, frequency) in zip(orders, points):
            axes.annotate(f"l = {order}", (nd, frequency), textcoords="offset points",
                          xytext=(4, 4), fontsize="small")
    axes.set(xlabel="nodal diameter", ylabel="frequency [Hz]", title=title)
    axes.legend(fontsize="small")
    return _drawn(figure, ax)


def sector_amplitudes(orbits: Mapping[str, PeriodicOrbit], slot: int = -1, *,
                      scale: float = 1e3, unit: str = "mm",
                      title: str = "Amplitude round the ring",
                      ax: Axes | None = None) -> Figure | Axes:
    """Each sector's amplitude (half its peak-to-peak, [m] times ``scale`` in ``unit``) of
    the node in position ``slot`` of its sector, one line per orbit of a ring or disc of
    sectors: flat for a travelling wave, localised where a symmetry-breaking bifurcation
    has taken over. On ``ax`` when given (returned), else on a new figure (returned)."""
    for label, orbit in orbits.items():
        if orbit.scene.group.graph.graph.get("sectors") is None:
            raise ValueError(f"sector_amplitudes: the orbit {label!r} is not of a ring or a "
                             "disc of sectors")
    figure, axes = _canvas(ax, "sector_amplitudes", (7, 4.5))
    for k, (label, orbit) in enumerate(orbits.items()):
        sectors = orbit.scene.group.graph.graph["sectors"]
        half = 0.5 * (orbit.maximum - orbit.minimum)
        per_sector = len(half) // sectors
        values = half.reshape(sectors, per_sector)[:, slot] * scale
        axes.plot(np.arange(1, sectors + 1), values, "o-", color=f"C{k}", label=label)
    axes.set(xlabel="sector", ylabel=f"amplitude, ½ peak-to-peak [{unit}]", title=title,
             ylim=(0.0, None))
    axes.legend(fontsize="small")
    return _drawn(figure, ax)


def mistuning_histogram(study: MistuningStudy, *,
                        title: str = "Mistuning: amplification factor",
                        ax: Axes | None = None) -> Figure | Axes:
    """The distribution of the amplification factors of a ``MistuningStudy``, with its
    largest and Whitehead's bound ½(1 + √N) marked; on ``ax`` when given (returned), else
    on a new figure (returned)."""
    figure, axes = _canvas(ax, "mistuning_histogram", (7, 4.5))
    factors = study.amplification
    axes.hist(factors, bins=max(5, min(30, len(factors) // 2)), color="C0", alpha=0.8,
              label=f"{len(factors)} patterns, spread {study.spread:g}")
    axes.axvline(1.0, color="k", lw=0.8, ls=":", label="tuned")
    axes.axvline(factors.max(), color="C3", lw=1.2, label=f"largest {factors.max():.3f}")
    axes.axvline(study.whitehead_bound, color="C2", lw=1.2, ls="--",
                 label=f"Whitehead ½(1 + √{study.sectors}) = {study.whitehead_bound:.3f}")
    axes.set(xlabel="worst blade peak / tuned peak", ylabel="patterns", title=title)
    axes.legend(fontsize="small")
    return _drawn(figure, ax)


def stick_slip_cycle(sim: Simulation, interface=0, skip: int = 0, *,
                     shown_periods: int = 10, title: str = "",
                     axes: Sequence[Axes] | None = None) -> Figure | Sequence[Axes]:
    """A friction interface's stick–slip motion after ``skip`` periods: its blade's
    displacement with the stuck phases shaded, the phase portrait with stuck and slipping
    samples apart, and the friction coefficient f/N the interface carried against its slip
    velocity, over its law's μ(|v|) sgn v. ``interface`` is an interface's position, or
    (interface, k) for a patch's k-th contact (``Scene.contact_position``).

    Three panels, on ``axes`` in that order when given (the title then heads the first),
    else on a new figure, which is returned.
    """
    column = sim.checked_interface(interface, "stick_slip_cycle")
    contact = sim.scene.contacts[column]
    left, right = contact.left, contact.right
    face = sim.scene.group.interfaces[contact.interface][2]
    blade = left if left in sim.scene.blades else right
    rows = slice(skip * sim.samples_per_period, None)
    t = sim.t[rows]
    if sim.scene.arrays.is_structure:  # the displacement along the interface's tangent
        blade = f"t·r, interface {interface}"
        x = sim.slip_displacement(interface)[rows]
        v = sim.slip_velocity(interface)[rows]
    else:
        i = sim.scene.blade_position(blade)
        x, v = sim.x[rows, i], sim.v[rows, i]
    stuck = sim.modes[rows, column] == Mode.STICK
    normal, friction = sim.normal_force[rows, column], sim.friction_force[rows, column]
    a = sim.scene.arrays
    u_rate = sim.slip_velocity(interface)[rows]
    given = axes
    figure, axes = _mosaic(given, "stick_slip_cycle", (11, 7.5),
                           [["history", "history"], ["phase", "law"]])
    shown = slice(None, shown_periods * sim.samples_per_period + 1)
    axes["history"].plot(t[shown] * 1e3, x[shown] * 1e3, lw=0.9, color="C0")
    axes["history"].fill_between(t[shown] * 1e3, 0, 1, where=stuck[shown], color="C1",
                                 alpha=0.2, transform=axes["history"].get_xaxis_transform(),
                                 label="stuck")
    axes["history"].set(xlabel="t [ms]", ylabel=f"x [mm] ({blade})", title="displacement")
    axes["history"].legend(loc="upper right", fontsize="small")
    axes["phase"].plot(x[~stuck] * 1e3, v[~stuck], ".", ms=2, color="C0", label="slipping")
    axes["phase"].plot(x[stuck] * 1e3, v[stuck], ".", ms=2, color="C1", label="stuck")
    axes["phase"].set(xlabel="x [mm]", ylabel="ẋ [m/s]", title="phase portrait")
    axes["phase"].legend(loc="upper right", fontsize="small")
    closed = normal > 0.0
    axes["law"].plot(u_rate[closed & ~stuck], friction[closed & ~stuck] / normal[closed & ~stuck],
                     ".", ms=2, color="C0", label="slipping")
    axes["law"].plot(u_rate[closed & stuck], friction[closed & stuck] / normal[closed & stuck],
                     ".", ms=2, color="C1", label="stuck (static friction)")
    if face.friction is not None and np.any(closed):
        reach = np.abs(u_rate).max()
        speeds = np.linspace(-reach, reach, 401)
        law = face.friction
        axes["law"].plot(speeds, [law(abs(s)) * np.sign(s) for s in speeds], lw=0.8,
                         color="k", label="μ(|v|) sgn v")
        axes["law"].axhline(a.static_mu[column], color="0.5", lw=0.6, ls=":")
        axes["law"].axhline(-a.static_mu[column], color="0.5", lw=0.6, ls=":")
    axes["law"].set(xlabel="slip velocity v [m/s]", ylabel="f / N",
                    title=f"friction on {left}–{right}")
    axes["law"].legend(loc="lower right", fontsize="small")
    _headed(figure, axes, title or f"stick–slip of {blade}")
    return _drawn(figure, given)


def hysteresis_loops(loops: Mapping[str, HysteresisLoop], *, title: str = "",
                     scale: float = 1e6, unit: str = "µm",
                     ax: Axes | None = None) -> Figure | Axes:
    """Friction force against tangential relative displacement, one labelled loop each
    (``hysteresis_loop``), with its dissipated energy per cycle in the legend; on ``ax``
    when given (returned), else on a new figure (returned)."""
    figure, axes = _canvas(ax, "hysteresis_loops", (7, 5))
    for label, loop in loops.items():
        axes.plot(loop.slip * scale, loop.force, lw=1.0,
                  label=f"{label}: {_energy(loop.area_per_cycle())}/cycle")
    axes.axhline(0.0, color="0.6", lw=0.5)
    axes.set(xlabel=f"tangential relative displacement u_t [{unit}]",
             ylabel="friction force f [N]", title=title)
    axes.legend(fontsize="small")
    return _drawn(figure, ax)


#: The colours of a contact-state map: open, stuck, slipping (either way).
STATE_COLOURS = ("0.93", "C1", "C0")


def patch_map(patch: PatchHistory, *, quantity: str = "state", title: str = "",
              ax: Axes | None = None) -> Figure | Axes:
    """A patch's contacts over time (``analysis.patch_history``): one row per point pair
    against t/T_e, coloured by its state (``quantity`` "state": open, stuck or slipping)
    or by its normal load N_k [N] ("normal": the load distribution over the face); on
    ``ax`` when given (returned), else on a new figure (returned)."""
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    check_instance("patch_map", "patch", patch, PatchHistory,
                   expected="a PatchHistory (analysis.patch_history)")
    quantity = check_choice("patch_map", "quantity", quantity, ("state", "normal"))
    figure, axes = _canvas(ax, "patch_map", (8, 1.2 + 0.3 * patch.contacts))
    phase = (patch.time - patch.time[0]) / patch.period
    edges = np.concatenate([phase, [phase[-1] + (phase[-1] - phase[-2] if len(phase) > 1
                                                 else 1.0)]])
    rows = np.arange(patch.contacts + 1) - 0.5
    if quantity == "state":
        codes = np.where(patch.modes == Mode.OPEN, 0, np.where(patch.modes == Mode.STICK, 1, 2))
        axes.pcolormesh(edges, rows, codes.T, cmap=ListedColormap(STATE_COLOURS), vmin=-0.5,
                        vmax=2.5, shading="flat")
        axes.legend(handles=[Patch(color=c, label=name) for c, name in
                             zip(STATE_COLOURS, ("open", "stuck", "slipping"))],
                    loc="upper right", fontsize="small", ncols=3)
    else:
        mesh = axes.pcolormesh(edges, rows, patch.normal.T, cmap="viridis", shading="flat")
        axes.figure.colorbar(mesh, ax=axes, label="normal force N [N]")
    axes.set(xlabel="t / T_e", ylabel="contact", yticks=range(patch.contacts),
             title=title or f"interface {patch.interface}: "
             + ("contact states" if quantity == "state" else "normal load"))
    return _drawn(figure, ax)


def _energy(joules: float) -> str:
    """``joules`` in J, mJ or µJ, whichever gives 1 to 1000 of it (µJ below)."""
    for factor, unit in ((1.0, "J"), (1e3, "mJ"), (1e6, "µJ")):
        if abs(joules) * factor >= 1.0:
            return f"{joules * factor:.3g} {unit}"
    return f"{joules * 1e6:.3g} µJ"


#: What ``harmonic_precision_diagram`` draws against: the number of harmonics, or the CPU
#: time of a solve.
HARMONIC_AXES = ("harmonics", "time")


def harmonic_precision_diagram(study: HarmonicPrecision, *, ax=None, against: str = "harmonics",
                               label: str = ""):
    """Harmonic balance against the exact orbit (``studies.harmonic_precision``): the
    relative errors of the amplitude and of the energy dissipated per cycle against the
    number of harmonics H, or against the CPU time of a solve [ms] with the exact
    shooting's time marked, on ``ax``; returns ``ax``, or the new figure drawn when none
    is given. ``label`` prefixes the curves' labels (several scenes on one axes)."""
    if against not in HARMONIC_AXES:
        raise ValueError(f"harmonic_precision_diagram: against must be one of "
                         f"{HARMONIC_AXES}, got {against!r}")
    figure, ax = _canvas(ax, "harmonic_precision_diagram", (6, 4.5))
    x = study.harmonics if against == "harmonics" else study.seconds * 1e3
    prefix = f"{label}: " if label else ""
    for values, style, name in ((study.amplitude_error, "o-", "amplitude"),
                                (study.energy_error, "s--", "energy per cycle")):
        ax.loglog(x, np.maximum(values, 1e-16), style, ms=4, label=f"{prefix}{name}")
    if against == "time":
        ax.axvline(study.exact_seconds * 1e3, color="0.4", ls=":", lw=1.0,
                   label=f"{prefix}exact orbit by shooting")
        for h, t, e in zip(study.harmonics, x, study.amplitude_error):
            ax.annotate(f"H={h}", (t, max(e, 1e-16)), textcoords="offset points",
                        xytext=(3, 3), fontsize="x-small")
    ax.set(xlabel="harmonics H" if against == "harmonics" else "CPU time of a solve [ms]",
           ylabel="relative error against the exact orbit")
    ax.grid(True, which="major", lw=0.3)
    ax.legend(fontsize="small")
    return _drawn(figure, ax)


#: The exact multipliers whose errors ``hill_floquet_diagram`` draws, at most, and how
#: near two of them (or one and the other's conjugate) are to be drawn as one.
DRAWN_MULTIPLIERS = 4
SAME_MULTIPLIER = 1e-9


def hill_floquet_diagram(study: HillFloquet, *, label: str = "",
                         axes: Sequence[Axes] | None = None) -> Figure | Sequence[Axes]:
    """Hill's multipliers against the exact Floquet multipliers
    (``studies.hill_floquet``), on two panels: (a) the multipliers in the complex plane,
    Hill's at each H (coloured by H) over the exact ones (black rings) and the unit
    circle; (b) against H, the error e_j(H) = min_i |μ_j − μ̂_i(H)| of each exact
    multiplier of largest modulus (a complex pair drawn once, at most
    ``DRAWN_MULTIPLIERS``).

    Parameters
    ----------
    study : HillFloquet
    label : str
        Panel (a)'s title (the scene's name); panel (b)'s says whether the orbits'
        contact forces are smooth (``HarmonicOrbit.smooth``), where Hill's method is to be
        trusted.
    axes : sequence of two Axes, optional
        The panels (a) and (b); by default those of a new figure, which is returned.

    Returns
    -------
    Figure or the given ``axes``
    """
    figure, panels = _mosaic(axes, "hill_floquet_diagram", (11, 4.5), [["plane", "error"]])
    plane, error = panels["plane"], panels["error"]
    smooth = all(orbit.smooth for orbit in study.orbits)
    smoothness = "smooth contact forces" if smooth else "contacts switch: not smooth"
    angle = np.linspace(0.0, 2.0 * math.pi, 361)
    plane.plot(np.cos(angle), np.sin(angle), color="0.6", lw=0.8, label="unit circle")
    colours = [f"C{k % 10}" for k in range(len(study.harmonics))]
    for k, (h, orbit) in enumerate(zip(study.harmonics, study.orbits)):
        plane.plot(orbit.multipliers.real, orbit.multipliers.imag, "o", color=colours[k],
                   ms=7.0 - 5.0 * k / max(len(study.harmonics) - 1, 1),
                   label=f"Hill, H = {h}")
    exact = study.exact.multipliers
    plane.plot(exact.real, exact.imag, "o", mfc="none", mec="k", ms=11, mew=1.2,
               label="exact (Floquet)")
    plane.set(xlabel="Re μ", ylabel="Im μ", aspect="equal", title=f"(a) {label or 'multipliers'}")
    plane.grid(True, lw=0.3)
    plane.legend(fontsize="x-small", loc="upper left", bbox_to_anchor=(1.02, 1.0))
    for j in _distinct(exact)[:DRAWN_MULTIPLIERS]:
        error.loglog(study.harmonics, np.maximum(study.errors[:, j], 1e-16), "o-", ms=4,
                     label=f"exact μ = {_shown_multiplier(exact[j])}")
    error.set(xlabel="harmonics H", ylabel="distance to the nearest of Hill's",
              title=f"(b) {smoothness}")
    error.grid(True, which="major", lw=0.3)
    error.legend(fontsize="small", loc="best")
    return _drawn(figure, axes)


def _shown_multiplier(mu: complex) -> str:
    """μ as a ± bi to three digits, a part below ``SAME_MULTIPLIER`` shown as 0."""
    real, imaginary = (part if abs(part) > SAME_MULTIPLIER else 0.0
                       for part in (mu.real, mu.imag))
    return f"{real:.3g}" + (f" ± {abs(imaginary):.3g}i" if imaginary else "")


def _distinct(multipliers: np.ndarray) -> list[int]:
    """The positions of ``multipliers`` that are neither a repeat of an earlier one nor
    its conjugate (within ``SAME_MULTIPLIER``)."""
    kept: list[int] = []
    for j, mu in enumerate(multipliers):
        if all(min(abs(mu - multipliers[k]), abs(mu - np.conj(multipliers[k])))
               > SAME_MULTIPLIER for k in kept):
            kept.append(j)
    return kept


# ---- where a figure is drawn --------------------------------------------------------------

def _canvas(ax: Axes | None, owner: str, size: tuple[float, float]
            ) -> tuple[Figure | None, Axes]:
    """(the new figure, or None when ``ax`` is given; the Axes to draw on): ``ax`` itself,
    checked, or the one Axes of a new figure of ``size`` inches."""
    if ax is None:
        figure = Figure(figsize=size, layout="constrained")
        return figure, figure.add_subplot()
    return None, check_instance(owner, "ax", ax, Axes, expected="a matplotlib Axes")


def _given_panels(axes: object, owner: str, counts: tuple[int, ...]) -> tuple[Axes, ...]:
    """The Axes of ``axes`` (a sequence, or an array of them as ``subplots`` returns), of
    one of the numbers ``counts``, or raise naming ``owner.axes``."""
    if isinstance(axes, np.ndarray):
        axes = axes.ravel()
    wanted = " or ".join(str(count) for count in counts)
    panels = check_sequence(owner, "axes", axes, expected=f"a sequence of {wanted} Axes")
    if len(panels) not in counts:
        raise ValueError(f"{owner}.axes needs {wanted} Axes, one a panel; got {len(panels)}")
    for k, panel in enumerate(panels):
        check_instance(owner, f"axes[{k}]", panel, Axes, expected="a matplotlib Axes")
    return panels


def _mosaic(axes: object, owner: str, size: tuple[float, float],
            layout: list[list[str]]) -> tuple[Figure | None, dict[str, Axes]]:
    """(the new figure, or None when ``axes`` are given; the panels by name): the given
    ``axes``, one for each name of ``layout`` in reading order, or a new figure of
    ``size`` inches laid out as ``layout``."""
    if axes is None:
        figure = Figure(figsize=size, layout="constrained")
        return figure, figure.subplot_mosaic(layout)
    names = list(dict.fromkeys(name for row in layout for name in row))
    return None, dict(zip(names, _given_panels(axes, owner, (len(names),))))


def _headed(figure: Figure | None, panels, heading: str) -> None:
    """Put ``heading`` over a figure of several ``panels`` (a sequence, or a mapping in
    reading order): the suptitle of a figure of its own, else before the first panel's
    title, leaving the given figure's suptitle to its owner."""
    if figure is not None:
        figure.suptitle(heading)
        return
    first = next(iter(panels.values())) if isinstance(panels, dict) else panels[0]
    first.set_title(f"{heading}: {first.get_title()}" if first.get_title() else heading)


def _drawn(figure: Figure | None, given):
    """What a figure function returns: the new ``figure``, or what it was ``given``."""
    return given if figure is None else figure
