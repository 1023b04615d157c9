"""Contact laws for shroud interfaces: normal-contact laws N(δ, δ̇) and friction laws μ(|v|).

Laws are small immutable objects that validate their parameters and carry their math as a
static function of plain floats, so a solver can compile them. This package knows nothing of
blades or groups; ``shroudnet`` composes a law of each kind with a gap and an angle.

Normal laws: ``LinearSpring`` (the paper's eqs. 2–3), ``Hertz``, ``KelvinVoigt``,
``HuntCrossley``, ``ConstantLoad``. Friction laws: ``Coulomb``, ``ExponentialFriction``
(the paper's eq. 4), ``Stribeck``, and ``Regularised`` (a tanh-smoothed wrapper).
"""

from ._checks import check_array as check_array
from ._checks import check_callable as check_callable
from ._checks import check_calls_with as check_calls_with
from ._checks import check_choice as check_choice
from ._checks import check_instance as check_instance
from ._checks import check_int as check_int
from ._checks import check_real as check_real
from ._checks import check_sequence as check_sequence
from .base import FrictionLaw as FrictionLaw
from .base import NormalLaw as NormalLaw
from .friction import Coulomb as Coulomb
from .friction import ExponentialFriction as ExponentialFriction
from .friction import Regularised as Regularised
from .friction import Stribeck as Stribeck
from .normal import ConstantLoad as ConstantLoad
from .normal import Hertz as Hertz
from .normal import HuntCrossley as HuntCrossley
from .normal import KelvinVoigt as KelvinVoigt
from .normal import LinearSpring as LinearSpring

#: The built-in laws, registered here and nowhere else: the compiled engine shares one
#: kernel among every combination of them (an exact friction law; ``Regularised`` wraps
#: one of these). A new built-in law is added to one of these tuples.
BUILT_IN_NORMAL = (LinearSpring, Hertz, KelvinVoigt, HuntCrossley, ConstantLoad)
BUILT_IN_FRICTION = (Coulomb, ExponentialFriction, Stribeck)

#: Every public name, so that tools and tests can walk the public surface; a new export
#: is added here too.
__all__ = [
    "check_array",
    "check_callable",
    "check_calls_with",
    "check_choice",
    "check_instance",
    "check_int",
    "check_real",
    "check_sequence",
    "FrictionLaw",
    "NormalLaw",
    "Coulomb",
    "ExponentialFriction",
    "Regularised",
    "Stribeck",
    "ConstantLoad",
    "Hertz",
    "HuntCrossley",
    "KelvinVoigt",
    "LinearSpring",
    "BUILT_IN_NORMAL",
    "BUILT_IN_FRICTION",
]
