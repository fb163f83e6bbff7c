"""riser_tools: everything that drives riser from outside.

* `riser_tools.cli`: the CLI driver (`riser run`/`statics` as subprocesses, JSON and CSV read back);
* `riser_tools.fmu`: the FMU driver (fmpy) and the packaging of fmu/riser.fmu;
* `riser_tools.cases`: motions, the lines of the built-in scenes, cases and grids (checked on creation);
* `riser_tools.reference`: closed-form references (the elastic catenary, the catenary with touchdown);
* `riser_tools.moordyn`: the one MoorDyn v2 driver every peer comparison uses;
* `riser_tools.series`: window statistics and errors of time series;
* `riser_tools.report`: the Markdown helpers of the generated pages;
* `riser_tools.plots`: the figures shared by the studies;
* `riser_tools.studies`: each study behind a page of docs/ (`riser-tools NAME`, or the make target).

The package `riser_sweep` (the `riser-sweep` command: sweeps of the FMU on Dask) ships in the
same distribution, `python/riser_tools`.
"""

__version__ = "0.2.0"
