"""Figures in the paper's style, drawn with matplotlib from computed results.

Nothing in the computation imports this module. Each function returns a matplotlib
``Figure`` and leaves saving to the caller (``fig.savefig(path)``).
"""

from __future__ import annotations

import math
from collections.abc import Hashable, Mapping, Sequence

import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import NullFormatter

from ..analysis.readings import Campbell, HysteresisLoop, PatchHistory, classify, spectrum
from ..engine.codes import Mode
from ..linear.modes import GroupCampbell, LinearModes, excited_diameter
from ..run.simulation import Simulation
from ..steady.continuation import Branch
from ..steady.orbits import PeriodicOrbit
from ..studies.mistuning import MistuningStudy
from ..studies.precision import Study
from ..studies.sweep import Sweep


def response_panel(sim: Simulation, blade: Hashable | int, skip: int, *, title: str = "",
                   max_ratio: float = 6.0, shown_periods: int = 30) -> Figure:
    """The panel of the paper's Figs. 7–19 for one blade after ``skip`` periods.

    Displacement history, phase portrait with Poincaré points, amplitude spectrum against
    f/f_e, and the impact (normal) and friction forces of the blade's interfaces.
    """
    rows = slice(skip * sim.samples_per_period, None)
    t = sim.t[rows]
    x, v = (sim.scene.response_of(values[rows], blade) for values in (sim.x, sim.v))
    shown = slice(None, shown_periods * sim.samples_per_period + 1)
    label = sim.scene.responses[sim.scene.response_position(blade)]
    node = label[0] if sim.scene.arrays.is_structure else label
    own = np.array([e for e, contact in enumerate(sim.scene.contacts)
                    if node in (contact.left, contact.right)], dtype=int)
    figure = Figure(figsize=(11, 8), layout="constrained")
    axes = figure.subplot_mosaic([["history", "history"], ["phase", "spectrum"],
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
    figure.suptitle(f"{title}  [{kind.label}]" if title else kind.label)
    return figure


def bifurcation_diagram(result: Sweep, *, xlabel: str = "", title: str = "",
                        scale: float = 1e3, unit: str = "mm") -> Figure:
    """Poincaré displacements of the swept blade against the parameter (Figs. 6, 12, 16);
    below them, where the sweep kept it (``sweep(..., lyapunov=True)``), the largest
    Lyapunov exponent of each point that does not repeat, with its error."""
    values, section = result.diagram(0)
    exponents = [(p.value, p.classification.lyapunov, p.classification.lyapunov_error)
                 for p in result.points
                 if not p.failed and math.isfinite(p.classification.lyapunov)]
    figure = Figure(figsize=(8, 7 if exponents else 5), layout="constrained")
    if exponents:
        axes, below = figure.subplots(2, 1, sharex=True, height_ratios=(3, 1.4))
    else:
        axes, below = figure.add_subplot(), None
    axes.plot(values, section * scale, ",", color="k")
    if len(result.points) < 40:
        axes.plot(values, section * scale, ".", ms=2, color="k")
    axes.set(ylabel=f"x at t = k T_e [{unit}]", title=title)
    label = xlabel or result.parameter
    if below is None:
        axes.set(xlabel=label)
        return figure
    where, largest, error = (np.array(column) for column in zip(*exponents))
    below.axhline(0.0, color="0.6", lw=0.8)
    below.errorbar(where, largest, yerr=2.0 * error, fmt=".", ms=3, color="C3", lw=0.6)
    below.set(xlabel=label, ylabel="λ_max per period")
    return figure


def curves(x: Sequence[float], series: Mapping[str, Sequence[float]], *, xlabel: str,
           ylabel: str, title: str = "", logy: bool = False) -> Figure:
    """Labelled curves over one axis (the E_ρ curves of Figs. 21–23)."""
    figure = Figure(figsize=(7, 4.5), layout="constrained")
    axes = figure.add_subplot()
    for label, values in series.items():
        axes.plot(x, values, "o-", ms=3, label=label)
    if logy:
        axes.set_yscale("log")
    axes.set(xlabel=xlabel, ylabel=ylabel, title=title)
    if len(series) > 1:
        axes.legend()
    return figure


def campbell_diagram(diagram: Campbell, *, title: str = "Campbell diagram") -> Figure:
    """f_d1 against speed with the engine-order lines and the resonances (Fig. 20)."""
    figure = Figure(figsize=(7, 5), layout="constrained")
    axes = figure.add_subplot()
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
    return figure


def group_campbell_diagram(diagram: GroupCampbell, *, modes: int | None = None,
                           title: str = "Campbell diagram of the group") -> Figure:
    """The group's natural frequencies against speed (the lowest ``modes``; by default
    all), the engine-order lines, and the crossings where an order meets a mode it
    excites (its nodal diameter, on a ring)."""
    figure = Figure(figsize=(7, 5), layout="constrained")
    axes = figure.add_subplot()
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
    return figure


def work_precision_diagram(study: Study, *, title: str = "What accuracy costs") -> Figure:
    """Relative error against CPU time per period, one panel per regime, one line per family
    of settings; in chaos, the sampling floor of the record as a dashed line."""
    regimes = list(study.floors)
    figure = Figure(figsize=(5 * len(regimes), 4.5), layout="constrained")
    axes = figure.subplots(1, len(regimes), squeeze=False)[0]
    styles = {"FixedStep": "o-", "Adaptive": "s-", "event tolerance": "^-",
              "Regularised": "v-", "Accuracy": "x:"}
    for ax, regime in zip(axes, regimes):
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
    axes[0].legend(fontsize="small")
    figure.suptitle(title)
    return figure


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
                    unit: str = "mm", quantity: str = "amplitude") -> Figure:
    """Forced-response curves: the amplitude of ``blade`` (half its peak-to-peak,
    ``PeriodicOrbit.amplitude``), or another ``quantity`` of ``QUANTITIES`` (its peak
    |x|, the orbit's equivalent damping ratio, its friction loss per cycle, the phase of
    its first harmonic), and its E_ρ along each branch, stable orbits solid and unstable
    ones dashed, bifurcation points marked by kind; on the E_ρ panel, the E_ρ of
    transient ``sweeps`` (e.g. up and down) as points. ``limits`` are labelled curves
    (parameter, amplitude [m]) drawn thin and grey on the amplitude panel: the linear
    responses with the interfaces open and stuck (``frequency_response``), between which
    friction moves the branches."""
    if quantity not in QUANTITIES:
        raise ValueError(f"forced_response: quantity must be one of {list(QUANTITIES)}, "
                         f"got {quantity!r}")
    value_of, quantity_label, length = QUANTITIES[quantity]
    if limits and not length:
        raise ValueError("forced_response: linear limits are amplitudes; draw them with "
                         "quantity='amplitude' or 'peak'")
    figure = Figure(figsize=(8, 7), layout="constrained")
    peak_axes, energy_axes = figure.subplots(2, 1, sharex=True)
    for k, (label, (parameter, amplitude)) in enumerate((limits or {}).items()):
        peak_axes.plot(parameter, np.asarray(amplitude) * scale, color="0.45", lw=0.9,
                       ls=("-", ":", "-.", (0, (5, 2, 1, 2)))[k % 4], label=label)
    for k, (label, branch) in enumerate(branches.items()):
        color = f"C{k}"
        factor = scale if length else 1.0
        peak = np.array([value_of(orbit, blade) for orbit in branch.orbits]) * factor
        energy = branch.energy_density(blade) * scale**2
        stable = branch.stable
        for axes, values in ((peak_axes, peak), (energy_axes, energy)):
            for start, stop, is_stable in _runs(stable):
                piece = slice(start, min(stop + 1, len(stable)))
                axes.plot(branch.parameter[piece], values[piece], color=color,
                          ls="-" if is_stable else "--", lw=1.2,
                          label=label if start == 0 and axes is peak_axes else None)
        for bifurcation in branch.bifurcations:
            marker, marker_color = BIFURCATION_MARKERS[bifurcation.kind]
            orbit = bifurcation.orbit
            for axes, value in ((peak_axes, value_of(orbit, blade) * factor),
                                (energy_axes, orbit.energy_density(blade) * scale**2)):
                axes.plot(bifurcation.parameter, value, marker, color=marker_color, ms=5,
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
    return figure


def branch_content(branches: Mapping[str, Branch], blade: Hashable | int, *,
                   xlabel: str = "", title: str = "", scale: float = 1e3,
                   unit: str = "mm") -> Figure:
    """A branch's response in an engineer's terms, one panel each along the branches: the
    amplitude of ``blade`` (half its peak-to-peak), the phase of its first harmonic
    against the excitation's sine, unwrapped along each branch, and the orbit's
    equivalent damping ratio ζ_eq; stable orbits solid, unstable ones dashed."""
    figure = Figure(figsize=(8, 8), layout="constrained")
    panels = figure.subplots(3, 1, sharex=True)
    for k, (label, branch) in enumerate(branches.items()):
        phases = np.unwrap(branch.harmonics(blade, order=1)[1][:, 1])
        curves = (branch.amplitude(blade) * scale, phases, branch.equivalent_damping)
        for axes, values in zip(panels, curves):
            for start, stop, stable in _runs(branch.stable):
                piece = slice(start, min(stop + 1, len(branch)))
                axes.plot(branch.parameter[piece], values[piece], color=f"C{k}",
                          ls="-" if stable else "--", lw=1.2,
                          label=label if start == 0 and axes is panels[0] else None)
    panels[0].set(ylabel=f"amplitude, ½ peak-to-peak [{unit}]", title=title)
    panels[0].legend(fontsize="small")
    panels[1].set(ylabel="phase of the 1st harmonic [rad]")
    panels[2].set(ylabel="equivalent damping ratio ζ_eq [-]",
                  xlabel=xlabel or next(iter(branches.values())).name)
    return figure


def _runs(flags):
    """(start, stop, flag) of each run of equal ``flags``: stop is the run's last index + 1."""
    edges = np.flatnonzero(np.diff(np.asarray(flags, dtype=int))) + 1
    starts = np.concatenate([[0], edges])
    stops = np.concatenate([edges, [len(flags)]])
    return [(int(a), int(b), bool(flags[a])) for a, b in zip(starts, stops)]


def zzenf_diagram(modes: Mapping[str, LinearModes], *, speed_rpm: float,
                  engine_orders: Sequence[int] = (), families: int = 3,
                  title: str = "Frequency against nodal diameter") -> Figure:
    """The ZZENF (SAFE) diagram: each family's frequency against the nodal diameter, for
    each set of modes (e.g. contacts open and stuck), and the zig-zag of the engine orders
    at ``speed_rpm``: order l excites diameter ``excited_diameter(l, N)`` at l Ω/60."""
    figure = Figure(figsize=(7, 5), layout="constrained")
    axes = figure.add_subplot()
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
    return figure


def sector_amplitudes(orbits: Mapping[str, PeriodicOrbit], slot: int = -1, *,
                      scale: float = 1e3, unit: str = "mm",
                      title: str = "Amplitude round the ring") -> Figure:
    """Each sector's amplitude (half its peak-to-peak, [m] times ``scale`` in ``unit``) of
    the node in position ``slot`` of its sector, one line per orbit of a ring or disc of
    sectors: flat for a travelling wave, localised where a symmetry-breaking bifurcation
    has taken over."""
    figure = Figure(figsize=(7, 4.5), layout="constrained")
    axes = figure.add_subplot()
    for k, (label, orbit) in enumerate(orbits.items()):
        sectors = orbit.scene.group.graph.graph.get("sectors")
        if sectors is None:
            raise ValueError(f"sector_amplitudes: the orbit {label!r} is not of a ring or a "
                             "disc of sectors")
        half = 0.5 * (orbit.maximum - orbit.minimum)
        per_sector = len(half) // sectors
        values = half.reshape(sectors, per_sector)[:, slot] * scale
        axes.plot(np.arange(1, sectors + 1), values, "o-", color=f"C{k}", label=label)
    axes.set(xlabel="sector", ylabel=f"amplitude, ½ peak-to-peak [{unit}]", title=title,
             ylim=(0.0, None))
    axes.legend(fontsize="small")
    return figure


def mistuning_histogram(study: MistuningStudy, *,
                        title: str = "Mistuning: amplification factor") -> Figure:
    """The distribution of the amplification factors of a ``MistuningStudy``, with its
    largest and Whitehead's bound ½(1 + √N) marked."""
    figure = Figure(figsize=(7, 4.5), layout="constrained")
    axes = figure.add_subplot()
    factors = study.amplification
    axes.hist(factors, bins=max(5, min(30, len(factors) // 2)), color="C0", alpha=0.8,
              label=f"{len(factors)} patterns, spread {study.spread:g}")
    axes.axvline(1.0, color="k", lw=0.8, ls=":", label="tuned")
    axes.axvline(factors.max(), color="C3", lw=1.2, label=f"largest {factors.max():.3f}")
    axes.axvline(study.whitehead_bound, color="C2", lw=1.2, ls="--",
                 label=f"Whitehead ½(1 + √{study.sectors}) = {study.whitehead_bound:.3f}")
    axes.set(xlabel="worst blade peak / tuned peak", ylabel="patterns", title=title)
    axes.legend(fontsize="small")
    return figure


def stick_slip_cycle(sim: Simulation, interface=0, skip: int = 0, *,
                     shown_periods: int = 10, title: str = "") -> Figure:
    """A friction interface's stick–slip motion after ``skip`` periods: its blade's
    displacement with the stuck phases shaded, the phase portrait with stuck and slipping
    samples apart, and the friction coefficient f/N the interface carried against its slip
    velocity, over its law's μ(|v|) sgn v. ``interface`` is an interface's position, or
    (interface, k) for a patch's k-th contact (``Scene.contact_position``)."""
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
    figure = Figure(figsize=(11, 7.5), layout="constrained")
    axes = figure.subplot_mosaic([["history", "history"], ["phase", "law"]])
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
    figure.suptitle(title or f"stick–slip of {blade}")
    return figure


def hysteresis_loops(loops: Mapping[str, HysteresisLoop], *, title: str = "",
                     scale: float = 1e6, unit: str = "µm") -> Figure:
    """Friction force against tangential relative displacement, one labelled loop each
    (``analysis.hysteresis_loop``), with its dissipated energy per cycle in the legend."""
    figure = Figure(figsize=(7, 5), layout="constrained")
    axes = figure.subplots()
    for label, loop in loops.items():
        axes.plot(loop.slip * scale, loop.force, lw=1.0,
                  label=f"{label}: {_energy(loop.area_per_cycle())}/cycle")
    axes.axhline(0.0, color="0.6", lw=0.5)
    axes.set(xlabel=f"tangential relative displacement u_t [{unit}]",
             ylabel="friction force f [N]", title=title)
    axes.legend(fontsize="small")
    return figure


#: The colours of a contact-state map: open, stuck, slipping (either way).
STATE_COLOURS = ("0.93", "C1", "C0")


def patch_map(patch: PatchHistory, *, quantity: str = "state", ax=None, title: str = ""):
    """A patch's contacts over time (``analysis.patch_history``): one row per point pair
    against t/T_e, coloured by its state (``quantity`` "state": open, stuck or slipping)
    or by its normal load N_k [N] ("normal": the load distribution over the face).
    Draws on ``ax`` (a new figure's axes if None) and returns it."""
    from matplotlib.colors import ListedColormap

    if quantity not in ("state", "normal"):
        raise ValueError(f"patch_map.quantity must be 'state' or 'normal', got {quantity!r}")
    if ax is None:
        ax = Figure(figsize=(8, 1.2 + 0.3 * patch.contacts), layout="constrained").subplots()
    phase = (patch.time - patch.time[0]) / patch.period
    edges = np.concatenate([phase, [phase[-1] + (phase[-1] - phase[-2] if len(phase) > 1
                                                 else 1.0)]])
    rows = np.arange(patch.contacts + 1) - 0.5
    if quantity == "state":
        codes = np.where(patch.modes == Mode.OPEN, 0, np.where(patch.modes == Mode.STICK, 1, 2))
        ax.pcolormesh(edges, rows, codes.T, cmap=ListedColormap(STATE_COLOURS), vmin=-0.5,
                      vmax=2.5, shading="flat")
        from matplotlib.patches import Patch
        ax.legend(handles=[Patch(color=c, label=name) for c, name in
                           zip(STATE_COLOURS, ("open", "stuck", "slipping"))],
                  loc="upper right", fontsize="small", ncols=3)
    else:
        mesh = ax.pcolormesh(edges, rows, patch.normal.T, cmap="viridis", shading="flat")
        ax.figure.colorbar(mesh, ax=ax, label="normal force N [N]")
    ax.set(xlabel="t / T_e", ylabel="contact", yticks=range(patch.contacts),
           title=title or f"interface {patch.interface}: "
           + ("contact states" if quantity == "state" else "normal load"))
    return ax


def _energy(joules: float) -> str:
    """``joules`` in J, mJ or µJ, whichever gives 1 to 1000 of it (µJ below)."""
    for factor, unit in ((1.0, "J"), (1e3, "mJ"), (1e6, "µJ")):
        if abs(joules) * factor >= 1.0:
            return f"{joules * factor:.3g} {unit}"
    return f"{joules * 1e6:.3g} µJ"
