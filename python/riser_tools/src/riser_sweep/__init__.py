"""riser-sweep: parameter sweeps of fmu/riser.fmu through fmpy on Dask distributed.

    riser-sweep SPEC.toml --out DIR [--scheduler ADDRESS] [--workers N]
    riser-sweep plot DIR
    riser-sweep FATIGUE.toml --out DIR [--riser-bin PATH]   # a [fatigue] spec: a scatter diagram's life

The spec format: riser_sweep.spec. From Python::

    from riser_sweep import load_spec, check_spec_with_fmu, run_sweep
    spec = load_spec("heave4.toml"); check_spec_with_fmu(spec); run_sweep(spec, "out/heave4")
"""

from .case import motion_signal, run_case
from .fatigue import FatigueSpec, load_fatigue_spec, read_scatter, run_fatigue_sweep
from .spec import Spec, SpecError, load_spec
from .sweep import Summary, check_spec_with_fmu, run_sweep

__all__ = ["FatigueSpec", "Spec", "SpecError", "Summary", "check_spec_with_fmu", "load_fatigue_spec", "load_spec",
           "motion_signal", "read_scatter", "run_case", "run_fatigue_sweep", "run_sweep"]
__version__ = "0.1.0"
