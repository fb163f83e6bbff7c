"""The studies behind the pages of docs/, one module each, run by `riser-tools NAME` (or its make
target). Each writes its page (or its section of a page) and its figures.

How each runs its cases, and why:

* plain loops of `riser run` (riser_tools.cli), where a case's wall time is part of the result and
  must not share the machine with a Dask worker's scheduling, transfers or a second case:
  `study` (speed against accuracy), `noise`, `rho`, `physics-switches`, `moordyn`,
  `moordyn-seabed` (the peer comparisons time both codes on one pinned CPU), `paper` (the
  table's real-time factors), `lowe-langley`, `accuracy` (the accuracy knob's calibration and check:
  its cost is the runs' work, elements x steps x Newton iterations, read from their summaries);
* plain loops where the case is not an FMU run riser-sweep can express: `stability` checks
  the CLI itself (a crash, a hang under a timeout, the "riser: error" of a clean stop, NaN in
  the CSV), which an fmpy run in a worker cannot see; `cosim` feeds the FMU the displacement
  alone (no velocity inputs) at communication steps down to 0.01 s, against `riser run`;
* `bench-cli`: this build's `riser run` against an earlier build's, interleaved;
* riser-sweep itself: `bench-sweep` (its cost against a plain loop; the 48 cases are a spec).

None of these grids is large: the longest (`study`, about 500 runs) is long because each run is,
not because there are many; a sweep on a cluster is what riser-sweep is for.
"""

COMMANDS = {
    "demo": ("riser_tools.studies.demo", "the paper's catenary case through the FMU, then on the 6-DOF vessel "
                                        "FMU in libcosim (make demo)"),
    "plot-statics": ("riser_tools.plots", "plot shape.csv of `riser statics --out` (make demo)"),
    "plot-fatigue": ("riser_tools.fatigue_plot", "plot fatigue.csv of `riser run --fatigue CURVE --out` (damage along the line)"),
    "paper": ("riser_tools.studies.paper", "the seed paper's runs (make paper)"),
    "study": ("riser_tools.studies.speed_accuracy", "speed against accuracy (make study)"),
    "noise": ("riser_tools.studies.noise", "tension noise and numerical dissipation (make noise)"),
    "stability": ("riser_tools.studies.stability", "the stability matrix (make stability)"),
    "cosim": ("riser_tools.studies.cosim", "co-simulation fidelity against the communication step"),
    "coupling": ("riser_tools.coupling_analysis", "the input path in a vessel–riser loop: stability, noise (docs/coupling.md)"),
    "coupling-loop": ("riser_tools.coupling_loop", "two-way runs of riser with a vessel and a buoy (Jacobi master loop)"),
    "coupling-mono": ("riser_tools.coupling_mono", "two-way libcosim runs of a heave–pitch body against the monolithic reference (issue 53, docs/coupling.md)"),
    "rho": ("riser_tools.studies.rho", "choosing rho_infinity"),
    "physics-switches": ("riser_tools.studies.physics_switches", "the cost of each physics switch"),
    "moordyn": ("riser_tools.studies.moordyn_compare", "MoorDyn on the catenary scene (make moordyn)"),
    "moordyn-seabed": ("riser_tools.studies.moordyn_seabed", "MoorDyn on the steel catenary (make moordyn-seabed)"),
    "moordyn-system": ("riser_tools.studies.moordyn_system", "OC3-Hywind's mooring under a prescribed vessel motion against "
                                                            "MoorDyn-C (docs/system_moordyn.md)"),
    "lowe-langley": ("riser_tools.studies.lowe_langley", "the Lowe & Langley jumper (make lowe-langley)"),
    "accuracy": ("riser_tools.studies.accuracy", "the accuracy study: the grid of orders, the measured choice on its cases and new scenes (make accuracy)"),
    "accuracy-ref": ("riser_tools.studies.accuracy_ref", "the accuracy study's references at shorter steps: the references' floor (docs/accuracy.md)"),
    "bench-sweep": ("riser_tools.studies.bench_sweep", "riser-sweep against a plain loop (make bench-sweep)"),
    "bench-cli": ("riser_tools.studies.bench_cli", "the command line against an earlier build, interleaved: wall time, "
                                                 "instructions, the same bytes (docs/performance.md)"),
    "bench-fmu": ("riser_tools.studies.bench_fmu", "the FMU against an earlier build's through fmpy, interleaved: wall "
                                                 "time, top_tension bit for bit (docs/performance.md)"),
    "package-fmu": ("riser_tools.fmu", "package fmu/riser.fmu (make fmu)"),
    "interface-doc": ("riser_tools.interface_doc", "write or check docs/interface.md"),
    "fuzz": ("riser_tools.fuzz", "the long fuzz run of the FMU's C ABI (make fuzz)"),
    "valgrind": ("riser_tools.valgrind", "riser.so under valgrind memcheck (make valgrind)"),
}
