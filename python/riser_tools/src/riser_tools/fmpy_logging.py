"""An fmpy instance with a Python logger that cannot crash the process later.

fmpy formats an FMU's variadic log message in a native proxy
(`fmpy.logging.addLoggerProxy`, which `fmpy.simulation.instantiate_fmu` calls
when given a `logger`). The proxy keeps ONE process-wide pointer to the last
Python logger it was given and calls it for every later message of every
instance in the process, including instances made with fmpy's default
callbacks. When the instance that brought the logger is freed, its ctypes
callback is freed with it and that pointer dangles: the next message any FMU
logs in the process (an error, say) jumps into freed memory and the process
dies of a segmentation fault. Seen in `make test` under pytest-xdist: a
sweep's spec check (riser_sweep.spec) ran first in a worker, and a later
test's expected fmi2Error killed it.

`instantiate_logged` keeps the callbacks of the last instance it made alive
for the rest of the process: the proxy points at them until another logger
replaces them.
"""

from __future__ import annotations

from typing import Any, Callable

# the callbacks (and so the ctypes logger) the proxy last pointed at
_KEPT: list[Any] = [None]


def instantiate_logged(unzipdir: str, model_description: Any, logger: Callable[..., None], **kwargs: Any) -> Any:
    """`fmpy.simulation.instantiate_fmu(unzipdir, md, "CoSimulation", logger=logger, **kwargs)`,
    its logger kept alive after the instance is freed (see the module's docstring)."""
    from fmpy.simulation import instantiate_fmu

    fmu = instantiate_fmu(unzipdir, model_description, "CoSimulation", logger=logger, **kwargs)
    _KEPT[0] = fmu.callbacks
    return fmu
