"""A seeded fuzz test of the FMU's C ABI (the robustness issue): 400 random FMI
call sequences (seeds 20261125 .. 20261524, about 55,000 calls) through
fmpy's FMU2Slave functions, each in a forked child, two at a time. The
generator, the oracle and the runner are in riser_tools.fmi_fuzz; the long run is
`riser-tools fuzz` (`make fuzz`); both are described in docs/fuzz.md.

Asserted for every sequence: no crash (death by a signal); no hang (30 s per
sequence); no getter returning fmi2OK/fmi2Warning with a NaN or an infinity;
no fmi2Fatal; no fmi2GetReal of valid outputs failing right after the FMU
accepted a state (an OK step, initialisation or fmi2SetFMUstate); and
afterwards fmi2Reset (or a fresh instance where the sequence freed one) leads
to a normal run: n_elements = 10, setup at 0, initialisation, three 0.1 s
steps with a small heave, every call fmi2OK and every output finite.

Measured: 32.7 s for the 400 sequences on the 2-core machine (load average
1.9 from other work; 71 s under a load average of 4.5). The test stops
starting new sequences after 10 failing ones, so a broken FMU fails in
bounded time. One sequence call by call:
`.venv/bin/riser-tools fuzz --replay SEED`; shrunk to the calls
that matter: `--minimize SEED`.
"""

import time

import pytest
from riser_tools.fmi_fuzz import Library, run_many, seeds, tally

BASE_SEED = 20261125
SEQUENCES = 400
TIMEOUT = 30.0
MAX_FAILURES = 10


def test_random_fmi_call_sequences_never_crash_hang_or_return_ok_with_non_finite_values(unzipped):
    lib = Library(unzipped)
    t0 = time.monotonic()
    outcomes = run_many(lib, seeds(BASE_SEED, SEQUENCES), jobs=2, timeout=TIMEOUT, max_failures=MAX_FAILURES)
    seconds = time.monotonic() - t0
    bad = sorted((o for o in outcomes if o.kind != "ok"), key=lambda o: o.seed)
    counts = tally(outcomes)
    report = [f"{len(outcomes)} of {SEQUENCES} sequences run in {seconds:.0f} s: {counts}"]
    for o in bad:
        report.append(o.summary())
        for f in o.failures[1:3]:
            report.append(f"    also: {f['call']} -> {f['status']}: {f['detail']}")
    report.append("replay one: .venv/bin/riser-tools fuzz --replay SEED  "
                  "(shrink it: --minimize SEED)")
    if bad:
        pytest.fail("\n".join(report), pytrace=False)
    assert len(outcomes) == SEQUENCES
