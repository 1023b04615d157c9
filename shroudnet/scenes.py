"""Named scenes: canonical groups shared by the docs, the tests and the examples."""

from __future__ import annotations

import functools
import inspect
import math
from collections.abc import Sequence

from contact_laws import (
    ConstantLoad,
    Coulomb,
    ExponentialFriction,
    FrictionLaw,
    LinearSpring,
    NormalLaw,
    Stribeck,
    check_choice,
    check_int,
    check_real,
)

from .model.beam import cantilever_beam
from .model.blade import Blade, Southwell
from .model.coupling import Coupling
from .model.excitation import (NO_EXCITATION, AntiPhase, EngineOrderWave, Excitation,
                               ExplicitPhases, PhasePattern)
from .model.group import BladeGroup
from .model.interface import Interface
from .model.motion import ConstantVelocity
from .model.scene import Scene
from .model.substructure import Substructure

#: The most sectors or blades a named scene is built with.
MAX_NODES = 100_000


def _same(value, default) -> bool:
    """Whether ``value`` is the parameter's default (arrays and odd types: only itself)."""
    if value is default:
        return True
    try:
        return type(value) is type(default) and bool(value == default)
    except (TypeError, ValueError):
        return False


def _named_arguments(factory):
    """Make the errors raised while ``factory`` builds its scene name the arguments the
    caller changed: "three_blade_paper with q1 = None: Excitation.amplitudes must be a real
    number ...". A number too large for the arithmetic (``OverflowError``) becomes a
    ``ValueError`` so named."""
    signature = inspect.signature(factory)

    @functools.wraps(factory)
    def build(*args, **kwargs):
        try:
            return factory(*args, **kwargs)
        except (ValueError, TypeError, OverflowError, ZeroDivisionError) as error:
            try:
                bound = signature.bind(*args, **kwargs)
            except TypeError:
                raise error from None
            changed = ", ".join(f"{name} = {value!r:.60}" for name, value in
                                bound.arguments.items()
                                if not _same(value, signature.parameters[name].default))
            kind = TypeError if isinstance(error, TypeError) else ValueError
            raise kind(f"{factory.__name__}" + (f" with {changed}" if changed else "")
                       + f": {error}") from error
    return build


#: The paper's §3 data: blade material and geometry, shroud mass and damping, friction.
PAPER = {
    "young_modulus": 2.1e11,   # E [Pa]
    "density": 7800.0,         # ρ [kg/m³]
    "length": 0.15,            # L [m]
    "width": 0.05,             # b [m]
    "thickness": 0.007,        # h [m]
    "damping": 4.0,            # c [N·s/m]
    "mass": 0.082,             # m, the shroud [kg]
    "mu_static": 0.5,          # μ_s
    "mu_kinetic": 0.3,         # μ_m
    "beta": 5.0,               # β [s/m]
}

#: Southwell coefficient B chosen so that f_d1 = f_e = 216.25 Hz at 6487.5 rpm with l = 2.
PAPER_SOUTHWELL_COEFFICIENT = 0.76


@_named_arguments
def cantilever_frequency(*, young_modulus: float, density: float, length: float, width: float,
                         thickness: float, tip_mass: float) -> float:
    """First bending frequency [Hz] of a clamped rectangular beam with a tip mass.

    f0 = (1/2π) sqrt(k / (m_tip + (33/140) ρ b h L)), with the static tip stiffness
    k = 3 E I / L³, I = b h³/12, and Rayleigh's effective mass 33/140 of the beam.
    """
    young_modulus, density, length, width, thickness = (
        check_real("cantilever_frequency", name, value, low=0.0, low_open=True)
        for name, value in (("young_modulus", young_modulus), ("density", density),
                            ("length", length), ("width", width), ("thickness", thickness)))
    tip_mass = check_real("cantilever_frequency", "tip_mass", tip_mass, low=0.0, unit="kg")
    inertia = width * thickness**3 / 12.0
    stiffness = 3.0 * young_modulus * inertia / length**3
    effective_mass = tip_mass + 33.0 / 140.0 * density * width * thickness * length
    return math.sqrt(stiffness / effective_mass) / (2.0 * math.pi)


def paper_frequency_model() -> Southwell:
    """The default f_d1(Ω) of the paper's blade: Southwell with f0 ≈ 194.6 Hz and B = 0.76.

    The paper takes f_d1(Ω) from a finite-element model whose numbers are not published
    (its Fig. 2). We use f0 from ``cantilever_frequency`` with the paper's E, ρ, L, b, h and
    shroud mass, and B = 0.76, which makes the curve pass through the paper's resonance
    point f_d1 = f_e = 216.25 Hz at 6487.5 rpm (l = 2; the paper prints 6847.5 rpm there,
    which l = 2 does not allow). Other speeds differ from the paper's curve by an unknown
    amount: pass ``frequency=`` to ``three_blade_paper`` to use your own.
    """
    f0 = cantilever_frequency(
        young_modulus=PAPER["young_modulus"], density=PAPER["density"],
        length=PAPER["length"], width=PAPER["width"], thickness=PAPER["thickness"],
        tip_mass=PAPER["mass"])
    return Southwell(f0=f0, coefficient=PAPER_SOUTHWELL_COEFFICIENT)


@_named_arguments
def three_blade_paper(*, gamma1: float | None = None, speed_rpm: float = 6000.0,
                      q1: float = 50.0, gap: float | Sequence[float] = 2e-5,
                      alpha: float = math.pi / 3,
                      friction: FrictionLaw | None = ExponentialFriction(
                          mu_static=PAPER["mu_static"], mu_kinetic=PAPER["mu_kinetic"],
                          beta=PAPER["beta"]),
                      normal: NormalLaw | None = None,
                      phases: PhasePattern | Sequence[float] = AntiPhase(),
                      frequency=None, damping: float = PAPER["damping"],
                      mass: float = PAPER["mass"], q0: float = 0.0,
                      engine_order: int = 2) -> Scene:
    """The paper's integrally shrouded group of three blades (§2–3, Figs. 3–4).

    Blades ``"blade1"``, ``"blade2"``, ``"blade3"`` (positions 0, 1, 2; the reference blade
    is ``"blade2"``, position 1) with interfaces (blade1, blade2) and (blade2, blade3).
    Defaults are the paper's: m = 0.082 kg, c = 4 N·s/m, μ_s = 0.5, μ_m = 0.3, β = 5 s/m,
    Δ1 = Δ2 = 0.02 mm, α = π/3, l = 2, anti-phase excitation, Ω = 6000 rpm, q1 = 50 N,
    linear contact springs k_c = γ1 k(Ω) with γ1 = 2.2, and f_d1(Ω) from
    ``paper_frequency_model`` (read its note: the paper's FE curve is not published).

    Parameters
    ----------
    gamma1 : float, optional
        Stiffness ratio γ1 = k_c/k > 0 (default 2.2). Not allowed together with ``normal``.
    speed_rpm : float
        Ω [rev/min].
    q1 : float
        First-harmonic excitation amplitude [N].
    gap : float or (float, float)
        Δ1 and Δ2 [m]; one number sets both.
    alpha : float
        Contact angle α [rad] of both interfaces.
    friction : FrictionLaw or None
        Friction law of both interfaces (None: frictionless).
    normal : NormalLaw, optional
        Normal law of both interfaces, replacing the linear spring γ1 k.
    phases : phase pattern or sequence of float
        φ_i (default anti-phase, φ_{i+1} − φ_i = π).
    frequency : float or frequency model, optional
        f_d1(Ω) of every blade instead of ``paper_frequency_model()``.
    damping, mass, q0, engine_order
        c [N·s/m], m [kg], mean force q0 [N], engine order l.
    """
    if gamma1 is not None and normal is not None:
        raise ValueError("three_blade_paper: give gamma1 (a linear spring k_c = gamma1 k) or "
                         "normal (any normal law), not both")
    blade = Blade(mass=mass, damping=damping,
                  frequency=paper_frequency_model() if frequency is None else frequency)
    if normal is None:
        gamma1 = check_real("three_blade_paper", "gamma1", 2.2 if gamma1 is None else gamma1,
                            low=0.0, low_open=True)
        normal = LinearSpring(stiffness=gamma1 * blade.stiffness_at(speed_rpm))
    gaps = (gap, gap) if not isinstance(gap, Sequence) else tuple(gap)
    if len(gaps) != 2:
        raise ValueError(f"three_blade_paper: gap is one number or two (Δ1, Δ2), got {gap!r}")
    group = BladeGroup()
    for name in ("blade1", "blade2", "blade3"):
        group.add_blade(name, blade)
    for (left, right), delta in zip((("blade1", "blade2"), ("blade2", "blade3")), gaps):
        group.connect(left, right, Interface(gap=delta, angle=alpha, normal=normal,
                                             friction=friction))
    excitation = Excitation(engine_order=engine_order, amplitudes=(q0, q1), phases=phases)
    return Scene(group=group, excitation=excitation, speed_rpm=speed_rpm)


#: The 24-sector bladed disc's parts: per sector a disc node on its spring to the shaft,
#: joined to its neighbours, and a blade of two nodes (root and shrouded tip, the tip with
#: the paper's shroud mass) held by couplings alone. The first blade family lies near the
#: paper blade's 194 Hz; the disc is stiff enough to keep it flat in nodal diameter.
BLADED_DISC = {
    "disc_mass": 0.5, "disc_damping": 5.0, "disc_stiffness": 5e6,  # kg, N·s/m, N/m
    "disc_coupling": 2e6,                                          # N/m
    "root_mass": 0.04, "root_damping": 2.0, "root_coupling": 6e5,  # disc–root
    "tip_mass": PAPER["mass"], "tip_damping": PAPER["damping"], "tip_coupling": 1.6e5,
}


@_named_arguments
def bladed_disc_24(*, speed_rpm: float = 3000.0, engine_order: int = 6, q1: float = 10.0,
                   gap: float = -2e-5, alpha: float = math.pi / 3,
                   contact_stiffness: float = 3e5,
                   friction: FrictionLaw | None = ExponentialFriction(
                       mu_static=PAPER["mu_static"], mu_kinetic=PAPER["mu_kinetic"],
                       beta=PAPER["beta"]),
                   sectors: int = 24) -> Scene:
    """A shrouded bladed disc of 24 sectors forced in engine order (``BLADED_DISC``).

    Each sector is a disc node and a two-node blade (``BladeGroup.bladed_disc``); the
    tips of neighbouring blades meet at shroud interfaces with the paper's contact angle
    and friction and a linear contact spring, assembled with an interference Δ = −0.02 mm
    (a preload: at rest each contact presses with k_c |Δ| sin α ≈ 5 N). The tips carry the
    excitation Q = q1 sin(l Ω t + φ_s), φ_s = 2π l s / N for sector s: engine order l
    excites the nodal diameter l mod N only. With the default l = 6 the shrouds open,
    slip and stick every period; the response peaks near 3100 rpm, where l Ω/60 meets the
    first family's ND-6 mode stiffened by the closed contacts (its frequency lies between
    the open and the stuck limits of ``linear_modes``).
    """
    check_int("bladed_disc_24", "sectors", sectors, low=3, most=MAX_NODES)
    p = BLADED_DISC
    disc = Blade(mass=p["disc_mass"], damping=p["disc_damping"],
                 stiffness=p["disc_stiffness"], excitation_scale=0.0)
    root = Blade(mass=p["root_mass"], damping=p["root_damping"], stiffness=0.0,
                 excitation_scale=0.0)
    tip = Blade(mass=p["tip_mass"], damping=p["tip_damping"], stiffness=0.0)
    shroud = Interface(gap=gap, angle=alpha, normal=LinearSpring(stiffness=contact_stiffness),
                       friction=friction)
    group = BladeGroup.bladed_disc(
        sectors, disc=disc, disc_coupling=Coupling(stiffness=p["disc_coupling"]),
        blade=[root, tip], blade_couplings=[Coupling(stiffness=p["root_coupling"]),
                                            Coupling(stiffness=p["tip_coupling"])],
        shroud=shroud)
    excitation = Excitation(engine_order=engine_order, amplitudes=(0.0, q1),
                            phases=EngineOrderWave())
    return Scene(group=group, excitation=excitation, speed_rpm=speed_rpm)


@_named_arguments
def block_on_belt(*, belt_speed: float = 0.1, normal_force: float = 10.0, mass: float = 1.0,
                  stiffness: float = 1e4, damping: float = 0.0,
                  friction: FrictionLaw = Stribeck(mu_static=0.4, mu_kinetic=0.25,
                                                   stribeck_velocity=0.05),
                  period: float = 0.1) -> Scene:
    """A block on a spring to ground, pressed by ``normal_force`` [N] on a belt moving at
    ``belt_speed`` [m/s] (a ``ConstantVelocity`` node): the classical stick–slip oscillator.

    The belt's face is along x (α = 0, a ``ConstantLoad`` normal law), so friction acts on
    the slip velocity ẋ − V. The block rides with the belt, stuck, until the spring pulls
    with μ_s N (at x = μ_s N / k), breaks away, slides back under the lower kinetic friction
    of a velocity-weakening law, and sticks again when its velocity meets the belt's: a
    self-excited limit cycle. No force excites it; ``period`` [s] is only the unit the run
    counts in (its ``speed_rpm`` is 60/period).
    """
    check_real("block_on_belt", "period", period, low=0.0, low_open=True, unit="s")
    group = BladeGroup().add_blade("block", Blade(mass=mass, damping=damping,
                                                  stiffness=stiffness))
    group.add_prescribed("belt", ConstantVelocity(velocity=belt_speed))
    group.connect("block", "belt", Interface(gap=0.0, angle=0.0,
                                             normal=ConstantLoad(force=normal_force),
                                             friction=friction))
    return Scene(group=group, excitation=NO_EXCITATION, speed_rpm=60.0 / period)


@_named_arguments
def blade_pair(*, tangential_stiffness: float | None = None, q1: float = 60.0) -> Scene:
    """Two blades (0.1 and 0.3 kg, 1e5 and 2e5 N/m) pressed together 0.1 mm at a face
    inclined at 0.6 rad (a 3e5 N/m contact spring, Coulomb μ = 0.3), forced apart in phase
    opposition at ``q1`` [N] and 6000 rpm, so that the contact slips for part of each
    cycle and sticks for the rest; stick rigid, or elastic with ``tangential_stiffness``
    k_t [N/m] (a Jenkins element), which tends to rigid stick as k_t grows."""
    group = BladeGroup().add_blade("a", Blade(mass=0.1, damping=2.0, stiffness=1e5))
    group.add_blade("b", Blade(mass=0.3, damping=3.0, stiffness=2e5))
    group.connect("a", "b", Interface(
        gap=-1e-4, angle=0.6, normal=LinearSpring(stiffness=3e5), friction=Coulomb(mu=0.3),
        tangential_stiffness=tangential_stiffness))
    return Scene(group=group, speed_rpm=6000.0, excitation=Excitation(
        engine_order=1, amplitudes=(0.0, q1), phases=AntiPhase()))


#: The shroud point's displacement per unit modal coordinate of ``modal_blade``'s three
#: modes: flapwise, edgewise and radial rows (the radial one taken with ``dimensions=3``).
SHROUD_SHAPES = ((1.0, 0.25, -0.5), (0.15, 1.0, 0.35), (0.08, -0.12, 0.3))


@_named_arguments
def modal_blade(*, damping_ratio: float = 0.003, dimensions: int = 2) -> Substructure:
    """A blade given by three modes, as an FE modal analysis prints them: first flap
    (180 Hz at rest), edgewise (450 Hz) and second flap (1050 Hz), each stiffening with
    speed by Southwell's law; modal masses 0.06, 0.05, 0.04 kg; the shapes at the shroud
    (``dimensions`` components: flapwise, edgewise and, with 3, radial:
    ``SHROUD_SHAPES``) and at the load point (flapwise)."""
    dimensions = check_int("modal_blade", "dimensions", dimensions, low=2, most=3)
    return Substructure.modal(
        frequencies=[Southwell(f0=180.0, coefficient=3.0), Southwell(f0=450.0, coefficient=1.5),
                     Southwell(f0=1050.0, coefficient=2.0)],
        damping_ratios=damping_ratio, masses=[0.06, 0.05, 0.04],
        shapes={"shroud": [list(row) for row in SHROUD_SHAPES[:dimensions]],
                "load": [[0.7, 0.4, 0.2]]},
        load="load")


@_named_arguments
def modal_packet(*, blades: int = 6, speed_rpm: float = 2800.0, gap: float = -2e-6,
                 face: float = 0.6, contact_stiffness: float = 1e5,
                 friction: FrictionLaw | None = Coulomb(mu=0.3), q1: float = 1.0,
                 engine_order: int = 4, damping_ratio: float = 0.02,
                 normal_law: NormalLaw | None = None,
                 blades_on_disc: int | None = None,
                 tangential_stiffness: float | None = None) -> Scene:
    """A packet of ``blades`` ``modal_blade``s whose shrouds meet on faces inclined at
    ``face`` [rad] to the flapwise direction, each interface a ``contact_stiffness`` [N/m]
    spring (or ``normal_law``) with ``gap`` [m] (negative: a preload) and ``friction``,
    forced by engine order ``engine_order`` at ``q1`` [N] on the load points, on a disc of
    ``blades_on_disc`` blades (by default the packet's own count, as if it were the whole
    disc). The first flap mode meets engine order 4 near 3000 rpm (199.7 Hz).

    With a ``tangential_stiffness`` k_t [N/m] the contacts are elastic and 3-D: the
    shroud points move in three directions (``modal_blade(dimensions=3)``), and each face
    slides in its plane, spanned by its in-plane direction of the flap–edge plane and the
    radial direction, its stick the Jenkins element of that k_t and a circular Coulomb
    limit. Without, the faces slide along the one in-plane direction, stick rigid."""
    normal = (math.cos(face), math.sin(face))
    if normal_law is None:
        normal_law = LinearSpring(stiffness=contact_stiffness)
    if tangential_stiffness is None:
        shroud = Interface(gap=gap, normal=normal_law,
                           friction=friction, normal_direction=normal,
                           tangent_direction=(-normal[1], normal[0]))
        blade = modal_blade(damping_ratio=damping_ratio)
    else:
        shroud = Interface(gap=gap, normal=normal_law, friction=friction,
                           normal_direction=(*normal, 0.0),
                           tangent_directions=((-normal[1], normal[0], 0.0), (0.0, 0.0, 1.0)),
                           tangential_stiffness=tangential_stiffness)
        blade = modal_blade(damping_ratio=damping_ratio, dimensions=3)
    group = BladeGroup()
    blades = check_int("modal_packet", "blades", blades, low=1, most=MAX_NODES)
    names = [f"blade{k}" for k in range(1, blades + 1)]
    for name in names:
        group.add_blade(name, blade)
    for left, right in zip(names, names[1:]):
        group.connect((left, "shroud"), (right, "shroud"), shroud)
    return Scene(group=group, speed_rpm=speed_rpm,
                 excitation=Excitation(engine_order=engine_order, amplitudes=(0.0, q1),
                                       phases=EngineOrderWave(blades_on_disc or blades)))


@_named_arguments
def beam_pair(*, elements: int = 2, gap: float = -2e-6, face: float = 0.5,
              contact_stiffness: float = 1e5, friction: FrictionLaw | None = Coulomb(mu=0.4),
              q1: float = 2.0, blade: Substructure | None = None,
              speed_rpm: float | None = None) -> Scene:
    """Two clamped steel beams (80 × 20 × 3 mm, ``elements`` Euler–Bernoulli elements each,
    unreduced, a 20 g shroud mass at the tip) whose tip shrouds meet on a face inclined at
    ``face`` [rad], preloaded, forced in anti-phase at engine order 2 just above the first
    flap resonance (5 % above it): the contact separates, closes, sticks and slips.

    ``blade`` replaces the beam (a reduced model of it, say, with the points "shroud" and
    "load"), and ``speed_rpm`` the speed 5 % above the blade's first flap resonance."""
    if blade is None:
        blade = cantilever_beam(length=0.08, width=0.02, thickness=0.003,
                                youngs_modulus=2.1e11, density=7800.0, elements=elements,
                                tip_mass=0.02, damping_ratios=0.01)
    normal = (math.cos(face), math.sin(face))
    group = BladeGroup().add_blade("blade1", blade).add_blade("blade2", blade)
    group.connect(("blade1", "shroud"), ("blade2", "shroud"), Interface(
        gap=gap, normal=LinearSpring(stiffness=contact_stiffness), friction=friction,
        normal_direction=normal, tangent_direction=(-normal[1], normal[0])))
    if speed_rpm is None:
        speed_rpm = 1.05 * blade.frequencies_at(0.0)[0] * 60.0 / 2.0
    return Scene(group=group, speed_rpm=speed_rpm,
                 excitation=Excitation(engine_order=2, amplitudes=(0.0, q1),
                                       phases=AntiPhase()))


#: ``faced_blade``'s modes: each one's frequency at rest [Hz] and Southwell coefficient,
#: modal mass [kg], and the rigid motion of its shroud per unit modal coordinate, a
#: translation (radial, tangential, axial) [m] and a rotation about those axes [rad]:
#: first flap, edgewise, shroud twist (about the radial axis) and second flap.
FACED_MODES = (
    ((180.0, 3.0), 0.06, (0.0, 0.4, 1.0), (8.0, 0.0, 0.0)),
    ((450.0, 1.5), 0.05, (0.1, 1.0, -0.3), (-20.0, 0.0, 4.0)),
    ((700.0, 1.0), 0.03, (0.0, 0.15, 0.1), (150.0, 0.0, 0.0)),
    ((1050.0, 2.0), 0.04, (0.05, -0.2, 0.6), (40.0, 6.0, 0.0)),
)
#: Half the shroud's pitch [m] (tangential: where its left and right faces are), and the
#: half-extents [m] of a face, radial and axial.
FACE_PITCH, FACE_HEIGHT, FACE_WIDTH = 4e-3, 2e-3, 6e-3


def face_point_names(side: str, count: int) -> list[str]:
    """The names of ``faced_blade``'s ``count`` points on its ``side`` ("L" or "R")
    face: "L0" … in the order of ``faced_blade``'s grid."""
    side = check_choice("face_point_names", "side", side, ("L", "R"))
    count = check_int("face_point_names", "count", count, low=1, most=MAX_NODES)
    return [f"{side}{k}" for k in range(count)]


@_named_arguments
def faced_blade(*, face_points: int = 9, components: int = 3,
                damping_ratio: float = 0.02) -> Substructure:
    """A blade of four modes, as an FE modal analysis prints them, whose shroud has a left
    and a right face meshed with ``face_points`` points each (a square grid: 1, 4, 9,
    16, …), named "L0" … and "R0" … (``face_point_names``): first flap (180 Hz at rest),
    edgewise (450 Hz), shroud twist (700 Hz) and second flap (1050 Hz), each stiffening by
    Southwell's law (``FACED_MODES``), ``damping_ratio`` in every mode.

    The shroud moves rigidly in each mode: a point p of it moves u + θ × p. The faces lie
    at tangential ∓``FACE_PITCH``, their grids spanning ±``FACE_HEIGHT`` radially and
    ±``FACE_WIDTH`` axially, so that the twist opens one end of a face while it closes the
    other. Components are (radial, tangential, axial): the third along the disc's axis,
    as ``BladeGroup.ring`` turns sectors; with ``components`` 1, each point is its
    tangential displacement alone. The excitation acts at the point "load" (one
    component)."""
    count = check_int("faced_blade", "face_points", face_points, low=1, most=MAX_NODES)
    side = math.isqrt(count)
    if side * side != count:
        raise ValueError(f"faced_blade.face_points must be a square (1, 4, 9, 16, …), a "
                         f"grid of points on each face, got {count}")
    components = check_int("faced_blade", "components", components, low=1, high=3)
    if components == 2:
        raise ValueError("faced_blade.components must be 1 or 3, got 2")
    grid = [(0.0, 0.0)] if side == 1 else [
        (FACE_HEIGHT * (2.0 * i / (side - 1) - 1.0), FACE_WIDTH * (2.0 * j / (side - 1) - 1.0))
        for i in range(side) for j in range(side)]
    points = {}
    for name, tangential in (("L", -FACE_PITCH), ("R", FACE_PITCH)):
        for k, (radial, axial) in enumerate(grid):
            place = (radial, tangential, axial)
            shapes = [[u[c] + _cross(theta, place)[c] for *_, u, theta in FACED_MODES]
                      for c in range(3)]
            points[f"{name}{k}"] = shapes if components == 3 else [shapes[1]]
    points["load"] = [[0.7, 0.4, 0.2, 0.3]]
    return Substructure.modal(
        frequencies=[Southwell(f0=f0, coefficient=b) for (f0, b), *_ in FACED_MODES],
        damping_ratios=damping_ratio, masses=[mass for _, mass, *_ in FACED_MODES],
        shapes=points, load="load")


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


@_named_arguments
def faced_group(*, blades: int = 6, face_points: int = 9, components: int = 3,
                shape: str = "chain", speed_rpm: float = 2900.0, gap: float = -2e-6,
                face: float = 0.6, contact_stiffness: float = 1e5,
                tangential_stiffness: float | None = 3e5,
                friction: FrictionLaw = Coulomb(mu=0.3), q1: float = 1.0,
                engine_order: int = 4, blades_on_disc: int = 36,
                damping_ratio: float = 0.02, frequency: float | None = None,
                tangents: int = 2) -> Scene:
    """``blades`` ``faced_blade``s face to face, as a packet (``shape`` "chain") on a disc
    of ``blades_on_disc`` or a whole ring ("ring"), each blade in its own sector frame,
    turned by 2π/N from the last (``BladeGroup.ring``, ``chain``): blade s's right face
    meets blade s + 1's left face point to point, a patch of ``face_points`` contacts that
    share the interface's stiffnesses (``contact_stiffness`` and, unless None for rigid
    stick, ``tangential_stiffness`` [N/m] in all), so that refining the patch keeps the
    face's total. The faces are inclined at ``face`` [rad] to the tangential direction
    about the radial one; with three components they slide in their plane (``tangents``
    2, elastic stick: ``tangential_stiffness`` is needed) or along its in-plane direction
    of the tangential–axial plane alone (``tangents`` 1, the radial sliding free), with
    one along the tangential direction alone (the angle form, its angle π/2 − ``face``).
    ``gap`` [m] (negative: a preload), ``friction``; engine order ``engine_order`` at
    ``q1`` [N] on the load points, at the frequency l Ω or at ``frequency`` [Hz]
    (``Excitation.frequency``)."""
    count = check_int("faced_group", "face_points", face_points, low=1, most=MAX_NODES)
    blade = faced_blade(face_points=count, components=components, damping_ratio=damping_ratio)
    normal = check_real("faced_group", "contact_stiffness", contact_stiffness, low=0.0,
                        low_open=True, unit="N/m") / count
    tangential = None if tangential_stiffness is None else check_real(
        "faced_group", "tangential_stiffness", tangential_stiffness, low=0.0, low_open=True,
        unit="N/m") / count
    tangents = check_int("faced_group", "tangents", tangents, low=1, high=2)
    if components == 3:
        plane = ((0.0, -math.sin(face), math.cos(face)), (1.0, 0.0, 0.0))[:tangents]
        shroud = Interface(gap=gap, normal=LinearSpring(stiffness=normal), friction=friction,
                           normal_direction=(0.0, math.cos(face), math.sin(face)),
                           tangent_directions=plane, tangential_stiffness=tangential)
    else:
        shroud = Interface(gap=gap, angle=math.pi / 2 - face, normal=LinearSpring(
            stiffness=normal), friction=friction, tangential_stiffness=tangential)
    faces = (face_point_names("L", count), face_point_names("R", count))
    shape = check_choice("faced_group", "shape", shape, ("chain", "ring"))
    blades = check_int("faced_group", "blades", blades, low=1 if shape == "chain" else 3,
                       most=MAX_NODES)
    if shape == "ring":
        group = BladeGroup.ring(blades, blade, shroud, points=faces)
        phases = EngineOrderWave()
    else:
        group = BladeGroup.chain(blades, blade, shroud, points=faces,
                                 blades_on_disc=blades_on_disc)
        phases = EngineOrderWave(blades_on_disc)
    return Scene(group=group, speed_rpm=speed_rpm, excitation=Excitation(
        engine_order=engine_order, amplitudes=(0.0, q1), phases=phases, frequency=frequency))


@_named_arguments
def jenkins_chain(*, q1: float = 20.0, frequency: float = 12.0,
                  tangential_stiffness: float = 2e4, normal_force: float = 30.0,
                  mu: float = 0.3) -> Scene:
    """The 2-DOF friction-damped chain of the harmonic-balance literature: masses of 1 and
    0.5 kg on springs of 1e4 and 5e3 N/m to ground (dampers 2 and 1 N·s/m), joined by
    8e3 N/m (0.5 N·s/m); the first rubs on the ground through a Jenkins element
    (``tangential_stiffness`` k_t [N/m], Coulomb ``mu``, a constant ``normal_force``
    [N]), both forced in phase by ``q1`` [N] at ``frequency`` [Hz]. At the defaults it
    sticks and slips twice a cycle."""
    group = BladeGroup().add_blade("a", Blade(mass=1.0, damping=2.0, stiffness=1e4))
    group.add_blade("b", Blade(mass=0.5, damping=1.0, stiffness=5e3)).add_fixed("ground")
    group.connect("a", "b", Coupling(stiffness=8e3, damping=0.5))
    group.connect("a", "ground", Interface(
        gap=0.0, angle=0.0, normal=ConstantLoad(force=normal_force), friction=Coulomb(mu=mu),
        tangential_stiffness=tangential_stiffness))
    check_real("jenkins_chain", "frequency", frequency, low=0.0, low_open=True, unit="Hz")
    return Scene(group=group, speed_rpm=60.0 * frequency, excitation=Excitation(
        engine_order=1, amplitudes=(0.0, q1), phases=ExplicitPhases((0.0, 0.0))))


@_named_arguments
def modal_pair(*, normal_force: float = 2.0, tangential_stiffness: float = 3e4,
               q1: float = 3.0, speed_rpm: float = 3100.0, mu: float = 0.3) -> Scene:
    """Two ``modal_blade``s of three modes whose 3-D shroud points meet on a face
    inclined at 0.6 rad, pressed by a constant ``normal_force`` [N], sliding in the face's
    plane through a 2-D Jenkins element (``tangential_stiffness`` k_t [N/m], a circular
    Coulomb limit ``mu``), forced in anti-phase in engine order 4 by ``q1`` [N]: at the
    defaults it sticks and slips twice a cycle, below the first flap resonance."""
    blade = modal_blade(dimensions=3)
    normal = (math.cos(0.6), math.sin(0.6))
    group = BladeGroup().add_blade("blade1", blade).add_blade("blade2", blade)
    group.connect(("blade1", "shroud"), ("blade2", "shroud"), Interface(
        gap=0.0, normal=ConstantLoad(force=normal_force), friction=Coulomb(mu=mu),
        normal_direction=(*normal, 0.0),
        tangent_directions=((-normal[1], normal[0], 0.0), (0.0, 0.0, 1.0)),
        tangential_stiffness=tangential_stiffness))
    return Scene(group=group, speed_rpm=speed_rpm, excitation=Excitation(
        engine_order=4, amplitudes=(0.0, q1), phases=AntiPhase()))


@_named_arguments
def mass_on_stop(*, gap: float = 1e-3, normal: NormalLaw = LinearSpring(stiffness=1e5),
                 q1: float = 20.0, frequency: float = 100.0 / (2.0 * math.pi)) -> Scene:
    """A 1 kg mass on a 1e4 N/m spring (2 N·s/m) forced by ``q1`` [N] at ``frequency``
    [Hz] against a rigid stop ``gap`` [m] away, the contact's ``normal`` law (a negative
    gap presses the mass on the stop): at the defaults it hits the stop once a cycle."""
    group = BladeGroup().add_blade("mass", Blade(mass=1.0, damping=2.0, stiffness=1e4))
    group.add_fixed("stop").connect("mass", "stop", Interface(gap=gap, angle=math.pi / 2,
                                                              normal=normal))
    check_real("mass_on_stop", "frequency", frequency, low=0.0, low_open=True, unit="Hz")
    return Scene(group=group, speed_rpm=60.0 * frequency, excitation=Excitation(
        engine_order=1, amplitudes=(0.0, q1), phases=AntiPhase()))
