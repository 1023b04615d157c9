"""Compiling every kernel flavour the project ships ahead of use: ``shroudnet cache --warm``.

A kernel is compiled once per combination of law classes, effects and method, on first use,
and kept in the cache (``engine.cache``). The scenes of built-in laws share one kernel per
*flavour*: its method (adaptive, fixed-step, exponential), whether its nodes are
substructures, whether its contacts are elastic (sliders in the state), and whether it
carries the tangent flow (orbits, monodromy, Lyapunov exponents; adaptive only). Warming
compiles each flavour in a process of its own, as many at once as there are cores, by
running the smallest scene that calls for it for one period; a flavour already in the cache
only loads.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass

from .. import scenes
from ..analysis.stability import monodromy
from ..run.methods import Adaptive, Exponential, FixedStep
from ..run.simulate import simulate


@dataclass(frozen=True)
class Flavour:
    """One shipped kernel flavour: its ``method`` ("adaptive", "fixed_step",
    "exponential"), whether it runs substructures (``structures``), elastic contacts
    (``sliders``) and the tangent flow (``tangent``)."""

    method: str
    structures: bool = False
    sliders: bool = False
    tangent: bool = False

    @property
    def name(self) -> str:
        nodes = "elastic contacts" if self.sliders else \
            "substructures" if self.structures else "blades"
        return f"{self.method.replace('_', '-')}, {nodes}" + \
            (", tangent flow" if self.tangent else "")


#: Every flavour a scene of built-in laws can call for. The exponential method runs
#: substructures whose phases are linear: no elastic contacts, no tangent flow.
FLAVOURS = tuple(
    Flavour(method, structures, sliders, tangent)
    for structures, sliders in ((False, False), (True, False), (True, True))
    for method, tangent in (("adaptive", False), ("adaptive", True), ("fixed_step", False),
                            ("exponential", False))
    if method != "exponential" or (structures and not sliders))


def _scene(flavour: Flavour):
    """The smallest shipped scene of ``flavour``'s nodes."""
    if flavour.sliders:
        return scenes.modal_packet(blades=2, tangential_stiffness=3e5)
    if flavour.structures:
        return scenes.modal_packet(blades=2)
    return scenes.three_blade_paper()


def compile_flavour(flavour: Flavour) -> float:
    """Compile (or load) ``flavour``'s kernel by running its scene for one period; returns
    the seconds that took in this process's CPU time, which the compile fills."""
    scene = _scene(flavour)
    began = time.process_time()
    if flavour.tangent:
        monodromy(scene)
    else:
        method = {"adaptive": Adaptive(), "fixed_step": FixedStep(steps_per_period=64),
                  "exponential": Exponential(steps_per_period=64)}[flavour.method]
        simulate(scene, 1, method=method, samples_per_period=4)
    return time.process_time() - began


def warm(flavours: tuple[Flavour, ...] = FLAVOURS, workers: int = 1,
         done: Callable[[Flavour, float], None] | None = None) -> dict[Flavour, float]:
    """Compile ``flavours`` on ``workers`` processes at once (one process each, so that a
    flavour's compile is never shared); ``done(flavour, seconds)`` hears each as it
    finishes. Returns the seconds of each (``compile_flavour``)."""
    seconds = {}
    with ProcessPoolExecutor(max_workers=workers, max_tasks_per_child=1) as pool:
        futures = {pool.submit(compile_flavour, flavour): flavour for flavour in flavours}
        for future in as_completed(futures):
            flavour = futures[future]
            seconds[flavour] = future.result()
            if done is not None:
                done(flavour, seconds[flavour])
    return seconds

