"""Mistuning: how small blade-to-blade frequency scatter amplifies the forced response.

No two blades are alike: their frequencies scatter by a percent or so, and the scatter
localises vibration energy on a few blades. The amplification factor of a pattern is the
worst blade's peak amplitude over a speed range divided by the tuned group's peak over the
same range. It is a random variable over patterns; for a tuned, linearly coupled disc of N
blades without contact it never exceeds Whitehead's bound ½(1 + √N) (Whitehead, 1966),
which friction contacts can move either way.

A pattern gives each sector s a frequency deviation ε_s ~ Normal(0, spread). Its blade
nodes (``blades``: by default every node of the group, or, for a bladed disc, its blade
nodes) are made stiffer by (1 + ε_s)²: their springs to ground (a frequency model is
scaled by 1 + ε_s) and their couplings, a coupling between two mistuned nodes by
(1 + ε_a)(1 + ε_b). A blade on a rigid disc then has its frequencies scaled by 1 + ε_s
exactly, its mode shapes unchanged.

A ``Substructure`` node is mistuned the same way: its stiffness K(Ω) = K₀ + Ω² K₁ by
(1 + ε)² (both matrices), or, for modal data, each mode's frequency model by 1 + ε; its
mass, damping matrix and points are kept, so each of its natural frequencies, at every
speed, is scaled by 1 + ε and its mode shapes are unchanged. Its amplitude in a study is
the largest of its points' components.
"""

from __future__ import annotations

import math
from collections.abc import Hashable, Sequence
from dataclasses import dataclass, replace

import numpy as np

from contact_laws import (
    check_array,
    check_calls_with,
    check_instance,
    check_int,
    check_real,
    check_sequence,
)

from ..checked_records import check_record
from ..model.blade import Blade, ConstantFrequency, FrequencyTable, Southwell
from ..model.group import BladeGroup
from ..model.scene import Scene
from ..model.substructure import Substructure
from ..run.methods import TRANSIENT, Adaptive
from ..run.reporting import ProgressReporter
from ..run.simulation import SimulationError
from .sweep import sweep

#: The most mistuned groups one study may draw: each runs at every speed.
MAX_SAMPLES = 1_000_000


@dataclass(frozen=True, eq=False)
class MistuningStudy:
    """The amplification factors of random mistuning patterns.

    ``patterns[k, s]`` is sample k's frequency deviation ε of sector s; ``peaks[k, j]`` the
    worst blade's peak amplitude [m] at ``speeds_rpm[j]`` (row ``samples`` is the tuned
    group); ``amplification[k]`` sample k's worst peak over the tuned one.
    """

    spread: float
    speeds_rpm: np.ndarray
    patterns: np.ndarray
    peaks: np.ndarray
    blades: tuple[Hashable, ...]
    sectors: int

    #: Fields that may hold NaN or ±inf (see ``checked_records``).
    NON_FINITE = ("peaks",)

    def __post_init__(self):
        check_record(self)

    @property
    def tuned_peak(self) -> float:
        """The tuned group's largest blade amplitude over the speeds [m]."""
        return float(self.peaks[-1].max())

    @property
    def amplification(self) -> np.ndarray:
        """Per sample, its largest blade amplitude over the speeds / the tuned one [-]."""
        return self.peaks[:-1].max(axis=1) / self.tuned_peak

    @property
    def worst(self) -> int:
        """The sample with the largest amplification."""
        return int(np.argmax(self.amplification))

    @property
    def worst_pattern(self) -> np.ndarray:
        """The frequency deviations ε per sector of the worst sample."""
        return self.patterns[self.worst]

    @property
    def whitehead_bound(self) -> float:
        """½(1 + √N) for N sectors: the largest amplification of a tuned, linearly coupled
        disc without contact."""
        return 0.5 * (1.0 + math.sqrt(self.sectors))


@dataclass(frozen=True, eq=False)
class MistunedScenes:
    """value k ↦ the scene of sample k // n_speeds at speed k % n_speeds (the last sample
    tuned): one sweep runs every sample at every speed."""

    scene: Scene
    factors: np.ndarray        # (samples + 1, n_blades): 1 + ε of each node, 1 if tuned
    speeds_rpm: tuple[float, ...]
    mistuned: tuple[Hashable, ...] | None = None  # the nodes mistuned (``mistuned_group``)

    def __call__(self, value: float) -> Scene:
        sample, speed = divmod(int(round(value)), len(self.speeds_rpm))
        group = mistuned_group(self.scene, self.factors[sample], self.mistuned)
        return replace(self.scene, group=group, speed_rpm=self.speeds_rpm[speed])


def mistuned_group(scene: Scene, factors,
                   mistuned: Sequence[Hashable] | None = None) -> BladeGroup:
    """The scene's group with each node's frequency scaled by its factor (module
    docstring): ground springs by factor², couplings by the factors of their mistuned
    ends, (1 + ε_a)(1 + ε_b) between two and (1 + ε)² where one end is. ``mistuned``
    names the mistuned nodes (a node among them may draw ε = 0); by default those whose
    factor is not 1."""
    names = scene.blades
    factor = dict(zip(names, (float(f) for f in factors)))
    if mistuned is None:
        mistuned = [name for name in names if factor[name] != 1.0]
    mistuned = set(mistuned)
    group = BladeGroup()
    for name, data in scene.group.graph.nodes(data=True):
        if data["blade"] is not None:
            group.add_blade(name, _scaled_node(data["blade"], factor[name]),
                            scene.group.frame(name))
        elif data.get("motion") is not None:
            group.add_prescribed(name, data["motion"])
        else:
            group.add_fixed(name)
    for (left, right, interface), points in zip(scene.group.interfaces,
                                                scene.group.edge_points("interface")):
        group.connect(*_ends(left, right, points), interface)
    for (left, right, coupling), points in zip(scene.group.couplings,
                                               scene.group.edge_points("coupling")):
        ends = [factor[n] for n in (left, right) if n in mistuned]
        scale = 1.0 if not ends else ends[0] ** 2 if len(ends) == 1 else ends[0] * ends[1]
        group.connect(*_ends(left, right, points),
                      replace(coupling, stiffness=coupling.stiffness * scale))
    group.graph.graph.update(scene.group.graph.graph)
    return group


def _ends(left, right, points):
    """An edge's two ends for ``BladeGroup.connect``: (node, point) where it joins a named
    point, the node alone where it does not."""
    return tuple(node if point is None else (node, point)
                 for node, point in zip((left, right), points))


def _scaled_node(body: Blade | Substructure, factor: float) -> Blade | Substructure:
    """``body`` with its natural frequencies scaled by ``factor`` (module docstring)."""
    if isinstance(body, Substructure):
        return _scaled_substructure(body, factor)
    return _scaled_blade(body, factor)


def _scaled_substructure(body: Substructure, factor: float) -> Substructure:
    if factor == 1.0:
        return body
    if body.modal_frequencies is not None:
        return replace(body, modal_frequencies=tuple(_scaled_frequency(model, factor)
                                                     for model in body.modal_frequencies))
    speed = None if body.stiffness_speed is None else body.stiffness_speed * factor**2
    return replace(body, stiffness=body.stiffness * factor**2, stiffness_speed=speed)


def _scaled_blade(blade: Blade, factor: float) -> Blade:
    if factor == 1.0:
        return blade
    if blade.stiffness is not None:
        return replace(blade, stiffness=blade.stiffness * factor**2)
    return replace(blade, frequency=_scaled_frequency(blade.frequency, factor))


def _scaled_frequency(model, factor: float):
    """A frequency model whose f(Ω) is ``factor`` times ``model``'s at every speed."""
    if isinstance(model, ConstantFrequency):
        return ConstantFrequency(hz=model.hz * factor)
    if isinstance(model, Southwell):
        return Southwell(f0=model.f0 * factor, coefficient=model.coefficient * factor**2)
    if isinstance(model, FrequencyTable):
        return FrequencyTable(speeds_rpm=model.speeds_rpm,
                              frequencies=tuple(f * factor for f in model.frequencies))
    raise TypeError(f"cannot scale the frequency model {model!r}")  # pragma: no cover


def mistuning_study(scene: Scene, *, spread: float, samples: int,
                    speeds_rpm: Sequence[float], blades: Sequence[Hashable] | None = None,
                    patterns=None, seed: int = 0, transient: int = TRANSIENT, record: int = 10,
                    samples_per_period: int = 100, method=Adaptive(),
                    workers: int | None = None, executor=None,
                    progress=None) -> MistuningStudy:
    """A Monte Carlo of the forced response over random mistuning patterns: the
    computation behind ``shroudnet.mistuning_study`` (``front.studies.mistuning_study``,
    where every argument is documented), with its progress given as an object.

    Parameters
    ----------
    progress : ProgressCallback or None
        Handed to the study's ``sweep``: ``progress(done, total)`` after each run (a
        ``ProgressReporter`` hears the notices too); None or False reports nothing.

    The other arguments are ``shroudnet.mistuning_study``'s.
    """
    check_instance("mistuning_study", "scene", scene, Scene, expected="a shroudnet.Scene")
    spread = check_real("mistuning_study", "spread", spread, low=0.0, high=0.3)
    samples = check_int("mistuning_study", "samples", samples, low=1, most=MAX_SAMPLES)
    seed = check_int("mistuning_study", "seed", seed, low=0)
    if progress is not None and progress is not False \
            and not isinstance(progress, ProgressReporter):
        check_calls_with("mistuning_study", "progress", progress, 2,
                         expected='None, False, a ProgressReporter or a callable '
                                  'progress(done, total)')
    speeds = tuple(float(s) for s in check_array(
        "mistuning_study", "speeds_rpm", speeds_rpm, shape=(None,), low=0.0, low_open=True,
        unit="rpm"))
    if not speeds:
        raise ValueError("mistuning_study needs at least one speed in speeds_rpm")
    names = scene.blades
    sectors = scene.group.graph.graph.get("sectors") or len(names)
    per_sector = len(names) // sectors
    if blades is not None:
        blades = check_sequence("mistuning_study", "blades", blades,
                                expected="a sequence of blade names, or None for every blade")
    if blades is None:
        disc = scene.group.graph.graph.get("sectors") and per_sector > 1
        blades = [n for n in names if not disc or str(n).startswith("blade")]
    unknown = [b for b in blades if not isinstance(b, Hashable) or b not in names]
    if unknown or not blades:
        raise ValueError(f"mistuning_study: blades must name moving nodes of the group; "
                         f"unknown: {unknown}" if unknown else "mistuning_study: no blades")
    if patterns is None:
        patterns = np.random.default_rng(seed).normal(0.0, spread, size=(samples, sectors))
    patterns = check_array("mistuning_study", "patterns", patterns, shape=(None, None))
    if patterns.shape != (samples, sectors) or not np.all(patterns > -1.0):
        raise ValueError(f"mistuning_study: patterns must be {samples} × {sectors} "
                         f"deviations ε > −1, got shape {patterns.shape}")
    mistuned = np.array([names.index(b) for b in blades])
    factors = np.ones((samples + 1, len(names)))
    factors[:samples, mistuned] = 1.0 + patterns[:, mistuned // per_sector]
    if np.all(factors == 1.0):
        raise ValueError(f"mistuning_study: the patterns (spread = {spread:g}) leave every "
                         "blade as tuned, to a float's precision: give a spread, or patterns, "
                         "of at least 1e-12")
    scenes = MistunedScenes(scene, factors, speeds, tuple(blades))
    result = sweep(scenes, range((samples + 1) * len(speeds)), parameter="sample×speed",
                   transient=transient, record=record, samples_per_period=samples_per_period,
                   method=method, workers=workers, executor=executor, progress=progress)
    failed = result.failures
    if failed:
        raise SimulationError(f"mistuning_study: {len(failed)} of the runs failed, the "
                              f"first: {failed[0]} (sample×speed k is sample "
                              f"k // {len(speeds)}, speed k % {len(speeds)})")
    columns = mistuned
    if scene.arrays.is_structure:  # the sweep keeps a peak per point component
        chosen = set(blades)
        columns = [k for k, (node, _, _) in enumerate(scene.responses) if node in chosen]
    peaks = result.peaks()[:, columns].max(axis=1).reshape(samples + 1, len(speeds))
    return MistuningStudy(spread=spread, speeds_rpm=np.array(speeds), patterns=patterns,
                          peaks=peaks, blades=tuple(blades), sectors=sectors)
