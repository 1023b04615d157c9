"""Result files: simulations, sweeps and branches saved and loaded without loss.

The public face of ``shroudnet.io.results`` (where the formats are documented): every name
a user calls, under the path it has always had.
"""

from .io.results import FORMAT as FORMAT
from .io.results import ResultsError as ResultsError
from .io.results import SimulationArrays as SimulationArrays
from .io.results import SweepStore as SweepStore
from .io.results import atomic_write as atomic_write
from .io.results import load as load
from .io.results import load_arrays as load_arrays
from .io.results import load_branch as load_branch
from .io.results import load_run_settings as load_run_settings
from .io.results import load_simulation as load_simulation
from .io.results import load_sweep as load_sweep
from .io.results import open_sweep_store as open_sweep_store
from .io.results import save_branch as save_branch
from .io.results import save_simulation as save_simulation

__all__ = ["FORMAT", "ResultsError", "SimulationArrays", "SweepStore", "atomic_write", "load",
           "load_arrays", "load_branch", "load_run_settings", "load_simulation", "load_sweep",
           "open_sweep_store", "save_branch", "save_simulation"]
