"""A seeded fuzzer of riser.fmu's FMI 2.0 C ABI, shared by tests/python/test_fuzz.py
(a few hundred sequences in `make test`) and riser_tools.fuzz (`riser-tools fuzz`, `make fuzz`: thousands,
replay, minimisation).

One *sequence* is a seed: a deterministic random walk of FMI calls over one or
two interleaved instances of one loaded riser.so, as a buggy co-simulation
master might make them: calls in and out of order, valid and invalid value
references, values from a pool (0, -0.0, ±1, NaN, ±inf, 5e-324, 1e-300, 9e15,
±1e308 and realistic ones: the start values scaled by 0.5..2), step sizes
from {0, -1, 1e-12, 1e-6, 0.01, 0.05, 0.3, 1, 7, 1e300, NaN, inf} at the right
or a wrong time, scene strings (built-in names, garbage TOML files, valid TOML
with hostile numbers, missing files, empty, non-UTF-8), n_elements mostly
4..20 but also huge, FMU states got, set, freed, serialized and deserialized
from corrupted blobs (truncated, flipped, random, empty, and re-checksummed
with hostile numbers inside), reset, terminate, free. The generator follows the
statuses the FMU returns (so it reaches the stepping states), and the calls are
plain data (`Call`) so that a recorded sequence can be replayed and shrunk.

The oracle, per sequence:
  * no crash (the sequence runs in a forked child; death by a signal fails);
  * no hang (a per-sequence time limit);
  * no getter (fmi2GetReal, fmi2GetRealStatus, fmi2GetDirectionalDerivative,
    fmi2GetRealOutputDerivatives) returns fmi2OK or fmi2Warning with a
    non-finite value;
  * no fmi2Fatal (riser returns it only for a panic caught at the boundary);
  * the outputs of a state the FMU accepted are readable: fmi2GetReal of
    valid output or input references does not fail after an fmi2DoStep,
    fmi2ExitInitializationMode or fmi2SetFMUstate that returned OK (or a
    step that returned Discard): a non-finite state is refused where it
    arises, not at the next read;
  * no fmi2DoStep beyond its bound: after a step that returned OK, Warning or
    Discard, its Newton iterations (`step_newton_iterations`) are at most its
    bound (`step_newton_bound`, 10 n w + 75: docs/theory.md §7.6); the longest
    doStep's wall time and the largest iterations/bound ratio are reported;
  * afterwards every live instance comes back with fmi2Reset to a normal run
    (n_elements = 10, setup 0, init, 3 steps of 0.1 s with a small heave, all
    fmi2OK and finite); a freed instance is replaced by a fresh one that must
    do the same.

Only fmpy's public pieces are used: FMU2Slave loads the library and gives the
fmi2* functions with their ctypes signatures; a non-OK status raised as
FMICallException is caught and its status kept. Instances are handled by their
fmi2Component directly (not FMU2Slave.instantiate/freeInstance, which unloads
the library), so that two instances share one loaded riser.so as in a master.
"""

from __future__ import annotations

import ctypes
import json
import math
import os
import random
import resource
import select
import signal
import struct
import sys
import tempfile
import time
import traceback
from ctypes import byref, c_char_p, c_double, c_int, c_size_t, c_uint, c_void_p, create_string_buffer
from dataclasses import dataclass, field

from fmpy import read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (FMU2Slave, fmi2CallbackFunctions, fmi2CallbackLoggerTYPE, defaultCallbacks)

OK, WARNING, DISCARD, ERROR, FATAL = 0, 1, 2, 3, 4
STATUS = {0: "OK", 1: "Warning", 2: "Discard", 3: "Error", 4: "Fatal"}

NAN, INF = float("nan"), float("inf")
REAL_SPECIAL = [0.0, -0.0, 1.0, -1.0, NAN, INF, -INF, 5e-324, 1e-300, 9e15, 1e308, -1e308]
STEP_SIZES = [0.0, -1.0, 1e-12, 1e-6, 0.01, 0.05, 0.3, 1.0, 7.0, 1e300, NAN, INF]
INT_SPECIAL = [0, -1, 1, 2, 3, 1000, 100000, 2**31 - 1, -2**31]
BOOL_POOL = [0, 1, 2, -1]
START_TIMES = [0.0, 0.0, 0.0, 1.5, -3.0, 1e9, 1e300, NAN, INF, 5e-324]
LOG_CATEGORIES = ["logEvents", "logStatusWarning", "logStatusDiscard", "logStatusError", "logSolver", "logAll",
                  "bogus", ""]

GETTERS = {"get_real", "get_integer", "get_string", "get_status", "directional_derivative",
           "get_output_derivatives"}
# calls that leave the line's state as it is (failure signatures name the last call that did not)
KEEP_STATE = GETTERS | {"set_input_derivatives", "set_debug_logging", "get_state", "serialize", "deserialize",
                        "free_state", "cancel_step", "null_component"}

# the normal run after each sequence
RECOVERY_ELEMENTS = 10
RECOVERY_STEPS = 3
RECOVERY_H = 0.1


def fmt(x):
    """A number or value as the trace shows it (repr round-trips floats)."""
    if isinstance(x, float):
        return repr(x)
    if isinstance(x, bytes):
        return repr(x if len(x) <= 40 else x[:40] + b"...")
    if isinstance(x, str):
        return repr(x if len(x) <= 60 else x[:60] + "...")
    if isinstance(x, (list, tuple)):
        return "[" + ", ".join(fmt(v) for v in x) + "]"
    return str(x)


# every logger handed to fmpy's process-wide proxy (see Library.__init__)
_LOGGERS_KEPT_ALIVE: list = []


@dataclass
class Var:
    vr: int
    name: str
    type: str
    causality: str
    start: object


class Library:
    """riser.so loaded once (through FMU2Slave); every fmi2* call returns its
    status instead of raising."""

    def __init__(self, unzipdir):
        self.unzipdir = str(unzipdir)
        md = read_model_description(self.unzipdir)
        self.guid = md.guid
        ident = md.coSimulation.modelIdentifier
        self.slave = FMU2Slave(guid=md.guid, unzipDirectory=self.unzipdir, modelIdentifier=ident,
                               instanceName="fuzz")
        self.resources = "file://" + os.path.join(os.path.abspath(self.unzipdir), "resources")
        self.vars = []
        for v in md.modelVariables:
            start = v.start
            if v.type == "Real" and start is not None:
                start = float(start)
            elif v.type == "Integer" and start is not None:
                start = int(start)
            self.vars.append(Var(v.valueReference, v.name, v.type, v.causality, start))
        self.by_name = {v.name: v for v in self.vars}
        self.by_vr = {v.vr: v for v in self.vars}
        self.n_vr = max(self.by_vr) + 1
        self.reals = [v for v in self.vars if v.type == "Real"]
        self.outputs = [v for v in self.reals if v.causality == "output"]
        self.inputs = [v for v in self.reals if v.causality == "input"]
        self.real_params = [v for v in self.reals if v.causality == "parameter"]
        self.ints = [v for v in self.vars if v.type == "Integer"]
        self.bools = [v for v in self.vars if v.type == "Boolean"]
        self.strings = [v for v in self.vars if v.type == "String"]
        # the logger: fmpy's native proxy formats the variadic message, then ours collects it
        self.messages = []
        self.echo = False
        self._logger = fmi2CallbackLoggerTYPE(self._log)
        self.callbacks = fmi2CallbackFunctions()
        self.callbacks.logger = self._logger
        self.callbacks.allocateMemory = defaultCallbacks.allocateMemory
        self.callbacks.freeMemory = defaultCallbacks.freeMemory
        try:
            from fmpy.logging import addLoggerProxy
            addLoggerProxy(byref(self.callbacks))
            # fmpy's logger proxy is process-wide: it keeps calling this
            # logger for every later instance in the process (other test
            # modules' too), so it must outlive this Library
            _LOGGERS_KEPT_ALIVE.append((self, self._logger, self.callbacks))
        except Exception:  # without the proxy the message is the format "%s": still fine
            pass
        # callbacks without a logger (the FMU must not call a null function)
        self.callbacks_nolog = fmi2CallbackFunctions()
        self.callbacks_nolog.allocateMemory = defaultCallbacks.allocateMemory
        self.callbacks_nolog.freeMemory = defaultCallbacks.freeMemory

    def _log(self, env, name, status, category, message):
        text = (message or b"").decode("utf-8", "replace")
        cat = (category or b"").decode("utf-8", "replace")
        line = f"    log [{STATUS.get(status, status)}] {cat}: {text}"
        self.messages.append(line)
        if len(self.messages) > 40:
            del self.messages[:20]
        if self.echo:
            print(line, flush=True)

    def call(self, fname, *args):
        """fmi2<fname>(*args) → status (an int), FMICallException caught."""
        try:
            return getattr(self.slave, fname)(*args)
        except FMICallException as e:
            return e.status


# --------------------------------------------------------------------------- the calls as data

@dataclass
class Call:
    """One FMI call. `slot` is the instance (0 or 1); `args` plain data; state
    handles and blobs by id (a call whose referent is gone is skipped)."""
    op: str
    slot: int
    args: dict = field(default_factory=dict)

    def to_json(self):
        def enc(v):
            if isinstance(v, float):
                if math.isnan(v):
                    return {"f": "nan"}
                if math.isinf(v):
                    return {"f": "inf" if v > 0 else "-inf"}
                if v == 0.0 and math.copysign(1.0, v) < 0:
                    return {"f": "-0.0"}
                return v
            if isinstance(v, bytes):
                return {"b": v.hex()}
            if isinstance(v, (list, tuple)):
                return [enc(x) for x in v]
            if isinstance(v, dict):
                return {"d": {k: enc(x) for k, x in v.items()}}
            return v
        return {"op": self.op, "slot": self.slot, "args": {k: enc(v) for k, v in self.args.items()}}

    @staticmethod
    def from_json(d):
        def dec(v):
            if isinstance(v, dict):
                if "f" in v:
                    return float(v["f"])
                if "b" in v:
                    return bytes.fromhex(v["b"])
                if "d" in v:
                    return {k: dec(x) for k, x in v["d"].items()}
            if isinstance(v, list):
                return [dec(x) for x in v]
            return v
        return Call(d["op"], d["slot"], {k: dec(v) for k, v in d["args"].items()})


@dataclass
class Inst:
    comp: int | None = None          # fmi2Component (an address), None when freed / never made
    mode: str = "none"               # the master's view: instantiated, init, step, failed, terminated, error
    time: float = 0.0
    states: dict = field(default_factory=dict)  # id -> [c_void_p, mode, time]
    used: bool = False               # instantiated at some point (the recovery covers it)


# --------------------------------------------------------------------------- hostile files and blobs

CATENARY_LINES = None


def scene_text(lib):
    global CATENARY_LINES
    if CATENARY_LINES is None:
        with open(os.path.join(lib.unzipdir, "resources", "catenary.toml")) as f:
            CATENARY_LINES = f.read().splitlines()
    return CATENARY_LINES


TOML_HOSTILE = ["nan", "inf", "-inf", "1e308", "-1e308", "5e-324", "0", "-1", "1e-300", "9e15", "99999999",
                "2147483648", "-0.0", '"abc"', "[1, 2]", "true", "{}"]


def garbage_toml(lib, rng):
    """The text of a garbage or hostile scene file."""
    kind = rng.randrange(6)
    lines = list(scene_text(lib))
    if kind == 0:    # random bytes
        return bytes(rng.randrange(256) for _ in range(rng.randrange(1, 400)))
    if kind == 1:    # truncated
        text = "\n".join(lines).encode()
        return text[:rng.randrange(len(text))]
    if kind == 2:    # valid TOML, hostile numbers (the scene-file route to the parameters)
        assigns = [i for i, ln in enumerate(lines) if "=" in ln and not ln.lstrip().startswith("#")]
        for i in rng.sample(assigns, rng.randint(1, 3)):
            key = lines[i].split("=")[0]
            lines[i] = f"{key}= {rng.choice(TOML_HOSTILE)}"
        return "\n".join(lines).encode()
    if kind == 3:    # n_elements or time_step alone made hostile
        key, vals = rng.choice([("n_elements", ["0", "1", "2", "1000000", "2147483647", "-5", "1e9"]),
                                ("time_step", ["1e-300", "5e-324", "0", "-0.05", "1e300", "nan", "inf"])])
        lines = [f"{key} = {rng.choice(vals)}" if ln.startswith(key) else ln for ln in lines]
        return "\n".join(lines).encode()
    if kind == 4:    # structure broken: a section dropped, a key duplicated, a table unclosed
        choice = rng.randrange(3)
        if choice == 0:
            start = rng.choice([i for i, ln in enumerate(lines) if ln.startswith("[")])
            end = next((j for j in range(start + 1, len(lines)) if lines[j].startswith("[")), len(lines))
            del lines[start:end]
        elif choice == 1:
            i = rng.choice([i for i, ln in enumerate(lines) if "=" in ln and not ln.startswith("#")])
            lines.insert(i, lines[i])
        else:
            lines.append("[analysis")
        return "\n".join(lines).encode()
    # huge line / deep nesting
    return ("x = " + "[" * rng.randint(100, 3000) + "]" * rng.randint(0, 3000)).encode()


def checksummed(body):
    h = 0xcbf29ce484222325
    for b in body:
        h ^= b
        h = (h * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
    return body + struct.pack("<Q", h)


def corrupt(blob, rng):
    """A corrupted copy of a serialized state (and what was done, for the trace)."""
    kind = rng.choice([0, 1, 2, 3, 4, 5, 5, 5, 6, 7])   # well-formed hostile numbers (5) weigh most
    b = bytearray(blob)
    if kind == 0:
        return b"", "empty"
    if kind == 1:
        n = rng.randrange(len(b)) if b else 0
        return bytes(b[:n]), f"truncated to {n}"
    if kind == 2:
        for _ in range(rng.randint(1, 4)):
            if b:
                b[rng.randrange(len(b))] ^= 1 << rng.randrange(8)
        return bytes(b), "bits flipped"
    if kind == 3:
        return bytes(rng.randrange(256) for _ in range(len(b))), "random bytes"
    if kind == 4:
        return bytes(b) + bytes(rng.randrange(256) for _ in range(rng.randint(1, 64))), "junk appended"
    if len(b) < 60:
        return bytes(b), "unchanged (too short)"
    body = b[:-8]
    if kind == 5:     # well-formed: hostile numbers in place of some f64s, checksum recomputed
        done = []
        for _ in range(rng.randint(1, 3)):
            # an f64 after the header (magic, version, 3 mesh counts, the extra count)
            k = rng.randrange(4, (len(body) - 12) // 8)
            v = rng.choice([1e308, -1e308, 1e300, -1e300, 1e200, 1e155, 9e15, 5e-324, NAN])
            body[12 + 8 * k:20 + 8 * k] = struct.pack("<d", v)
            done.append(f"f64 #{k - 4} := {v!r}")
        return checksummed(bytes(body)), "re-checksummed, " + ", ".join(done)
    if kind == 6:     # well-formed: counts (mesh, extra) changed, checksum recomputed
        at = 12 + 8 * rng.randrange(4)
        body[at:at + 8] = struct.pack("<Q", rng.choice([0, 1, 2**31, 2**62, 2**64 - 1, 1025]))
        return checksummed(bytes(body)), "counts changed, re-checksummed"
    # well-formed: version changed
    body[8:12] = struct.pack("<I", rng.choice([0, 2, 4, 2**32 - 1]))
    return checksummed(bytes(body)), "version changed, re-checksummed"


# --------------------------------------------------------------------------- executor

class Executor:
    """Runs `Call`s against the library, keeps instances, states and blobs,
    applies the oracle to what the getters return."""

    def __init__(self, lib, workdir, verbose=False):
        self.lib = lib
        self.workdir = workdir
        self.verbose = verbose
        self.insts = [Inst(), Inst()]
        self.blobs = {}                  # id -> (bytes, origin mode, origin time, intact)
        self.next_id = 0
        self.failures = []
        self.trace = []
        self.stats = {}                  # "op:status" -> count (what the sequences reached)
        self.longest_step = 0.0          # s, the longest fmi2DoStep of the sequence
        self.work_ratio = 0.0            # the largest step_newton_iterations / step_newton_bound
        self.last_change = ["-", "-"]    # per instance, the last call that changed the state (for signatures)
        self.slot = 0
        lib.echo = verbose

    # ---- bookkeeping
    def new_id(self):
        self.next_id += 1
        return self.next_id

    def record(self, text):
        self.trace.append(text)
        if self.verbose:
            print(text, flush=True)

    def fail(self, kind, call_text, status, detail):
        """Notes a failure; its signature (kind, function, the last call that
        changed the instance before it) groups failures of one cause."""
        fn = call_text.split("(")[0].split()[-1] if call_text else "?"
        after = (kind == "ok_nonfinite" and fn in ("fmi2GetReal", "fmi2GetRealStatus")) or kind == "unreadable"
        sig = f"{kind}: {fn}" + (f" after {self.last_change[self.slot]}" if after else "")
        self.failures.append({"kind": kind, "signature": sig, "call": call_text, "status": STATUS.get(status, status),
                              "detail": detail, "index": len(self.trace),
                              "log": list(self.lib.messages[-8:])})
        if self.verbose:
            print(f"  !! {kind}: {detail}", flush=True)

    def check_reals(self, call_text, status, names, values):
        if status in (OK, WARNING):
            bad = [(n, v) for n, v in zip(names, values) if not math.isfinite(v)]
            if bad:
                self.fail("ok_nonfinite", call_text, status, ", ".join(f"{n} = {v!r}" for n, v in bad))

    def vr_name(self, vr):
        v = self.lib.by_vr.get(vr)
        return v.name if v else f"vr{vr}"

    # ---- the mode the master believes the instance is in, from the status
    def after(self, inst, status, ok_mode=None, discard_mode=None):
        if status >= ERROR:
            inst.mode = "error"
        elif status == DISCARD and discard_mode:
            inst.mode = discard_mode
        elif status in (OK, WARNING) and ok_mode:
            inst.mode = ok_mode

    # ---- run one call
    def run(self, call):
        op = getattr(self, "op_" + call.op)
        inst = self.insts[call.slot]
        self.lib.messages.clear()
        self.slot = call.slot
        text, status = op(inst, call.slot, **call.args)
        if text is not None and call.op not in KEEP_STATE and not (call.op == "set_real" and inst.mode == "step"):
            self.last_change[call.slot] = text.split("(")[0]
        key = f"{call.op}:{'skipped' if status is None else STATUS.get(status, status)}"
        self.stats[key] = self.stats.get(key, 0) + 1
        if text is not None:
            self.record(f"i{call.slot} {text} -> {STATUS.get(status, status)}")
            if status == FATAL and call.op != "instantiate":
                self.fail("fatal", text, status, "fmi2Fatal (a panic caught at the C boundary?)")
        return status

    def comp(self, inst):
        return c_void_p(inst.comp) if inst.comp is not None else None

    def live(self, inst):
        return inst.comp is not None

    # ---- operations: each returns (text, status); text None = skipped
    def op_instantiate(self, inst, slot, variant="normal", name="riser"):
        if self.live(inst):
            return None, None
        lib = self.lib
        guid, kind, res, cb = lib.guid, 1, lib.resources, byref(lib.callbacks)
        if variant == "wrong_guid":
            guid = "{00000000-0000-0000-0000-000000000000}"
        elif variant == "model_exchange":
            kind = 0
        elif variant == "no_resources":
            res = None
        elif variant == "bad_resources":
            res = "http://example.com/%zz%/resources"
        elif variant == "no_logger":
            cb = byref(lib.callbacks_nolog)
        elif variant == "null_callbacks":
            cb = None
        enc = lambda s: s.encode() if isinstance(s, str) else s
        c = lib.slave.fmi2Instantiate(enc(name) if name is not None else None, kind, enc(guid),
                                      enc(res) if res is not None else None, cb, 0, 0)
        inst.used = True
        if c:
            inst.comp, inst.mode, inst.time, inst.states = c, "instantiated", 0.0, {}
        return f"fmi2Instantiate({fmt(name)}, {variant}) = {'component' if c else 'NULL'}", OK if c else ERROR

    def op_free_instance(self, inst, slot):
        if not self.live(inst):
            return None, None
        for sid in list(inst.states):
            self.op_free_state(inst, slot, sid=sid)
        self.lib.slave.fmi2FreeInstance(self.comp(inst))
        inst.comp, inst.mode, inst.states = None, "none", {}
        return "fmi2FreeInstance", OK

    def op_setup(self, inst, slot, tol_defined=0, tol=0.0, start=0.0, stop_defined=0, stop=0.0):
        if not self.live(inst):
            return None, None
        s = self.lib.call("fmi2SetupExperiment", self.comp(inst), tol_defined, tol, start, stop_defined, stop)
        if s in (OK, WARNING):
            inst.time = start
        self.after(inst, s)
        return f"fmi2SetupExperiment(tol={fmt(tol) if tol_defined else '-'}, start={fmt(start)}, " \
               f"stop={fmt(stop) if stop_defined else '-'})", s

    def _instance_call(self, inst, fn, *modes):
        """A call that takes the instance alone; on success the instance goes to modes[0]."""
        if not self.live(inst):
            return None, None
        s = self.lib.call(fn, self.comp(inst))
        self.after(inst, s, *modes)
        return fn, s

    def op_enter_init(self, inst, slot):
        return self._instance_call(inst, "fmi2EnterInitializationMode", "init")

    def op_exit_init(self, inst, slot):
        return self._instance_call(inst, "fmi2ExitInitializationMode", "step")

    def op_terminate(self, inst, slot):
        return self._instance_call(inst, "fmi2Terminate", "terminated")

    def op_reset(self, inst, slot):
        if not self.live(inst):
            return None, None
        s = self.lib.call("fmi2Reset", self.comp(inst))
        if s in (OK, WARNING):
            inst.time = 0.0
        self.after(inst, s, "instantiated")
        return "fmi2Reset", s

    def op_set_debug_logging(self, inst, slot, on=1, cats=()):
        if not self.live(inst):
            return None, None
        arr = (c_char_p * len(cats))(*[c.encode() for c in cats]) if cats else None
        s = self.lib.call("fmi2SetDebugLogging", self.comp(inst), on, len(cats), arr)
        self.after(inst, s)
        return f"fmi2SetDebugLogging({on}, {fmt(list(cats))})", s

    def _vrs(self, vrs):
        return (c_uint * len(vrs))(*vrs) if vrs else None

    def _set_values(self, inst, fn, ctype, vrs, values):
        """fmi2SetReal/Integer/Boolean of `values` (C type `ctype`) at `vrs`."""
        if not self.live(inst):
            return None, None
        vals = (ctype * len(values))(*values) if values else None
        s = self.lib.call(fn, self.comp(inst), self._vrs(vrs), len(vrs), vals)
        self.after(inst, s)
        return f"{fn}({fmt([self.vr_name(v) for v in vrs])}, {fmt(list(values))})", s

    def op_set_real(self, inst, slot, vrs=(), values=()):
        return self._set_values(inst, "fmi2SetReal", c_double, vrs, values)

    def op_set_integer(self, inst, slot, vrs=(), values=()):
        return self._set_values(inst, "fmi2SetInteger", c_int, vrs, values)

    def op_set_boolean(self, inst, slot, vrs=(), values=()):
        return self._set_values(inst, "fmi2SetBoolean", c_int, vrs, values)

    def op_set_string(self, inst, slot, vrs=(), values=()):
        if not self.live(inst):
            return None, None
        shown, raw = [], []
        for v in values:
            if isinstance(v, dict):      # a file written now: {"file": name, "text": bytes}
                path = os.path.join(self.workdir, v["file"])
                with open(path, "wb") as f:
                    f.write(v["text"])
                raw.append(path.encode())
                shown.append(f"<{v['file']}: {fmt(v['text'])}>")
            elif v is None:
                raw.append(None)
                shown.append("NULL")
            else:
                raw.append(v if isinstance(v, bytes) else v.encode())
                shown.append(fmt(v))
        vals = (c_char_p * len(raw))(*raw) if raw else None
        s = self.lib.call("fmi2SetString", self.comp(inst), self._vrs(vrs), len(vrs), vals)
        self.after(inst, s)
        return f"fmi2SetString({fmt([self.vr_name(v) for v in vrs])}, [{', '.join(shown)}])", s

    def op_get_real(self, inst, slot, vrs=()):
        if not self.live(inst):
            return None, None
        vals = (c_double * len(vrs))(*([NAN] * len(vrs))) if vrs else None
        mode = inst.mode
        s = self.lib.call("fmi2GetReal", self.comp(inst), self._vrs(vrs), len(vrs), vals)
        self.after(inst, s)
        names = [self.vr_name(v) for v in vrs]
        got = list(vals) if vrs else []
        text = f"fmi2GetReal({fmt(names) if len(vrs) <= 6 else f'<{len(vrs)} vrs>'})"
        if s in (OK, WARNING) and self.verbose:
            text += " = " + fmt(got[:6]) + ("..." if len(got) > 6 else "")
        self.check_reals(text, s, names, got)
        # the outputs of a state the FMU accepted (an OK step, initialisation,
        # fmi2SetFMUstate, or a discarded step's last good state) must be
        # readable: a non-finite state is to be refused where it arises
        outputs = {v.vr for v in self.lib.outputs} | {v.vr for v in self.lib.inputs}
        if s >= ERROR and vrs and set(vrs) <= outputs and mode in ("step", "failed", "terminated"):
            self.fail("unreadable", text, s, f"fmi2GetReal of valid outputs failed after {self.last_change[slot]} "
                      f"returned OK (state {mode}): " + (self.lib.messages[-1].strip() if self.lib.messages else ""))
        return text, s

    def op_get_integer(self, inst, slot, vrs=(), boolean=False):
        if not self.live(inst):
            return None, None
        vals = (c_int * len(vrs))() if vrs else None
        f = "fmi2GetBoolean" if boolean else "fmi2GetInteger"
        s = self.lib.call(f, self.comp(inst), self._vrs(vrs), len(vrs), vals)
        self.after(inst, s)
        text = f"{f}({fmt([self.vr_name(v) for v in vrs])})"
        if s in (OK, WARNING) and vrs:
            text += " = " + fmt(list(vals))
        return text, s

    def op_get_string(self, inst, slot, vrs=()):
        if not self.live(inst):
            return None, None
        vals = (c_char_p * len(vrs))() if vrs else None
        s = self.lib.call("fmi2GetString", self.comp(inst), self._vrs(vrs), len(vrs), vals)
        self.after(inst, s)
        text = f"fmi2GetString({fmt([self.vr_name(v) for v in vrs])})"
        if s in (OK, WARNING) and vrs:
            got = list(vals)
            text += " = " + fmt(got)
            if any(g is None for g in got):
                self.fail("ok_null_string", text, s, "fmi2GetString returned OK with a NULL string")
        return text, s

    def op_do_step(self, inst, slot, t=0.0, h=0.1, no_prior=1):
        if not self.live(inst):
            return None, None
        t0 = time.monotonic()
        s = self.lib.call("fmi2DoStep", self.comp(inst), t, h, no_prior)
        self.longest_step = max(self.longest_step, time.monotonic() - t0)
        if s in (OK, WARNING):
            inst.time = t + h
        self.after(inst, s, "step", "failed")
        text = f"fmi2DoStep(t={fmt(t)}, h={fmt(h)})"
        if s in (OK, WARNING, DISCARD) and "step_newton_bound" in self.lib.by_name:
            # the bounded step: the step's own work against its bound
            vrs = [self.lib.by_name[n].vr for n in ("step_newton_iterations", "step_newton_bound")]
            vals = (c_double * 2)(NAN, NAN)
            if self.lib.call("fmi2GetReal", self.comp(inst), self._vrs(vrs), 2, vals) in (OK, WARNING):
                work, bound = vals[0], vals[1]
                if bound > 0:
                    self.work_ratio = max(self.work_ratio, work / bound)
                if not work <= bound:
                    self.fail("unbounded", text, s, f"{work:.0f} Newton iterations, beyond the step's bound {bound:.0f}")
        return text, s

    def op_cancel_step(self, inst, slot):
        return self._instance_call(inst, "fmi2CancelStep")

    def op_get_status(self, inst, slot, which="status", kind=0, null=False):
        if not self.live(inst):
            return None, None
        ctype = {"status": c_int, "real": c_double, "integer": c_int, "boolean": c_int, "string": c_char_p}[which]
        f = {"status": "fmi2GetStatus", "real": "fmi2GetRealStatus", "integer": "fmi2GetIntegerStatus",
             "boolean": "fmi2GetBooleanStatus", "string": "fmi2GetStringStatus"}[which]
        value = ctype()
        s = self.lib.call(f, self.comp(inst), kind, None if null else byref(value))
        self.after(inst, s)
        text = f"{f}(kind={kind}{', NULL' if null else ''})"
        if s in (OK, WARNING) and not null:
            text += f" = {fmt(value.value)}"
            if which == "real":
                self.check_reals(text, s, ["lastSuccessfulTime"], [value.value])
        return text, s

    def op_set_input_derivatives(self, inst, slot, vrs=(), orders=(), values=()):
        if not self.live(inst):
            return None, None
        n = len(vrs)
        s = self.lib.call("fmi2SetRealInputDerivatives", self.comp(inst), self._vrs(vrs), n,
                          (c_int * n)(*orders) if n else None, (c_double * n)(*values) if n else None)
        self.after(inst, s)
        return f"fmi2SetRealInputDerivatives({fmt([self.vr_name(v) for v in vrs])}, {fmt(list(orders))}, " \
               f"{fmt(list(values))})", s

    def op_get_output_derivatives(self, inst, slot, vrs=(), orders=()):
        if not self.live(inst):
            return None, None
        n = len(vrs)
        vals = (c_double * n)() if n else None
        s = self.lib.call("fmi2GetRealOutputDerivatives", self.comp(inst), self._vrs(vrs), n,
                          (c_int * n)(*orders) if n else None, vals)
        self.after(inst, s)
        text = f"fmi2GetRealOutputDerivatives({fmt([self.vr_name(v) for v in vrs])}, {fmt(list(orders))})"
        self.check_reals(text, s, [self.vr_name(v) for v in vrs], list(vals) if n else [])
        return text, s

    def op_directional_derivative(self, inst, slot, unknowns=(), knowns=(), seeds=()):
        if not self.live(inst):
            return None, None
        nu, nk = len(unknowns), len(knowns)
        out = (c_double * nu)(*([NAN] * nu)) if nu else None
        s = self.lib.call("fmi2GetDirectionalDerivative", self.comp(inst), self._vrs(unknowns), nu,
                          self._vrs(knowns), nk, (c_double * nk)(*seeds) if nk else None, out)
        self.after(inst, s)
        names = [self.vr_name(v) for v in unknowns]
        text = f"fmi2GetDirectionalDerivative({fmt(names)}, {fmt([self.vr_name(v) for v in knowns])}, " \
               f"{fmt(list(seeds))})"
        got = list(out) if nu else []
        if s in (OK, WARNING) and self.verbose:
            text += " = " + fmt(got)
        self.check_reals(text, s, names, got)
        return text, s

    def _state_handle(self, inst, reuse):
        """The handle fmi2GetFMUstate or fmi2DeSerializeFMUstate writes: a new one, or the state
        `reuse`'s; None when `reuse` names no state of the instance."""
        if reuse is None:
            return c_void_p()
        return inst.states[reuse][0] if reuse in inst.states else None

    def op_get_state(self, inst, slot, sid=None, reuse=None):
        """fmi2GetFMUstate into a new handle (sid) or over an existing one (reuse)."""
        if not self.live(inst):
            return None, None
        handle = self._state_handle(inst, reuse)
        if handle is None:
            return None, None
        s = self.lib.call("fmi2GetFMUstate", self.comp(inst), byref(handle))
        key = reuse if reuse is not None else sid
        if handle.value:
            inst.states[key] = [handle, inst.mode, inst.time]
        if s in (OK, WARNING) and reuse is not None:
            inst.states[key][1:] = [inst.mode, inst.time]
        self.after(inst, s)
        return f"fmi2GetFMUstate(-> s{key})", s

    def op_set_state(self, inst, slot, sid=0, null=False):
        if not self.live(inst) or (not null and sid not in inst.states):
            return None, None
        handle, mode, t = inst.states[sid] if not null else (None, None, None)
        s = self.lib.call("fmi2SetFMUstate", self.comp(inst), handle)
        if s in (OK, WARNING):
            inst.mode = {"failed": "failed", "terminated": "terminated"}.get(mode, "step")
            if t is not None:
                inst.time = t
        self.after(inst, s)
        return f"fmi2SetFMUstate({'NULL' if null else f's{sid}'})", s

    def op_free_state(self, inst, slot, sid=0):
        if not self.live(inst) or sid not in inst.states:
            return None, None
        handle = inst.states.pop(sid)[0]
        s = self.lib.call("fmi2FreeFMUstate", self.comp(inst), byref(handle))
        if handle.value:        # not freed (an error): keep it for the cleanup
            inst.states[sid] = [handle, None, None]
        self.after(inst, s)
        return f"fmi2FreeFMUstate(s{sid})", s

    def op_serialize(self, inst, slot, sid=0, bid=0, short=False):
        if not self.live(inst) or sid not in inst.states:
            return None, None
        handle, mode, t = inst.states[sid]
        size = c_size_t(0)
        s = self.lib.call("fmi2SerializedFMUstateSize", self.comp(inst), handle, byref(size))
        text = f"fmi2SerializedFMUstateSize(s{sid}) = {size.value}"
        if s not in (OK, WARNING):
            self.after(inst, s)
            return text, s
        self.record(f"i{slot} {text} -> {STATUS[s]}")
        n = size.value - 1 if short and size.value > 0 else size.value
        buf = create_string_buffer(max(n, 1))
        s = self.lib.call("fmi2SerializeFMUstate", self.comp(inst), handle, buf, n)
        if s in (OK, WARNING):
            self.blobs[bid] = (buf.raw[:n], mode, t, True)
        self.after(inst, s)
        return f"fmi2SerializeFMUstate(s{sid}, {n} bytes -> b{bid})", s

    def op_deserialize(self, inst, slot, bid=0, sid=None, reuse=None, mutation=None):
        """fmi2DeSerializeFMUstate of blob `bid` (corrupted as `mutation` says:
        {"bytes": b, "what": text} replaces it)."""
        if not self.live(inst) or bid not in self.blobs:
            return None, None
        blob, mode, t, _ = self.blobs[bid]
        what = "intact"
        if mutation is not None:
            blob, what, mode, t = mutation["bytes"], mutation["what"], None, None
        handle = self._state_handle(inst, reuse)
        if handle is None:
            return None, None
        buf = create_string_buffer(blob, len(blob)) if blob else create_string_buffer(1)
        s = self.lib.call("fmi2DeSerializeFMUstate", self.comp(inst), buf, len(blob), byref(handle))
        key = reuse if reuse is not None else sid
        if handle.value:
            if s in (OK, WARNING) or key not in inst.states:
                inst.states[key] = [handle, mode, t]
        self.after(inst, s)
        return f"fmi2DeSerializeFMUstate(b{bid} {what}, {len(blob)} bytes -> s{key})", s

    def op_null_component(self, inst, slot, fn="fmi2DoStep"):
        args = {"fmi2DoStep": (None, 0.0, 0.1, 1), "fmi2Reset": (None,), "fmi2Terminate": (None,),
                "fmi2GetReal": (None, None, 0, None), "fmi2SetupExperiment": (None, 0, 0.0, 0.0, 0, 0.0),
                "fmi2FreeInstance": (None,)}[fn]
        if fn == "fmi2FreeInstance":
            self.lib.slave.fmi2FreeInstance(None)
            return f"{fn}(NULL)", OK
        return f"{fn}(NULL, ...)", self.lib.call(fn, *args)

    # ---- the oracle's last part: reset, then a normal run
    def recovery(self):
        lib = self.lib
        out_vrs = [v.vr for v in lib.outputs]
        for slot, inst in enumerate(self.insts):
            if not inst.used:
                continue
            if not self.live(inst):
                self.record(f"-- recovery i{slot}: fresh instance")
                self.run(Call("instantiate", slot))
                if not self.live(inst):
                    self.fail("recovery", f"i{slot} fmi2Instantiate", ERROR, "a fresh instance could not be made")
                    continue
            else:
                self.record(f"-- recovery i{slot}: reset")
                s = self.run(Call("reset", slot))
                if s != OK:
                    self.fail("recovery", f"i{slot} fmi2Reset", s, "fmi2Reset did not return OK")
                    continue
            steps = [Call("set_integer", slot, {"vrs": [lib.by_name["n_elements"].vr], "values": [RECOVERY_ELEMENTS]}),
                     Call("setup", slot, {"start": 0.0}),
                     Call("enter_init", slot), Call("exit_init", slot), Call("get_real", slot, {"vrs": out_vrs})]
            t = 0.0
            for k in range(RECOVERY_STEPS):
                steps += [Call("set_real", slot, {"vrs": [lib.by_name["heave"].vr], "values": [0.05 * (k + 1)]}),
                          Call("do_step", slot, {"t": t, "h": RECOVERY_H}),
                          Call("get_real", slot, {"vrs": out_vrs})]
                t += RECOVERY_H
            for c in steps:
                n_fail = len(self.failures)
                s = self.run(c)
                if s != OK:
                    self.fail("recovery", self.trace[-1], s, f"the normal run after the sequence failed at {c.op}")
                    break
                if len(self.failures) > n_fail:
                    break

    def cleanup(self):
        """Free every state and instance (so that valgrind sees no leak of ours)."""
        for slot, inst in enumerate(self.insts):
            if self.live(inst):
                self.op_free_instance(inst, slot)


# --------------------------------------------------------------------------- generator

class Generator:
    """Chooses the next call from the rng and what the master believes the
    instances' modes are."""

    def __init__(self, lib, rng, ex):
        self.lib, self.rng, self.ex = lib, rng, ex
        self.blob_ids = []
        self.file_no = 0
        self.fresh_sid = None
        self.look = None
        self.queue = []

    # ---- value pools
    def real_value(self, var, hostile=None):
        """A value for `var`: realistic (inputs a few metres, parameters their
        start value times 0.5..2) or, when hostile, from REAL_SPECIAL."""
        r = self.rng
        if hostile is None:
            hostile = r.random() < 0.4
        if var is not None and not hostile:
            if var.causality == "input":
                return r.uniform(-3, 3) if r.random() < 0.8 else 0.0
            start = var.start if isinstance(var.start, float) else 1.0
            if start == 0.0:
                return r.uniform(-1, 1)
            return start * r.uniform(0.5, 2.0)
        return r.choice(REAL_SPECIAL)

    def any_vr(self, pool, hostile=None):
        """A value reference: from `pool` or, when hostile, often of another
        type or invalid."""
        r = self.rng
        if hostile is None:
            hostile = r.random() < 0.2
        x = r.random() if hostile else 0.0
        if x < 0.5 and pool:
            return r.choice(pool).vr
        if x < 0.8:
            return r.randrange(self.lib.n_vr)
        return r.choice([self.lib.n_vr, self.lib.n_vr + 1, 1000, 2**31, 2**32 - 1])

    def reals(self, pool, n):
        """`n` value references of `pool` with values; a call is clean (valid
        references, realistic values) 70 % of the time, else each element is
        hostile with probability 1/2."""
        r = self.rng
        dirty = r.random() < 0.3
        vrs, vals = [], []
        for _ in range(n):
            vr = self.any_vr(pool, hostile=dirty and r.random() < 0.5)
            vrs.append(vr)
            vals.append(self.real_value(self.lib.by_vr.get(vr), hostile=dirty and r.random() < 0.5))
        return {"vrs": vrs, "values": vals}

    def n_elements(self):
        r = self.rng
        return r.randint(4, 20) if r.random() < 0.85 else r.choice(INT_SPECIAL)

    def set_n_elements(self, slot):
        """fmi2SetInteger of n_elements (a draw of n_elements)."""
        return Call("set_integer", slot, {"vrs": [self.lib.by_name["n_elements"].vr], "values": [self.n_elements()]})

    def string_value(self, var_name):
        r = self.rng
        x = r.random()
        if var_name == "model" and x < 0.6:
            return r.choice(["rod", "cable", "Rod", "", "cable ", "beam"])
        if x < 0.35:
            return r.choice(["catenary", "lazy_wave", "catenary.toml", "lazy_wave.toml"])
        if x < 0.6:
            self.file_no += 1
            return {"file": f"scene{self.file_no}.toml", "text": garbage_toml(self.lib, r)}
        return r.choice(["", "/nonexistent/dir/scene.toml", "missing.toml", "../../../../etc/passwd", "/",
                         "/dev/null", self.ex.workdir, b"\xff\xfe\xc3(\x80", "%s%s%n%x", "a" * 5000,
                         "catenary\nlazy_wave", None])

    # ---- calls
    def next(self):
        r, lib, ex = self.rng, self.lib, self.ex
        while self.queue:               # the rest of a chain (made now: it may need what came before)
            c = self.queue.pop(0)()
            if c is not None:
                return c
        live = [i for i, inst in enumerate(ex.insts) if ex.live(inst)]
        # instantiate when nothing is live; a second instance sometimes
        if not live or (len(live) == 1 and r.random() < 0.04):
            slot = 0 if 0 not in live else 1
            variant = "normal"
            if r.random() < 0.12:
                variant = r.choice(["wrong_guid", "model_exchange", "no_resources", "bad_resources", "no_logger",
                                    "null_callbacks"])
            name = r.choice(["riser", "riser", "riser", "", None, "ä%s"])
            return Call("instantiate", slot, {"variant": variant, "name": name})
        # a state just deserialized: set it (then look at the outputs it gives)
        fresh, self.fresh_sid = self.fresh_sid, None
        if fresh is not None and ex.live(ex.insts[fresh[0]]) and fresh[1] in ex.insts[fresh[0]].states \
                and r.random() < 0.8:
            self.look = fresh[0]
            return Call("set_state", fresh[0], {"sid": fresh[1]})
        look, self.look = self.look, None
        if look is not None and ex.live(ex.insts[look]) and r.random() < 0.8:
            return Call("get_real", look, {"vrs": [v.vr for v in lib.outputs]})
        slot = r.choice(live)
        inst = ex.insts[slot]
        mode = inst.mode
        if r.random() < 0.12:
            return self.any_call(slot, inst)
        # the calls each state draws: cumulative probabilities against one uniform draw, the first
        # row with x < p taken (a row of None is skipped), any call past the last
        again = [(0.6, lambda: Call("reset", slot)), (0.7, lambda: Call("free_instance", slot))]
        tables = {
            "error": again,
            "terminated": again,
            "failed": [(0.3, (lambda: Call("set_state", slot, {"sid": r.choice(list(inst.states))}))
                        if inst.states else None),
                       (0.5, lambda: Call("reset", slot)), (0.6, lambda: Call("terminate", slot))],
            "instantiated": [(0.35, lambda: self.set_n_elements(slot)), (0.5, lambda: self.set_param(slot)),
                             (0.7, lambda: self.setup(slot)), (0.9, lambda: Call("enter_init", slot))],
            "init": [(0.25, lambda: self.set_param(slot)), (0.35, lambda: self.set_n_elements(slot)),
                     (0.45, lambda: self.set_input(slot)), (0.55, lambda: self.get_outputs(slot)),
                     (0.9, lambda: Call("exit_init", slot))],
            "step": [(0.2, lambda: self.set_input(slot)), (0.45, lambda: self.do_step(slot, inst)),
                     (0.58, lambda: self.get_outputs(slot)), (0.76, lambda: self.state_call(slot, inst)),
                     (0.8, lambda: Call("directional_derivative", slot, self.dd_args())),
                     (0.82, lambda: self.state_round_trip(slot)), (0.84, lambda: Call("terminate", slot)),
                     (0.87, lambda: Call("reset", slot))],
        }
        x = r.random()
        for p, make in tables.get(mode, tables["step"]):
            if make is not None and x < p:
                return make()
        return self.any_call(slot, inst)

    def setup(self, slot):
        r = self.rng
        return Call("setup", slot, {"tol_defined": r.choice([0, 1]), "tol": r.choice([1e-6, 0.0, -1.0, NAN]),
                                    "start": r.choice(START_TIMES), "stop_defined": r.choice([0, 1]),
                                    "stop": r.choice([10.0, 0.0, -1.0, 1e308, NAN, INF])})

    def set_param(self, slot):
        r, lib = self.rng, self.lib
        x = r.random()
        if x < 0.55:
            return Call("set_real", slot, self.reals(lib.real_params, r.choice([1, 1, 1, 2, 3])))
        if x < 0.85:
            vr = self.any_vr(lib.strings)
            var = lib.by_vr.get(vr)
            return Call("set_string", slot, {"vrs": [vr], "values": [self.string_value(var.name if var else "")]})
        if x < 0.93:
            vr = self.any_vr(lib.bools)
            return Call("set_boolean", slot, {"vrs": [vr], "values": [r.choice(BOOL_POOL)]})
        vr = self.any_vr(lib.ints)
        return Call("set_integer", slot, {"vrs": [vr], "values": [self.n_elements()]})

    def set_input(self, slot):
        r, lib = self.rng, self.lib
        if r.random() < 0.15:
            vrs = [self.any_vr(lib.inputs)]
            return Call("set_input_derivatives", slot, {"vrs": vrs, "orders": [r.choice([1, 1, 2, 0, 3, -1])],
                                                        "values": [self.real_value(lib.by_vr.get(vrs[0]))]})
        return Call("set_real", slot, self.reals(lib.inputs, r.choice([1, 1, 2, 3, 6])))

    def get_outputs(self, slot):
        r, lib = self.rng, self.lib
        x = r.random()
        if x < 0.5:
            return Call("get_real", slot, {"vrs": [v.vr for v in lib.outputs]})
        if x < 0.8:
            return Call("get_real", slot, {"vrs": [self.any_vr(lib.reals) for _ in range(r.randint(0, 5))]})
        if x < 0.87:
            return Call("get_integer", slot, {"vrs": [self.any_vr(lib.ints + lib.bools) for _ in range(2)],
                                              "boolean": r.random() < 0.5})
        if x < 0.93:
            return Call("get_string", slot, {"vrs": [self.any_vr(lib.strings) for _ in range(2)]})
        return Call("get_status", slot, {"which": r.choice(["status", "real", "boolean", "integer", "string"]),
                                         "kind": r.choice([0, 1, 2, 3, 7]), "null": r.random() < 0.1})

    def do_step(self, slot, inst):
        r = self.rng
        h = r.choice(STEP_SIZES) if r.random() < 0.4 else r.choice([0.01, 0.05, 0.1, 0.3])
        t = inst.time if r.random() < 0.85 else r.choice([inst.time + 0.1, inst.time - 1.0, 0.0, NAN, 1e300])
        return Call("do_step", slot, {"t": t, "h": h, "no_prior": r.choice([0, 1])})

    def dd_args(self):
        r, lib = self.rng, self.lib
        forces = [lib.by_name[n] for n in ("top_force_x", "top_force_y", "top_force_z")]
        moves = [lib.by_name[n] for n in ("heave", "surge", "sway")]
        unknowns = [self.any_vr(forces) for _ in range(r.randint(0, 3))]
        knowns = [self.any_vr(moves) for _ in range(r.randint(0, 3))]
        seeds = [r.uniform(-1, 1) if r.random() < 0.7 else r.choice(REAL_SPECIAL) for _ in knowns]
        return {"unknowns": unknowns, "knowns": knowns, "seeds": seeds}

    def state_call(self, slot, inst):
        """fmi2GetFMUstate / SetFMUstate / FreeFMUstate / serialize /
        deserialize (blobs often corrupted; a state just deserialized is
        likely to be set next, and the outputs read)."""
        r, ex = self.rng, self.ex
        x = r.random()
        if x < 0.2 or not inst.states:
            reuse = r.choice(list(inst.states)) if inst.states and r.random() < 0.2 else None
            return Call("get_state", slot, {"sid": ex.new_id(), "reuse": reuse})
        sid = r.choice(list(inst.states))
        if x < 0.3:
            return Call("set_state", slot, {"sid": sid, "null": r.random() < 0.05})
        if x < 0.36:
            return Call("free_state", slot, {"sid": sid})
        if x < 0.5 or not self.blob_ids:
            bid = ex.new_id()
            self.blob_ids.append(bid)
            return Call("serialize", slot, {"sid": sid, "bid": bid, "short": r.random() < 0.1})
        bid = r.choice(self.blob_ids)
        mutation = None
        if bid in ex.blobs and r.random() < 0.75:
            b, what = corrupt(ex.blobs[bid][0], r)
            mutation = {"bytes": b, "what": what}
        reuse = r.choice(list(inst.states)) if r.random() < 0.2 else None
        new = ex.new_id()
        self.fresh_sid = (slot, reuse if reuse is not None else new)
        return Call("deserialize", slot, {"bid": bid, "sid": new, "reuse": reuse, "mutation": mutation})

    def state_round_trip(self, slot):
        """A chain: get the state, serialize it, deserialize a corrupted copy
        (mostly well-formed with hostile numbers), set it, read the outputs,
        step, read them again."""
        r, ex, lib = self.rng, self.ex, self.lib
        sid, bid, sid2 = ex.new_id(), ex.new_id(), ex.new_id()
        self.blob_ids.append(bid)
        outs = {"vrs": [v.vr for v in lib.outputs]}

        def deserialize():
            if bid not in ex.blobs:
                return None
            b, what = corrupt(ex.blobs[bid][0], r)
            return Call("deserialize", slot, {"bid": bid, "sid": sid2, "mutation": {"bytes": b, "what": what}})

        def step():
            inst = ex.insts[slot]
            return Call("do_step", slot, {"t": inst.time, "h": r.choice([0.05, 0.1, 0.3])})

        self.queue += [lambda: Call("serialize", slot, {"sid": sid, "bid": bid}), deserialize,
                       lambda: Call("set_state", slot, {"sid": sid2}), lambda: Call("get_real", slot, outs),
                       step, lambda: Call("get_real", slot, outs)]
        return Call("get_state", slot, {"sid": sid})

    def any_call(self, slot, inst):
        """Any operation, whatever the mode (out-of-order calls)."""
        r, lib = self.rng, self.lib
        op = r.choice(["setup", "enter_init", "exit_init", "terminate", "reset", "set_param", "set_input",
                       "get_outputs", "do_step", "state", "directional_derivative", "cancel_step",
                       "set_debug_logging", "get_output_derivatives", "free_instance", "null_component",
                       "set_integer"])
        if op == "setup":
            return self.setup(slot)
        if op == "set_param":
            return self.set_param(slot)
        if op == "set_input":
            return self.set_input(slot)
        if op == "get_outputs":
            return self.get_outputs(slot)
        if op == "do_step":
            return self.do_step(slot, inst)
        if op == "state":
            return self.state_call(slot, inst)
        if op == "directional_derivative":
            return Call(op, slot, self.dd_args())
        if op == "set_debug_logging":
            return Call(op, slot, {"on": r.choice([0, 1]),
                                   "cats": r.sample(LOG_CATEGORIES, r.randint(0, 3))})
        if op == "get_output_derivatives":
            vrs = [self.any_vr(lib.outputs) for _ in range(r.randint(0, 2))]
            return Call(op, slot, {"vrs": vrs, "orders": [r.choice([1, 0, 2]) for _ in vrs]})
        if op == "null_component":
            return Call(op, slot, {"fn": r.choice(["fmi2DoStep", "fmi2Reset", "fmi2Terminate", "fmi2GetReal",
                                                   "fmi2SetupExperiment", "fmi2FreeInstance"])})
        if op == "set_integer":
            vr = self.any_vr(lib.ints)
            return Call(op, slot, {"vrs": [vr], "values": [self.n_elements()]})
        if op == "free_instance" and r.random() < 0.5:
            return Call("reset", slot)
        return Call(op, slot)


# --------------------------------------------------------------------------- one sequence

def sequence_length(seed):
    return random.Random(seed ^ 0x5EED).randint(20, 200)


def run_sequence(lib, seed, workdir, verbose=False, calls=None, recover=True):
    """Runs sequence `seed` (or the given list of `Call`s), then the recovery
    run, then frees everything. Returns a dict: seed, calls (as JSON), trace,
    failures, seconds."""
    t0 = time.monotonic()
    ex = Executor(lib, workdir, verbose)
    done = []
    if calls is None:
        rng = random.Random(seed)
        gen = Generator(lib, rng, ex)
        for _ in range(sequence_length(seed)):
            c = gen.next()
            done.append(c)
            ex.run(c)
    else:
        for c in calls:
            done.append(c)
            ex.run(c)
    if recover:
        ex.recovery()
    ex.cleanup()
    return {"seed": seed, "calls": [c.to_json() for c in done], "trace": ex.trace, "failures": ex.failures,
            "stats": ex.stats, "seconds": time.monotonic() - t0, "longest_step": ex.longest_step,
            "work_ratio": ex.work_ratio}


# --------------------------------------------------------------------------- child processes

@dataclass
class Outcome:
    seed: int
    kind: str                    # ok, fail, crash, hang, harness
    seconds: float
    failures: list = field(default_factory=list)
    detail: str = ""
    trace: list = field(default_factory=list)
    calls: list = field(default_factory=list)
    stats: dict = field(default_factory=dict)
    longest_step: float = 0.0    # s, the sequence's longest fmi2DoStep
    work_ratio: float = 0.0      # its largest step_newton_iterations / step_newton_bound

    def summary(self):
        if self.kind == "fail":
            kinds = sorted({f["kind"] for f in self.failures})
            f = self.failures[0]
            return f"seed {self.seed}: {'/'.join(kinds)}: {f['call']} -> {f['status']}: {f['detail']}"
        return f"seed {self.seed}: {self.kind}: {self.detail}"


MEMORY_LIMIT = 4 << 30     # address space of a child: a runaway allocation aborts instead of eating the machine


def _child(lib, job, workdir, wfd, errpath):
    """In the forked child: run, write the JSON result to wfd, _exit."""
    try:
        try:    # die with the parent (Linux: PR_SET_PDEATHSIG)
            ctypes.CDLL(None).prctl(1, signal.SIGKILL)
        except (AttributeError, OSError):
            pass
        fd = os.open(errpath, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
        os.dup2(fd, 1)
        os.dup2(fd, 2)
        # print() goes to sys.stdout, which pytest may have pointed elsewhere
        sys.stdout = sys.stderr = os.fdopen(fd, "w", buffering=1)
        resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))
        # the trace of the calls so far goes to the file as they happen (for a crash or a hang)
        seed, calls, recover = (tuple(job) + (True,))[:3]
        calls = [Call.from_json(c) for c in calls] if calls is not None else None
        res = run_sequence(lib, seed, workdir, verbose=True, calls=calls, recover=recover)
        res.pop("trace")    # already in the file
        data = json.dumps(res).encode()
        view = memoryview(data)
        while view:
            n = os.write(wfd, view)
            view = view[n:]
        os._exit(0)
    except BaseException:
        try:
            os.write(2, traceback.format_exc().encode())
        finally:
            os._exit(70)


def _tail(path, n=40):
    try:
        with open(path, "rb") as f:
            lines = f.read().decode("utf-8", "replace").splitlines()
        return lines[-n:]
    except OSError:
        return []


def run_many(lib, jobs_list, jobs=2, timeout=60.0, max_failures=None, progress=None, keep_calls=False):
    """Runs each job, (seed, calls or None[, recover]), in its own forked
    child, `jobs` at a time, each within `timeout` seconds; stops starting new
    ones after `max_failures` bad outcomes. Returns the Outcomes in
    completion order."""
    pending = list(jobs_list)
    running = {}        # rfd -> dict(pid, seed, start, buf, workdir, errpath)
    outcomes = []
    n_bad = 0
    launched = 0
    base = tempfile.mkdtemp(prefix="riser_fuzz_")
    sys.stdout.flush()
    sys.stderr.flush()
    try:
        while pending or running:
            while pending and len(running) < jobs and (max_failures is None or n_bad < max_failures):
                spec = pending.pop(0)
                seed = spec[0]
                launched += 1
                workdir = os.path.join(base, f"s{seed}_{launched}")
                os.makedirs(workdir, exist_ok=True)
                errpath = os.path.join(workdir, "trace.txt")
                rfd, wfd = os.pipe()
                pid = os.fork()
                if pid == 0:
                    os.close(rfd)
                    _child(lib, spec, workdir, wfd, errpath)
                os.close(wfd)
                running[rfd] = {"pid": pid, "seed": seed, "start": time.monotonic(), "buf": bytearray(),
                                "workdir": workdir, "errpath": errpath}
            if not running:
                break
            ready, _, _ = select.select(list(running), [], [], 0.2)
            now = time.monotonic()
            finished = []
            for rfd in ready:
                chunk = os.read(rfd, 1 << 16)
                if chunk:
                    running[rfd]["buf"] += chunk
                else:
                    finished.append(rfd)
            for rfd, job in running.items():
                if rfd not in finished and now - job["start"] > timeout:
                    os.kill(job["pid"], signal.SIGKILL)
                    job["hung"] = True
                    finished.append(rfd)
            for rfd in finished:
                job = running.pop(rfd)
                os.close(rfd)
                _, status = os.waitpid(job["pid"], 0)
                secs = time.monotonic() - job["start"]
                tail = _tail(job["errpath"])
                seed = job["seed"]
                if job.get("hung"):
                    o = Outcome(seed, "hang", secs, detail=f"no result after {timeout:.0f} s; last calls: "
                                + " | ".join(ln.strip() for ln in tail[-3:]), trace=tail)
                elif os.WIFSIGNALED(status):
                    sig = signal.Signals(os.WTERMSIG(status)).name
                    o = Outcome(seed, "crash", secs, detail=f"killed by {sig}; last lines: "
                                + " | ".join(ln.strip() for ln in tail[-3:]), trace=tail)
                elif os.WEXITSTATUS(status) != 0 or not job["buf"]:
                    o = Outcome(seed, "harness", secs,
                                detail=f"child exit {os.WEXITSTATUS(status)}: " + " | ".join(tail[-3:]), trace=tail)
                else:
                    res = json.loads(job["buf"])
                    kind = "fail" if res["failures"] else "ok"
                    o = Outcome(seed, kind, res["seconds"], failures=res["failures"],
                                trace=tail if kind == "fail" else [],
                                calls=res["calls"] if (keep_calls or kind == "fail") else [], stats=res["stats"],
                                longest_step=res.get("longest_step", 0.0), work_ratio=res.get("work_ratio", 0.0))
                if o.kind != "ok":
                    n_bad += 1
                outcomes.append(o)
                if o.kind == "ok":
                    _rmtree(job["workdir"])
                if progress:
                    progress(o, len(outcomes))
    finally:
        for job in running.values():
            try:
                os.kill(job["pid"], signal.SIGKILL)
                os.waitpid(job["pid"], 0)
            except OSError:
                pass
        _rmtree(base)
    return outcomes


def _rmtree(path):
    import shutil
    shutil.rmtree(path, ignore_errors=True)


def seeds(base, n):
    """The seeds of a run: base, base+1, ..."""
    return [(base + k, None) for k in range(n)]


def tally(outcomes):
    """Counts for the summary table."""
    c = {"sequences": len(outcomes), "crashes": 0, "hangs": 0, "ok_nonfinite": 0, "recovery": 0, "fatal": 0,
         "unreadable": 0, "other": 0, "harness": 0}
    for o in outcomes:
        if o.kind == "crash":
            c["crashes"] += 1
        elif o.kind == "hang":
            c["hangs"] += 1
        elif o.kind == "harness":
            c["harness"] += 1
        elif o.kind == "fail":
            kinds = {f["kind"] for f in o.failures}
            if "ok_nonfinite" in kinds:
                c["ok_nonfinite"] += 1
            if "recovery" in kinds:
                c["recovery"] += 1
            if "fatal" in kinds:
                c["fatal"] += 1
            if "unreadable" in kinds:
                c["unreadable"] += 1
            if kinds - {"ok_nonfinite", "recovery", "fatal", "unreadable"}:
                c["other"] += 1
    return c
