"""A clamped–free beam blade in two bending planes: a substructure to try things with.

The finite elements are two-node beam elements with a transverse displacement and a section
rotation per node and plane. Their shape functions solve the static beam equations exactly
(cubic displacement; with shear, the rotation follows the "interdependent interpolation" of
Friedman & Kosmatka, Comput. Struct. 47, 1993), so the Euler–Bernoulli element is the
classical Hermite one and the Timoshenko element is free of shear locking. Element matrices
are integrated by Gauss quadrature, exactly for the polynomials involved.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse

from contact_laws import check_int, check_real

from .substructure import Substructure

#: Degrees of freedom per node, in this order: flapwise v, θ_z; edgewise w, θ_y.
NODE_DOFS = ("v", "theta_z", "w", "theta_y")
#: The most elements a beam may have: 4 degrees of freedom each, assembled sparse.
MAX_ELEMENTS = 100_000
#: The largest tip mass, as a multiple of the beam's own mass ρAL, whose mass matrix a
#: float still resolves (its eigenvalues span that ratio).
TIP_MASS_RATIO = 1e12
#: The largest ratio of an element's rotational to translational entries (L_e² or its
#: inverse, in m²) that the beam's matrices are built with: beyond it their eigenvalues
#: (and the positive definiteness of M) are lost to rounding.
ELEMENT_SPREAD = 1e12
#: Gauss–Legendre points on [0, 1]: five integrate the degree-8 products exactly.
_GAUSS_POINTS, _GAUSS_WEIGHTS = np.polynomial.legendre.leggauss(5)
_GAUSS_POINTS = 0.5 * (_GAUSS_POINTS + 1.0)
_GAUSS_WEIGHTS = 0.5 * _GAUSS_WEIGHTS


def cantilever_beam(*, length: float, youngs_modulus: float, density: float,
                    width: float | None = None, thickness: float | None = None,
                    area: float | None = None,
                    second_moments: tuple[float, float] | None = None, elements: int = 10,
                    shear_modulus: float | None = None, shear_coefficient: float = 5.0 / 6.0,
                    tip_mass: float = 0.0, damping_ratios=0.0, load_position: float = 1.0,
                    hub_radius: float | None = None,
                    excitation_scale: float = 1.0) -> Substructure:
    """A uniform blade clamped at its root, bending flapwise and edgewise, as a Substructure.

    ::

              root (clamped)                          tip (tip mass, point "shroud")
        hub ──┤███████████████████████████████████████│ ──▶ x (radial)
              x = 0                                   x = L
                              │ v: flapwise, along the thickness h (the weak direction)
        section:  ┌───────────┐
                  │           │ h                w: edgewise, along the width b
                  └───────────┘
                        b

    Each node j = 1 … ``elements`` (the clamped root node removed) carries, in this order,
    (v, θ_z, w, θ_y): the flapwise displacement v [m] and its section rotation θ_z ≈ dv/dx
    [rad], the edgewise displacement w [m] and its section rotation θ_y ≈ dw/dx [rad]; both
    rotations are slopes, so the two planes use the same element. DOF 4 (j − 1) + k is
    component k of node j; n = 4 × ``elements``.

    Parameters
    ----------
    length : float
        L > 0 [m].
    youngs_modulus, density : float
        E > 0 [Pa] and ρ > 0 [kg/m³].
    width, thickness : float, optional
        b, h > 0 [m] of a rectangular section: A = b h, I_flap = b h³/12, I_edge = h b³/12.
    area, second_moments : float and (float, float), optional
        A > 0 [m²] and (I_flap, I_edge) > 0 [m⁴] of any other section, instead of b and h.
    elements : int
        The number of equal elements, ≥ 1.
    shear_modulus : float, optional
        G > 0 [Pa]. None: Euler–Bernoulli elements (no shear, no rotary inertia). Given:
        Timoshenko elements, with shear stiffness κ G A and rotary inertia ρ I.
    shear_coefficient : float
        κ > 0 [-] of the Timoshenko elements (5/6 for a rectangle).
    tip_mass : float
        m_tip ≥ 0 [kg], a lumped shroud mass at the tip, translational (both planes).
    damping_ratios : float or sequence of float
        Modal damping ζ ≥ 0 (``Substructure.damping_ratios``); 0 is undamped.
    load_position : float
        ξ ∈ (0, 1], where the point "load" sits, as a fraction of L from the root.
    hub_radius : float, optional
        R ≥ 0 [m], the radius of the root. Given: centrifugal stiffening K₁ (the
        ``stiffness_speed``) from the tension T(x) = ρ A Ω² [(R + L)² − (R + x)²]/2 +
        m_tip Ω² (R + L), as the geometric stiffness ∫ T v'² dx in both planes (spin
        softening, which depends on how the blade is set in the disc, is left out). None:
        no stiffening.
    excitation_scale : float
        As for ``Substructure``.

    Returns
    -------
    Substructure
        Sparse M, K₀ (and K₁); points ``"shroud"`` (d = 2: the tip's (v, w)) and ``"load"``
        (d = 1: v at ξ L, interpolated with the element's shape functions); the load is the
        point "load".

    Examples
    --------
    >>> beam = cantilever_beam(length=0.1, width=0.02, thickness=0.004,
    ...                        youngs_modulus=2.0e11, density=7800.0, elements=20)
    >>> round(float(beam.frequencies_at(0.0)[0]), 1)   # 1.875² √(EI/ρAL⁴) / 2π
    327.2
    """
    owner = "cantilever_beam"
    length = check_real(owner, "length", length, low=0.0, low_open=True, unit="m")
    modulus = check_real(owner, "youngs_modulus", youngs_modulus, low=0.0, low_open=True,
                         unit="Pa")
    density = check_real(owner, "density", density, low=0.0, low_open=True, unit="kg/m³")
    try:
        area, flap, edge = _section(owner, width, thickness, area, second_moments)
    except OverflowError:
        raise ValueError(f"{owner}: the section (width = {width}, thickness = {thickness}, "
                         f"area = {area}, second_moments = {second_moments}) overflows a "
                         "float: check its units [m]") from None
    elements = check_int(owner, "elements", elements, low=1, most=MAX_ELEMENTS)
    shear = None
    if shear_modulus is not None:
        shear = check_real(owner, "shear_modulus", shear_modulus, low=0.0, low_open=True,
                           unit="Pa")
        shear *= check_real(owner, "shear_coefficient", shear_coefficient, low=0.0,
                            low_open=True)
    tip_mass = check_real(owner, "tip_mass", tip_mass, low=0.0, unit="kg")
    position = check_real(owner, "load_position", load_position, low=0.0, low_open=True,
                          high=1.0)
    if hub_radius is not None:
        hub_radius = check_real(owner, "hub_radius", hub_radius, low=0.0, unit="m")

    size, step = 4 * elements, length / elements
    spread = max(step, 1.0 / step) ** 2
    if spread > ELEMENT_SPREAD:
        raise ValueError(f"{owner}: length = {length:g} m over {elements} elements makes "
                         f"elements of {step:g} m, whose rotational and translational "
                         f"mass and stiffness entries differ by {spread:.1e} [m²], more than "
                         f"{ELEMENT_SPREAD:g}, beyond what the eigenvalues resolve: check "
                         "the length's units [m]")
    mass, stiffness, speed = ([], [], [])
    try:
        with np.errstate(over="raise", invalid="raise"):
            for plane, inertia in ((0, flap), (2, edge)):
                shape = _ElementShape(step, modulus * inertia,
                                      None if shear is None else shear * area)
                # Euler–Bernoulli elements carry no rotary inertia, like the classical beam
                # theory.
                element_m = shape.mass(density * area,
                                       0.0 if shear is None else density * inertia)
                element_k = shape.stiffness()
                for e in range(elements):
                    dofs = _element_dofs(e, plane)
                    mass.append((dofs, element_m))
                    stiffness.append((dofs, element_k))
                    if hub_radius is not None:
                        speed.append((dofs, shape.geometric(
                            _tension(density * area, tip_mass, hub_radius, length, e * step))))
            load = _flapwise_point(position, elements, step, modulus * flap,
                                   None if shear is None else shear * area)
    except (OverflowError, FloatingPointError, ZeroDivisionError):
        mass = None
    if mass is None or not all(np.isfinite(matrix).all() for _, matrix in mass + stiffness
                               + speed) or not np.isfinite(load).all() \
            or tip_mass > TIP_MASS_RATIO * density * area * length:
        raise ValueError(f"{owner}: length = {length:g} m, youngs_modulus = {modulus:g} Pa, "
                         f"density = {density:g} kg/m³, tip_mass = {tip_mass:g} kg and "
                         f"hub_radius = {hub_radius} m give mass or stiffness entries that a "
                         "float cannot resolve (beyond its range, or a tip mass more than "
                         f"{TIP_MASS_RATIO:g} times the beam's): check their units")
    tip = size - 4
    mass_matrix = _assemble(mass, size)
    if tip_mass:
        mass_matrix = mass_matrix + scipy.sparse.csr_array(
            ([tip_mass, tip_mass], ([tip, tip + 2], [tip, tip + 2])), shape=(size, size))
    shroud = np.zeros((2, size))
    shroud[0, tip], shroud[1, tip + 2] = 1.0, 1.0
    return Substructure(
        mass_matrix, _assemble(stiffness, size), damping_ratios=damping_ratios,
        stiffness_speed=None if hub_radius is None else _assemble(speed, size),
        points={"shroud": shroud, "load": load}, load="load",
        excitation_scale=excitation_scale)


def _section(owner, width, thickness, area, second_moments):
    """A, I_flap, I_edge from exactly one of (width, thickness) and (area, second_moments)."""
    rectangle = width is not None or thickness is not None
    general = area is not None or second_moments is not None
    if rectangle == general:
        raise ValueError(f"{owner} needs exactly one section: width= and thickness= [m], or "
                         "area= [m²] and second_moments=(I_flap, I_edge) [m⁴]")
    if rectangle:
        if width is None or thickness is None:
            raise ValueError(f"{owner} needs both width= and thickness= for a rectangle")
        b = check_real(owner, "width", width, low=0.0, low_open=True, unit="m")
        h = check_real(owner, "thickness", thickness, low=0.0, low_open=True, unit="m")
        return b * h, b * h**3 / 12.0, h * b**3 / 12.0
    if area is None or second_moments is None:
        raise ValueError(f"{owner} needs both area= and second_moments=(I_flap, I_edge)")
    if isinstance(second_moments, str) or np.shape(second_moments) != (2,):
        raise ValueError(f"{owner}.second_moments must be a pair (I_flap, I_edge) [m⁴], got "
                         f"{second_moments!r}")
    area = check_real(owner, "area", area, low=0.0, low_open=True, unit="m²")
    flap, edge = (check_real(owner, "second_moments", value, low=0.0, low_open=True,
                             unit="m⁴") for value in second_moments)
    return area, flap, edge


class _ElementShape:
    """The shape functions of a beam element of length l in one plane, which solve the static
    beam equations: v(x) = [1, x, x², x³] a, θ(x) = [0, 1, 2x, 3x² + c] a with c = 6EI/κGA
    (c = 0: Euler–Bernoulli, θ = v'), a = A⁻¹ (v₁, θ₁, v₂, θ₂). The shear strain
    γ = v' − θ = −c a₃ is constant."""

    def __init__(self, step: float, bending: float, shear: float | None):
        self.step, self.bending, self.shear = step, bending, 0.0 if shear is None else shear
        self.c = 0.0 if shear is None else 6.0 * bending / shear
        c, length = self.c, step
        self.coefficients = np.linalg.inv(np.array([
            [1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, c],
            [1.0, length, length**2, length**3], [0.0, 1.0, 2.0 * length, 3.0 * length**2 + c]]))

    def displacement(self, x: float) -> np.ndarray:
        """N_v(x): v(x) = N_v · (v₁, θ₁, v₂, θ₂)."""
        return np.array([1.0, x, x**2, x**3]) @ self.coefficients

    def _fields(self, x: float):
        a = self.coefficients
        return (np.array([1.0, x, x**2, x**3]) @ a,                 # v
                np.array([0.0, 1.0, 2.0 * x, 3.0 * x**2]) @ a,      # v'
                np.array([0.0, 1.0, 2.0 * x, 3.0 * x**2 + self.c]) @ a,  # θ
                np.array([0.0, 0.0, 2.0, 6.0 * x]) @ a,             # θ'
                np.array([0.0, 0.0, 0.0, -self.c]) @ a)             # γ = v' − θ

    def _integrate(self, integrand) -> np.ndarray:
        return sum(w * self.step * integrand(x * self.step, *self._fields(x * self.step))
                   for x, w in zip(_GAUSS_POINTS, _GAUSS_WEIGHTS))

    def stiffness(self) -> np.ndarray:
        """∫ (EI θ'ᵀθ' + κGA γᵀγ) dx."""
        bending, shear = self.bending, self.shear
        return self._integrate(lambda x, v, dv, theta, dtheta, gamma:
                               bending * np.outer(dtheta, dtheta) + shear * np.outer(gamma, gamma))

    def mass(self, linear: float, rotary: float) -> np.ndarray:
        """∫ (ρA vᵀv + ρI θᵀθ) dx."""
        return self._integrate(lambda x, v, dv, theta, dtheta, gamma:
                               linear * np.outer(v, v) + rotary * np.outer(theta, theta))

    def geometric(self, tension) -> np.ndarray:
        """∫ T(x) v'ᵀv' dx, with ``tension(x)`` on the element (x from its first node)."""
        return self._integrate(lambda x, v, dv, theta, dtheta, gamma:
                               tension(x) * np.outer(dv, dv))


def _tension(linear: float, tip_mass: float, hub: float, length: float, start: float):
    """T(x)/Ω² [N·s²] on the element starting at ``start``: the centrifugal force of the
    blade outboard of x and of the tip mass."""
    tip = hub + length
    return lambda x: linear * (tip**2 - (hub + start + x) ** 2) / 2.0 + tip_mass * tip


def _element_dofs(element: int, plane: int) -> np.ndarray:
    """The global DOFs (displacement, rotation of node e, then of node e + 1) of one plane
    (0: flapwise, 2: edgewise); the clamped root node's are −1."""
    first = 4 * (element - 1) + plane
    return np.array([first, first + 1, first + 4, first + 5])


def _assemble(blocks, size: int) -> scipy.sparse.csr_array:
    rows, columns, values = [], [], []
    for dofs, block in blocks:
        kept = dofs >= 0
        local = np.flatnonzero(kept)
        rows.append(np.repeat(dofs[kept], kept.sum()))
        columns.append(np.tile(dofs[kept], kept.sum()))
        values.append(block[np.ix_(local, local)].ravel())
    matrix = scipy.sparse.coo_array(
        (np.concatenate(values), (np.concatenate(rows), np.concatenate(columns))),
        shape=(size, size)).tocsr()
    matrix.sum_duplicates()
    return matrix


def _flapwise_point(position: float, elements: int, step: float, bending: float,
                    shear: float | None) -> np.ndarray:
    """The row Φ of v(ξ L) = Φ q, from the shape functions of the element holding ξ L."""
    element = min(int(math.floor(position * elements)), elements - 1)
    local = position * elements * step - element * step
    values = _ElementShape(step, bending, shear).displacement(local)
    row = np.zeros(4 * elements)
    dofs = _element_dofs(element, 0)
    kept = dofs >= 0
    row[dofs[kept]] = values[kept]
    return row
