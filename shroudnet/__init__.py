"""shroudnet: nonlinear forced vibration of shrouded blade groups that rub and impact.

Vocabulary, used the same way throughout:

blade
    A node of the group: a lumped mass m on a spring k(Ω) ≥ 0 with damping c, displaced by
    x in the tangential direction. A fixed node (disc, casing, damper platform) has x ≡ 0.
interface
    An edge of the group: two shrouds that may touch, with a gap Δ, a contact angle α, a
    normal-contact law and a friction law (``contact_laws``).
coupling
    An edge of the group that is structure, not contact: a linear spring and damper between
    two nodes (a disc sector, a blade's root and tip).
prescribed-motion node
    A node whose displacement is a given function of time (a belt, a shaker): it stands
    wherever a fixed node may, and friction against it acts on the relative velocity.
gap, penetration
    Δ is the clearance at rest (negative: preload); penetration δ = (x_i − x_j − Δ) sin α.
normal force, friction force
    N = N(δ, δ̇) ≥ 0 while the contact is closed; f = μ(|v|) N sgn(v) while slipping, any
    |f| ≤ μ_s N while stuck.
slip velocity, slip displacement
    v = (ẋ_i − ẋ_j) cos α, and u_t = (x_i − x_j) cos α, whose rate it is (between points of
    substructures, t·(ṙ_a − ṙ_b) and t·(r_a − r_b)).
stick cluster
    Blades joined by stuck interfaces, moving as one body.
engine order, excitation period
    l, the number of excitation cycles per revolution; T_e = 2π/(l Ω).

Units are SI throughout, except rotating speeds, given in rev/min where a name ends in
``_rpm``. Equation numbers refer to the reference paper, *Dynamic analysis of integrally
shrouded group blades with rubbing and impact*.
"""

from . import scenes as scenes
from .analysis.readings import Campbell as Campbell
from .analysis.readings import HysteresisLoop as HysteresisLoop
from .analysis.readings import PatchHistory as PatchHistory
from .analysis.readings import Spectrum as Spectrum
from .analysis.readings import amplitude_spectrum as amplitude_spectrum
from .analysis.readings import campbell as campbell
from .analysis.readings import classify as classify
from .analysis.readings import classify_section as classify_section
from .analysis.readings import friction_loss_per_cycle as friction_loss_per_cycle
from .analysis.readings import hysteresis_loop as hysteresis_loop
from .analysis.readings import patch_history as patch_history
from .analysis.readings import spectrum as spectrum
from .analysis.readings import zero_one_test as zero_one_test
from .analysis.stability import LyapunovExponents as LyapunovExponents
from .analysis.stability import lyapunov as lyapunov
from .analysis.stability import monodromy as monodromy
from .engine.assembly import Assembly as Assembly
from .engine.assembly import assemble as assemble
from .engine.clusters import stick_clusters as stick_clusters
from .engine.codes import EventKind as EventKind
from .engine.codes import Mode as Mode
from .front.studies import mistuning_study as mistuning_study
from .front.studies import sweep as sweep
from .front.studies import sweep_map as sweep_map
from .linear.modes import GroupCampbell as GroupCampbell
from .linear.modes import LinearModes as LinearModes
from .linear.modes import group_campbell as group_campbell
from .linear.modes import linear_modes as linear_modes
from .linear.response import FrequencyResponse as FrequencyResponse
from .linear.response import frequency_response as frequency_response
from .model.beam import cantilever_beam as cantilever_beam
from .model.blade import Blade as Blade
from .model.blade import ConstantFrequency as ConstantFrequency
from .model.blade import FrequencyTable as FrequencyTable
from .model.blade import Southwell as Southwell
from .model.coupling import Coupling as Coupling
from .model.excitation import AntiPhase as AntiPhase
from .model.excitation import EngineOrderWave as EngineOrderWave
from .model.excitation import Excitation as Excitation
from .model.excitation import ExplicitPhases as ExplicitPhases
from .model.excitation import TravellingWave as TravellingWave
from .model.group import BladeGroup as BladeGroup
from .model.interface import Interface as Interface
from .model.matrix_files import read_matrices as read_matrices
from .model.motion import ConstantVelocity as ConstantVelocity
from .model.motion import HarmonicMotion as HarmonicMotion
from .model.motion import MotionTable as MotionTable
from .model.reduction import craig_bampton as craig_bampton
from .model.reduction import modal_truncation as modal_truncation
from .model.scene import Scene as Scene
from .model.scene import SceneArrays as SceneArrays
from .model.substructure import Substructure as Substructure
from .run.classification import Classification as Classification
from .run.methods import Accuracy as Accuracy
from .run.methods import Adaptive as Adaptive
from .run.methods import Exponential as Exponential
from .run.methods import FixedStep as FixedStep
from .run.methods import ZenoGuard as ZenoGuard
from .run.simulate import simulate as simulate
from .run.simulation import EnergyLedger as EnergyLedger
from .run.simulation import EventLog as EventLog
from .run.simulation import Simulation as Simulation
from .run.simulation import SimulationError as SimulationError
from .run.simulation import Sweep as Sweep
from .run.simulation import SweepFailure as SweepFailure
from .run.simulation import SweepMap as SweepMap
from .run.simulation import SweepPoint as SweepPoint
from .steady.continuation import Bifurcation as Bifurcation
from .steady.continuation import Branch as Branch
from .steady.continuation import continuation as continuation
from .steady.harmonic.balance import harmonic_balance as harmonic_balance
from .steady.harmonic.certificate import Certificate as Certificate
from .steady.harmonic.certificate import certify as certify
from .steady.harmonic.continuation import harmonic_continuation as harmonic_continuation
from .steady.harmonic.orbit import HarmonicOrbit as HarmonicOrbit
from .steady.orbits import ConvergenceError as ConvergenceError
from .steady.orbits import PeriodicOrbit as PeriodicOrbit
from .steady.orbits import periodic_orbit as periodic_orbit
from .studies.mistuning import MistuningStudy as MistuningStudy

#: Every public name, so that tools and tests can walk the public surface; a new export
#: is added here too.
__all__ = [
    "scenes",
    "Campbell",
    "Spectrum",
    "amplitude_spectrum",
    "campbell",
    "classify",
    "classify_section",
    "HysteresisLoop",
    "friction_loss_per_cycle",
    "hysteresis_loop",
    "PatchHistory",
    "patch_history",
    "spectrum",
    "zero_one_test",
    "cantilever_beam",
    "Blade",
    "ConstantFrequency",
    "FrequencyTable",
    "Southwell",
    "Classification",
    "Bifurcation",
    "Branch",
    "continuation",
    "Certificate",
    "certify",
    "harmonic_balance",
    "harmonic_continuation",
    "HarmonicOrbit",
    "Coupling",
    "stick_clusters",
    "Assembly",
    "assemble",
    "AntiPhase",
    "EngineOrderWave",
    "Excitation",
    "ExplicitPhases",
    "TravellingWave",
    "read_matrices",
    "BladeGroup",
    "Interface",
    "GroupCampbell",
    "LinearModes",
    "group_campbell",
    "linear_modes",
    "FrequencyResponse",
    "frequency_response",
    "Accuracy",
    "MistuningStudy",
    "mistuning_study",
    "ConstantVelocity",
    "HarmonicMotion",
    "MotionTable",
    "Adaptive",
    "Exponential",
    "FixedStep",
    "ZenoGuard",
    "Mode",
    "ConvergenceError",
    "PeriodicOrbit",
    "periodic_orbit",
    "craig_bampton",
    "modal_truncation",
    "Scene",
    "SceneArrays",
    "simulate",
    "LyapunovExponents",
    "lyapunov",
    "monodromy",
    "Substructure",
    "EnergyLedger",
    "EventKind",
    "EventLog",
    "Simulation",
    "SimulationError",
    "Sweep",
    "SweepFailure",
    "SweepMap",
    "SweepPoint",
    "sweep",
    "sweep_map",
]
