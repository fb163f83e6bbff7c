//! The FMI 2.0 C ABI: thin `unsafe extern "C"` shims over the safe
//! [`Instance`]. The only `unsafe` code of the crate lives here. Every export
//! runs inside `guard` (`catch_unwind`), so no panic crosses the C boundary (as rustls-ffi's
//! `panic.rs` does); instances are opaque `Box::into_raw` handles; the state
//! machine is checked by `Instance::check` against one table.
//!
//! Signatures follow `fmi2FunctionTypes.h` (FMI 2.0.x): fmi2Component and
//! fmi2FMUstate are `void*`, fmi2ValueReference `unsigned int`, fmi2Boolean
//! and fmi2Integer `int`, fmi2Real `double`, fmi2String `const char*`.

#![allow(non_snake_case)]

use super::instance::{Category, Instance, Op, Saved, Status, Value};
use super::vars::Kind;
use libc::{c_char, c_double, c_int, c_uint, c_void, size_t};
use std::ffi::{CStr, CString};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::PathBuf;

type Component = *mut c_void;
type FmuState = *mut c_void;

/// fmi2CallbackLogger: C-variadic; we always pass "%s" and one message.
type Logger = Option<
    unsafe extern "C" fn(
        env: *mut c_void,
        instance_name: *const c_char,
        status: c_int,
        category: *const c_char,
        message: *const c_char,
        ...
    ),
>;

/// fmi2CallbackFunctions.
#[repr(C)]
pub struct CallbackFunctions {
    logger: Logger,
    allocate_memory: Option<unsafe extern "C" fn(size_t, size_t) -> *mut c_void>,
    free_memory: Option<unsafe extern "C" fn(*mut c_void)>,
    step_finished: Option<unsafe extern "C" fn(*mut c_void, c_int)>,
    component_environment: *mut c_void,
}

const ERROR: c_int = Status::Error as c_int;

/// Runs `f`, turning a panic into `on_panic` (no unwinding into C).
fn guard<T>(on_panic: T, f: impl FnOnce() -> T) -> T {
    catch_unwind(AssertUnwindSafe(f)).unwrap_or(on_panic)
}

/// The instance behind a handle.
///
/// # Safety
/// `c` must be null or a handle returned by `fmi2Instantiate` and not yet freed,
/// used by one thread at a time (FMI 2.0 §2.1.5).
unsafe fn inst<'a>(c: Component) -> Option<&'a mut Instance> {
    if c.is_null() { None } else { Some(unsafe { &mut *(c as *mut Instance) }) }
}

/// A C string as a Rust string.
///
/// # Safety
/// `s` must be null or a NUL-terminated string valid for reads.
unsafe fn string(s: *const c_char) -> Option<String> {
    if s.is_null() { None } else { Some(unsafe { CStr::from_ptr(s) }.to_string_lossy().into_owned()) }
}

/// The resources directory from an fmuResourceLocation URI (`file:/`,
/// `file:///`, `file://host/`, percent-encoded), or None.
pub fn resource_dir(uri: &str) -> Option<PathBuf> {
    let rest = uri.strip_prefix("file://localhost/").map(|r| format!("/{r}")).or_else(|| {
        uri.strip_prefix("file:///")
            .map(|r| format!("/{r}"))
            .or_else(|| uri.strip_prefix("file://").map(|r| r.to_string()))
            .or_else(|| uri.strip_prefix("file:").map(|r| r.to_string()))
    })?;
    let bytes = rest.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' && i + 2 < bytes.len() {
            if let Ok(v) = u8::from_str_radix(std::str::from_utf8(&bytes[i + 1..i + 3]).ok()?, 16) {
                out.push(v);
                i += 3;
                continue;
            }
        }
        out.push(bytes[i]);
        i += 1;
    }
    let s = String::from_utf8(out).ok()?;
    Some(PathBuf::from(s))
}

/// # Safety
/// No arguments; returns a static string.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    c"default".as_ptr()
}

/// # Safety
/// No arguments; returns a static string.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetVersion() -> *const c_char {
    c"2.0".as_ptr()
}

/// # Safety
/// `name`, `guid`, `resources` must be null or NUL-terminated strings;
/// `functions` must be null or point to a valid fmi2CallbackFunctions that
/// outlives the instance.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2Instantiate(
    name: *const c_char,
    fmu_type: c_int,
    guid: *const c_char,
    resources: *const c_char,
    functions: *const CallbackFunctions,
    _visible: c_int,
    logging_on: c_int,
) -> Component {
    guard(std::ptr::null_mut(), || {
        let name = unsafe { string(name) }.unwrap_or_else(|| "riser".into());
        let (logger_fn, env) = if functions.is_null() {
            (None, std::ptr::null_mut())
        } else {
            let f = unsafe { &*functions };
            (f.logger, f.component_environment)
        };
        let env_addr = env as usize;
        let cname = CString::new(name.clone()).unwrap_or_default();
        let logger: super::instance::Logger = std::sync::Arc::new(move |status: Status, cat: &str, msg: &str| {
            if let Some(log) = logger_fn {
                let cat = CString::new(cat).unwrap_or_default();
                let msg = CString::new(msg.replace('\0', " ")).unwrap_or_default();
                // SAFETY: the master's logger, called as fmi2CallbackLogger with a "%s" format
                unsafe {
                    log(
                        env_addr as *mut c_void,
                        cname.as_ptr(),
                        status as c_int,
                        cat.as_ptr(),
                        c"%s".as_ptr(),
                        msg.as_ptr(),
                    )
                };
            }
        });
        if fmu_type != 1 {
            logger(Status::Error, Category::Error.name(), "riser is a Co-Simulation FMU (fmi2CoSimulation = 1)");
            return std::ptr::null_mut();
        }
        let guid = unsafe { string(guid) }.unwrap_or_default();
        let res = unsafe { string(resources) }.and_then(|r| resource_dir(&r));
        match Instance::new(&name, &guid, res, logger, logging_on != 0) {
            Ok(i) => Box::into_raw(Box::new(i)) as Component,
            Err(msg) => {
                if let Some(log) = logger_fn {
                    let cname = CString::new(name).unwrap_or_default();
                    let msg = CString::new(msg).unwrap_or_default();
                    // SAFETY: as above
                    unsafe {
                        log(env, cname.as_ptr(), ERROR, c"logStatusError".as_ptr(), c"%s".as_ptr(), msg.as_ptr())
                    };
                }
                std::ptr::null_mut()
            }
        }
    })
}

/// # Safety
/// `c` must be null or a live handle from `fmi2Instantiate`; it is invalid afterwards.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2FreeInstance(c: Component) {
    guard((), || {
        if !c.is_null() {
            drop(unsafe { Box::from_raw(c as *mut Instance) });
        }
    })
}

/// Runs `f` on the instance after checking the state machine for `op`.
///
/// # Safety
/// As [`inst`].
unsafe fn with(c: Component, op: Option<Op>, fname: &str, f: impl FnOnce(&mut Instance) -> Status) -> c_int {
    guard(Status::Fatal as c_int, || {
        let Some(i) = (unsafe { inst(c) }) else { return ERROR };
        if let Some(op) = op
            && let Err(s) = i.check(op, fname)
        {
            return s as c_int;
        }
        f(i) as c_int
    })
}

/// # Safety
/// `c` a live handle; `categories` null or `n` valid C strings.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetDebugLogging(
    c: Component,
    on: c_int,
    n: size_t,
    categories: *const *const c_char,
) -> c_int {
    unsafe {
        with(c, Some(Op::SetDebugLogging), "fmi2SetDebugLogging", |i| {
            let cats: Vec<String> =
                if categories.is_null() { vec![] } else { (0..n).filter_map(|k| string(*categories.add(k))).collect() };
            i.set_debug_logging(on != 0, &cats)
        })
    }
}

/// # Safety
/// `c` a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetupExperiment(
    c: Component,
    _tol_defined: c_int,
    _tol: c_double,
    start: c_double,
    _stop_defined: c_int,
    _stop: c_double,
) -> c_int {
    unsafe { with(c, Some(Op::SetupExperiment), "fmi2SetupExperiment", |i| i.setup_experiment(start)) }
}

/// # Safety
/// `c` a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2EnterInitializationMode(c: Component) -> c_int {
    unsafe {
        with(c, Some(Op::EnterInitializationMode), "fmi2EnterInitializationMode", |i| i.enter_initialization_mode())
    }
}

/// # Safety
/// `c` a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2ExitInitializationMode(c: Component) -> c_int {
    unsafe { with(c, Some(Op::ExitInitializationMode), "fmi2ExitInitializationMode", |i| i.exit_initialization_mode()) }
}

/// # Safety
/// `c` a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2Terminate(c: Component) -> c_int {
    unsafe { with(c, Some(Op::Terminate), "fmi2Terminate", |i| i.terminate()) }
}

/// # Safety
/// `c` a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2Reset(c: Component) -> c_int {
    unsafe { with(c, Some(Op::Reset), "fmi2Reset", |i| i.reset()) }
}

/// # Safety
/// `c` a live handle; `vr` and `value` arrays of `n` elements (value writable).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetReal(c: Component, vr: *const c_uint, n: size_t, value: *mut c_double) -> c_int {
    unsafe {
        with(c, Some(Op::Get), "fmi2GetReal", |i| {
            if n > 0 && (vr.is_null() || value.is_null()) {
                return i.fail("fmi2GetReal: null array");
            }
            for k in 0..n {
                match i.get_real(*vr.add(k)) {
                    Ok(v) => *value.add(k) = v,
                    Err(s) => return s,
                }
            }
            Status::Ok
        })
    }
}

/// Shared body of the Integer/Boolean getters.
///
/// # Safety
/// As the getters.
unsafe fn get_int_like(
    c: Component,
    vr: *const c_uint,
    n: size_t,
    value: *mut c_int,
    kind: Kind,
    fname: &str,
) -> c_int {
    unsafe {
        with(c, Some(Op::Get), fname, |i| {
            if n > 0 && (vr.is_null() || value.is_null()) {
                return i.fail(&format!("{fname}: null array"));
            }
            for k in 0..n {
                match i.get_param(*vr.add(k), kind) {
                    Ok(Value::Integer(x)) => *value.add(k) = x,
                    Ok(Value::Boolean(b)) => *value.add(k) = b as c_int,
                    Ok(_) => return i.fail(&format!("{fname}: wrong type")),
                    Err(s) => return s,
                }
            }
            Status::Ok
        })
    }
}

/// # Safety
/// `c` a live handle; `vr` and `value` arrays of `n` elements.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetInteger(c: Component, vr: *const c_uint, n: size_t, value: *mut c_int) -> c_int {
    unsafe { get_int_like(c, vr, n, value, Kind::Integer, "fmi2GetInteger") }
}

/// # Safety
/// `c` a live handle; `vr` and `value` arrays of `n` elements.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetBoolean(c: Component, vr: *const c_uint, n: size_t, value: *mut c_int) -> c_int {
    unsafe { get_int_like(c, vr, n, value, Kind::Boolean, "fmi2GetBoolean") }
}

thread_local! {
    /// Backing store of strings returned by fmi2GetString (valid until the next call on this thread).
    static STRINGS: std::cell::RefCell<Vec<CString>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// # Safety
/// `c` a live handle; `vr` and `value` arrays of `n` elements. Returned
/// strings stay valid until the next fmi2GetString on the same thread.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetString(c: Component, vr: *const c_uint, n: size_t, value: *mut *const c_char) -> c_int {
    unsafe {
        with(c, Some(Op::Get), "fmi2GetString", |i| {
            if n > 0 && (vr.is_null() || value.is_null()) {
                return i.fail("fmi2GetString: null array");
            }
            let mut strings = Vec::with_capacity(n);
            for k in 0..n {
                match i.get_param(*vr.add(k), Kind::String) {
                    Ok(Value::String(s)) => strings.push(CString::new(s).unwrap_or_default()),
                    Ok(_) => return i.fail("fmi2GetString: wrong type"),
                    Err(s) => return s,
                }
            }
            for (k, s) in strings.iter().enumerate() {
                *value.add(k) = s.as_ptr();
            }
            STRINGS.with(|st| *st.borrow_mut() = strings);
            Status::Ok
        })
    }
}

/// # Safety
/// `c` a live handle; `vr` and `value` arrays of `n` elements.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetReal(c: Component, vr: *const c_uint, n: size_t, value: *const c_double) -> c_int {
    unsafe {
        with(c, None, "fmi2SetReal", |i| {
            if n > 0 && (vr.is_null() || value.is_null()) {
                return i.fail("fmi2SetReal: null array");
            }
            for k in 0..n {
                let s = i.set_real(*vr.add(k), *value.add(k));
                if s != Status::Ok {
                    return s;
                }
            }
            Status::Ok
        })
    }
}

/// # Safety
/// `c` a live handle; `vr` and `value` arrays of `n` elements.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetInteger(c: Component, vr: *const c_uint, n: size_t, value: *const c_int) -> c_int {
    unsafe {
        with(c, None, "fmi2SetInteger", |i| {
            if n > 0 && (vr.is_null() || value.is_null()) {
                return i.fail("fmi2SetInteger: null array");
            }
            for k in 0..n {
                let s = i.set_param(*vr.add(k), Value::Integer(*value.add(k)));
                if s != Status::Ok {
                    return s;
                }
            }
            Status::Ok
        })
    }
}

/// # Safety
/// `c` a live handle; `vr` and `value` arrays of `n` elements.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetBoolean(c: Component, vr: *const c_uint, n: size_t, value: *const c_int) -> c_int {
    unsafe {
        with(c, None, "fmi2SetBoolean", |i| {
            if n > 0 && (vr.is_null() || value.is_null()) {
                return i.fail("fmi2SetBoolean: null array");
            }
            for k in 0..n {
                let s = i.set_param(*vr.add(k), Value::Boolean(*value.add(k) != 0));
                if s != Status::Ok {
                    return s;
                }
            }
            Status::Ok
        })
    }
}

/// # Safety
/// `c` a live handle; `vr` and `value` arrays of `n` elements, each value a C string.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetString(
    c: Component,
    vr: *const c_uint,
    n: size_t,
    value: *const *const c_char,
) -> c_int {
    unsafe {
        with(c, None, "fmi2SetString", |i| {
            if n > 0 && (vr.is_null() || value.is_null()) {
                return i.fail("fmi2SetString: null array");
            }
            for k in 0..n {
                let Some(v) = string(*value.add(k)) else { return i.fail("fmi2SetString: null string") };
                let s = i.set_param(*vr.add(k), Value::String(v));
                if s != Status::Ok {
                    return s;
                }
            }
            Status::Ok
        })
    }
}

/// # Safety
/// `c` a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2DoStep(c: Component, t: c_double, h: c_double, _no_set_prior: c_int) -> c_int {
    unsafe { with(c, Some(Op::DoStep), "fmi2DoStep", |i| i.do_step(t, h)) }
}

/// # Safety
/// `c` a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2CancelStep(c: Component) -> c_int {
    unsafe { with(c, None, "fmi2CancelStep", |i| i.fail("fmi2CancelStep: steps are synchronous, nothing to cancel")) }
}

/// # Safety
/// `c` a live handle; `value` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetStatus(c: Component, kind: c_int, value: *mut c_int) -> c_int {
    unsafe {
        with(c, Some(Op::GetStatus), "fmi2GetStatus", |i| {
            if value.is_null() || kind != 0 {
                return i.fail("fmi2GetStatus: only fmi2DoStepStatus is provided");
            }
            *value = i.last_status() as c_int;
            Status::Ok
        })
    }
}

/// # Safety
/// `c` a live handle; `value` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetRealStatus(c: Component, kind: c_int, value: *mut c_double) -> c_int {
    unsafe {
        with(c, Some(Op::GetStatus), "fmi2GetRealStatus", |i| {
            // fmi2LastSuccessfulTime = 2
            if value.is_null() || kind != 2 {
                return i.fail("fmi2GetRealStatus: only fmi2LastSuccessfulTime is provided");
            }
            *value = i.last_successful_time();
            Status::Ok
        })
    }
}

/// # Safety
/// `c` a live handle; `value` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetIntegerStatus(c: Component, _kind: c_int, _value: *mut c_int) -> c_int {
    unsafe { with(c, None, "fmi2GetIntegerStatus", |i| i.fail("fmi2GetIntegerStatus: no integer status is provided")) }
}

/// # Safety
/// `c` a live handle; `value` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetBooleanStatus(c: Component, kind: c_int, value: *mut c_int) -> c_int {
    unsafe {
        with(c, Some(Op::GetStatus), "fmi2GetBooleanStatus", |i| {
            // fmi2Terminated = 3: true after a discarded step (the instance
            // cannot step on from fmi2LastSuccessfulTime without a restored
            // state), so that a master stops there with its results (fmpy's
            // simulate_fmu does)
            if value.is_null() || kind != 3 {
                return i.fail("fmi2GetBooleanStatus: only fmi2Terminated is provided");
            }
            *value = i.wants_to_terminate() as c_int;
            Status::Ok
        })
    }
}

/// # Safety
/// `c` a live handle; `value` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetStringStatus(c: Component, _kind: c_int, _value: *mut *const c_char) -> c_int {
    unsafe { with(c, None, "fmi2GetStringStatus", |i| i.fail("fmi2GetStringStatus: no string status is provided")) }
}

/// # Safety
/// `c` a live handle; arrays valid for `n` elements.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
    c: Component,
    vr: *const c_uint,
    n: size_t,
    order: *const c_int,
    value: *const c_double,
) -> c_int {
    unsafe {
        with(c, None, "fmi2SetRealInputDerivatives", |i| {
            if n > 0 && (vr.is_null() || order.is_null() || value.is_null()) {
                return i.fail("fmi2SetRealInputDerivatives: null array");
            }
            for k in 0..n {
                let s = i.set_input_derivative(*vr.add(k), *order.add(k), *value.add(k));
                if s != Status::Ok {
                    return s;
                }
            }
            Status::Ok
        })
    }
}

/// # Safety
/// `c` a live handle; arrays valid for `n` elements.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
    c: Component,
    _vr: *const c_uint,
    _n: size_t,
    _order: *const c_int,
    _value: *mut c_double,
) -> c_int {
    unsafe {
        with(c, None, "fmi2GetRealOutputDerivatives", |i| {
            i.fail("fmi2GetRealOutputDerivatives: maxOutputDerivativeOrder is 0")
        })
    }
}

/// The derivative of `top_force_*` with respect to `heave`, `surge`, `sway`
/// (the line's stiffness at the hang-off); other variables get fmi2Error.
///
/// # Safety
/// `c` a live handle; `unknown` and `dv_unknown` valid for `n_unknown`
/// elements, `known` and `dv_known` for `n_known` (null only when the count is 0).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetDirectionalDerivative(
    c: Component,
    unknown: *const c_uint,
    n_unknown: size_t,
    known: *const c_uint,
    n_known: size_t,
    dv_known: *const c_double,
    dv_unknown: *mut c_double,
) -> c_int {
    unsafe {
        with(c, Some(Op::GetDirectionalDerivative), "fmi2GetDirectionalDerivative", |i| {
            if (n_unknown > 0 && (unknown.is_null() || dv_unknown.is_null()))
                || (n_known > 0 && (known.is_null() || dv_known.is_null()))
            {
                return i.fail("fmi2GetDirectionalDerivative: null array");
            }
            let slice = |p: *const c_uint, n: size_t| if n == 0 { &[][..] } else { std::slice::from_raw_parts(p, n) };
            let unknowns = slice(unknown, n_unknown);
            let knowns = slice(known, n_known);
            let seeds = if n_known == 0 { &[][..] } else { std::slice::from_raw_parts(dv_known, n_known) };
            let out = if n_unknown == 0 { &mut [][..] } else { std::slice::from_raw_parts_mut(dv_unknown, n_unknown) };
            i.directional_derivative(unknowns, knowns, seeds, out)
        })
    }
}

/// # Safety
/// `c` a live handle; `state` writable; `*state` null or a state of this instance.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetFMUstate(c: Component, state: *mut FmuState) -> c_int {
    unsafe {
        with(c, Some(Op::GetFmuState), "fmi2GetFMUstate", |i| {
            if state.is_null() {
                return i.fail("fmi2GetFMUstate: null pointer");
            }
            let Some(saved) = i.save() else { return i.fail("fmi2GetFMUstate: nothing to save before initialisation") };
            if (*state).is_null() {
                *state = Box::into_raw(Box::new(saved)) as FmuState;
            } else {
                *(*state as *mut Saved) = saved;
            }
            Status::Ok
        })
    }
}

/// # Safety
/// `c` a live handle; `state` a state from fmi2GetFMUstate/fmi2DeSerializeFMUstate not yet freed.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetFMUstate(c: Component, state: FmuState) -> c_int {
    unsafe {
        with(c, Some(Op::SetFmuState), "fmi2SetFMUstate", |i| {
            if state.is_null() {
                return i.fail("fmi2SetFMUstate: null state");
            }
            let saved = &*(state as *const Saved);
            i.restore(saved)
        })
    }
}

/// # Safety
/// `c` a live handle; `state` points to null or a state not yet freed; set to null.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2FreeFMUstate(c: Component, state: *mut FmuState) -> c_int {
    unsafe {
        with(c, None, "fmi2FreeFMUstate", |_| {
            if !state.is_null() && !(*state).is_null() {
                drop(Box::from_raw(*state as *mut Saved));
                *state = std::ptr::null_mut();
            }
            Status::Ok
        })
    }
}

/// # Safety
/// `c` a live handle; `state` a live state; `size` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SerializedFMUstateSize(c: Component, state: FmuState, size: *mut size_t) -> c_int {
    unsafe {
        with(c, None, "fmi2SerializedFMUstateSize", |i| {
            if state.is_null() || size.is_null() {
                return i.fail("fmi2SerializedFMUstateSize: null pointer");
            }
            *size = i.serialize(&*(state as *const Saved)).len();
            Status::Ok
        })
    }
}

/// # Safety
/// `c` a live handle; `state` a live state; `bytes` writable for `size` bytes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SerializeFMUstate(
    c: Component,
    state: FmuState,
    bytes: *mut c_char,
    size: size_t,
) -> c_int {
    unsafe {
        with(c, None, "fmi2SerializeFMUstate", |i| {
            if state.is_null() || bytes.is_null() {
                return i.fail("fmi2SerializeFMUstate: null pointer");
            }
            let b = i.serialize(&*(state as *const Saved));
            if b.len() > size {
                return i.fail(&format!("fmi2SerializeFMUstate: {size} bytes given, {} needed", b.len()));
            }
            std::ptr::copy_nonoverlapping(b.as_ptr(), bytes as *mut u8, b.len());
            Status::Ok
        })
    }
}

/// # Safety
/// `c` a live handle; `bytes` readable for `size` bytes; `state` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
    c: Component,
    bytes: *const c_char,
    size: size_t,
    state: *mut FmuState,
) -> c_int {
    unsafe {
        with(c, None, "fmi2DeSerializeFMUstate", |i| {
            if bytes.is_null() || state.is_null() {
                return i.fail("fmi2DeSerializeFMUstate: null pointer");
            }
            let b = std::slice::from_raw_parts(bytes as *const u8, size);
            match i.deserialize(b) {
                Ok(saved) => {
                    if !(*state).is_null() {
                        drop(Box::from_raw(*state as *mut Saved));
                    }
                    *state = Box::into_raw(Box::new(saved)) as FmuState;
                    Status::Ok
                }
                Err(s) => s,
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::resource_dir;
    use std::path::PathBuf;

    #[test]
    fn resource_locations_are_decoded() {
        assert_eq!(resource_dir("file:///tmp/a%20b/resources"), Some(PathBuf::from("/tmp/a b/resources")));
        assert_eq!(resource_dir("file:/tmp/x/resources/"), Some(PathBuf::from("/tmp/x/resources/")));
        assert_eq!(resource_dir("file://localhost/tmp/r"), Some(PathBuf::from("/tmp/r")));
        assert_eq!(resource_dir("http://example.com/r"), None);
    }
}
