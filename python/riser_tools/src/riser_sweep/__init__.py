"""riser-sweep: parameter sweeps of fmu/riser.fmu through fmpy on Dask distributed.

    riser-sweep SPEC.toml --out DIR [--scheduler ADDRESS] [--workers N]
    riser-sweep plot DIR

The spec format: riser_sweep.spec. From Python::

    from riser_sweep import load_spec, check_spec_with_fmu, run_sweep
    spec = load_spec("heave4.toml"); check_spec_with_fmu(spec); run_sweep(spec, "out/heave4")
"""

from .case import motion_signal, run_case
from .spec import Spec, SpecError, load_spec
from .sweep import Summary, check_spec_with_fmu, run_sweep

__all__ = ["Spec", "SpecError", "Summary", "check_spec_with_fmu", "load_spec", "motion_signal", "run_case",
           "run_sweep"]
__version__ = "0.1.0"
