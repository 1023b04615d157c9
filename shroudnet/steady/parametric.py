"""What a study along a parameter asks of its ``scene_at`` (value ↦ Scene), checked once
for ``sweep`` and ``continuation`` alike: it returns a ``Scene``, and its value changes that
scene. A ``scene_at`` that ignores its value would give the same point at every value,
silently; both studies refuse it before any work.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import fields, is_dataclass

import numpy as np

from ..model.scene import Scene


def same_scene(a: Scene, b: Scene) -> bool:
    """Whether two scenes are the same to the dynamics: every array of ``Scene.arrays``
    equal (names and labels aside), the layout of substructures' coordinates included."""
    return _equal(a.arrays, b.arrays)


def _equal(a, b) -> bool:
    """Whether two of ``SceneArrays``' values are equal: arrays element by element, records
    without an equality of their own (``Layout``) field by field, tuples and dicts item by
    item, anything else by its ``==``."""
    if is_dataclass(a) and not a.__dataclass_params__.eq:
        return type(a) is type(b) and all(_equal(getattr(a, f.name), getattr(b, f.name))
                                          for f in fields(a))
    if isinstance(a, tuple) and isinstance(b, tuple):
        return len(a) == len(b) and all(_equal(x, y) for x, y in zip(a, b))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_equal(a[k], b[k]) for k in a)
    return np.array_equal(a, b)


def checked_scene_at(owner: str, scene_at: Callable[[float], Scene], value: float,
                     other: float) -> Scene:
    """The scene at ``value``, once ``scene_at`` is seen to return a ``Scene`` at ``value``
    and at ``other`` and, where the two differ, different scenes.

    ``owner`` (``"sweep"``, ``"continuation"``) names the study in the messages.

    Raises
    ------
    TypeError
        ``scene_at`` returns something other than a ``Scene``.
    ValueError
        ``scene_at`` returns the same scene at ``value`` and ``other`` (the value is
        ignored, or sets something that is not part of the scene).
    """
    first = _scene(owner, scene_at, value)
    if other == value:
        return first
    if same_scene(first, _scene(owner, scene_at, other)):
        raise ValueError(f"{owner}: scene_at returns the same scene for different values "
                         f"({value:g} and {other:g}): its value must change the scene (the "
                         "speed, an amplitude, a gap, a law's parameter, …)")
    return first


def _scene(owner: str, scene_at, value: float) -> Scene:
    scene = scene_at(value)
    if not isinstance(scene, Scene):
        raise TypeError(f"{owner}.scene_at must return a shroudnet.Scene, got "
                        f"{type(scene).__name__}")
    return scene
