"""The names a kernel's generated header defines, declared for readers and the linter.

``shroudnet.engine.generate`` writes, for the law classes of a scene, a header that
defines these names, then runs the phase modules of this package in the header's module
(``PHASES``), so that their functions see the header's names as module globals. The phase
modules import them from here under ``typing.TYPE_CHECKING`` only: at run time the
header's values are the ones read, and numba compiles each effect flag as a constant,
removing the branches it rules out (on the flag itself, not on a variable computed from
it).

Nothing here is called; the bodies only document the contracts.
"""

#: A normal law that opens is present: contact closing and opening are events.
HAS_CONTACT_EVENTS: bool = True
#: An exact friction law is present: interfaces may stick (stick clusters, breakaway).
HAS_STICK: bool = True
#: A friction law of any kind is present.
HAS_FRICTION: bool = True
#: A regularised (smoothed) friction law is present.
HAS_REGULARISED: bool = True
#: The scene has couplings (linear springs and dampers between nodes).
HAS_COUPLINGS: bool = True
#: The scene has prescribed-motion nodes.
HAS_PRESCRIBED: bool = True
#: The scene has substructures (``records.StructureScene``): its interfaces act along rows
#: of the coordinates, and stuck ones are constraints (``constraints``), not clusters.
HAS_STRUCTURES: bool = False
#: The scene has elastic contacts (``sliders``): their sliders are coordinates of the
#: state, integrated as first-order ones (a scene with substructures only).
HAS_SLIDERS: bool = False
#: The run integrates the tangent flow; otherwise its state holds a ``records.NoTangent``,
#: whose fields are not to be read.
HAS_TANGENT: bool = False
#: The kernel's method: Dormand–Prince 5(4) with error control and dense output (True),
#: or classical Runge–Kutta 4 on a fixed grid (False). It decides only how the state
#: inside a step is obtained (``step.motion_inside``) and how steps are sized and recorded.
ADAPTIVE: bool = True
#: The kernel propagates each phase exactly on a fixed grid (``step.exact_step``, for
#: scenes whose phases are linear: ``methods.Exponential``); ``ADAPTIVE`` is then False.
EXPONENTIAL: bool = False
#: The key of what a phase's code is made of, which its compiled functions' names carry,
#: and the folder numba caches them in (``compiled``): set by ``generate`` before each
#: phase runs, read by the compile flavours, never by the phases themselves.
CACHE_KEY: str = ""
CACHE_FOLDER: str = ""


def normal_force(kind: int, params, penetration: float, rate: float) -> float:
    """N [N] of the normal law of class index ``kind`` with parameter row ``params`` at
    penetration δ [m] and rate δ̇ [m/s]."""
    raise NotImplementedError


def friction_coefficient(kind: int, params, slip_speed: float) -> float:
    """μ of the friction law of class index ``kind`` at slip speed |v| [m/s] ≥ 0."""
    raise NotImplementedError


def normal_force_gradient(kind: int, params, penetration: float,
                          rate: float) -> tuple[float, float]:
    """(∂N/∂δ [N/m], ∂N/∂δ̇ [N s/m]): the law's own derivative, or central differences."""
    raise NotImplementedError


def friction_slope(kind: int, params, slip_speed: float) -> float:
    """dμ/d|v| [s/m]: the law's own derivative, or differences (one-sided near 0)."""
    raise NotImplementedError
