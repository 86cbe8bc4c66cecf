//! A checked, compiled theory behind an opaque handle, whose header outlives
//! `proclaim_theory_free` so that a freed theory is detected, not used.

use crate::detail::{fail, reported};
use crate::error::ProclaimError;
use crate::guard::{guarded, guarded_else};
use crate::status::ProclaimStatus;
use crate::text_from_c::{nul_terminated, sized, BadText};
use proclaim_cdl::{load_named, Engine, Language};
use std::ffi::c_char;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::{Arc, Mutex, PoisonError};

/// A theory, immutable once loaded: sessions share it and may outlive the handle. The pointer C
/// holds is a small header that is never deallocated: `proclaim_theory_free` drops the theory
/// and empties the header, so that later calls answer `DEAD_HANDLE`. Each call takes its own
/// reference to the theory under a lock (no call on a theory is on a proving loop's path), so a
/// free on another thread never pulls the theory from under a running call.
pub struct ProclaimTheory {
    engine: Mutex<Option<Arc<Engine>>>,
    /// This load's identity, carried by its atom and literal handles (`handles.rs`).
    tag: u32,
}

/// The engine behind `theory` and its identity: `BAD_ARGUMENT` for null, `DEAD_HANDLE` once freed.
///
/// # Safety
/// `theory` is null or a pointer from [`proclaim_theory_load`] (freed or not).
pub(crate) unsafe fn live_theory(
    theory: *const ProclaimTheory,
) -> Result<(Arc<Engine>, u32), ProclaimStatus> {
    let theory = theory
        .as_ref()
        .ok_or_else(|| fail(ProclaimStatus::BadArgument, "the theory is null"))?;
    // Nothing panics while the lock is held, so a poisoned lock still holds a sound value.
    let engine = theory.engine.lock().unwrap_or_else(PoisonError::into_inner);
    let engine = engine.as_ref().ok_or(ProclaimStatus::DeadHandle)?;
    Ok((engine.clone(), theory.tag))
}

/// The next theory's identity. It wraps after 2^32 loads; a handle kept that long could then
/// pass for one of a newer theory's, whose range check still keeps it in bounds.
static NEXT_TAG: AtomicU32 = AtomicU32::new(1);

/// The name a theory is loaded under when none is given, as in `proclaim_cdl::load`.
const UNNAMED: &str = "theory";

/// Loads a theory from `len` bytes of `.dl` text (no terminator needed). Returns the theory, or
/// null with `*error_out` set to why (every error, with the first one's line and column), which
/// the caller frees with `proclaim_error_free`. `error_out` may be null when the reason is not
/// wanted; on success `*error_out` is set to null.
///
/// # Safety
/// `text` is null or points to `len` readable bytes; `error_out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn proclaim_theory_load(
    text: *const c_char,
    len: usize,
    error_out: *mut *mut ProclaimError,
) -> *mut ProclaimTheory {
    load(Ok(UNNAMED), text, len, error_out)
}

/// [`proclaim_theory_load`] of the `len` bytes at `text`, naming them `name` (a file name) in
/// the errors written to `*error_out`; a name ending in `.dfl` is read as DFL (SPINdle's
/// syntax), anything else as `.dl`.
///
/// # Safety
/// `name` is null or a NUL-terminated string; otherwise as [`proclaim_theory_load`].
#[no_mangle]
pub unsafe extern "C" fn proclaim_theory_load_named(
    name: *const c_char,
    text: *const c_char,
    len: usize,
    error_out: *mut *mut ProclaimError,
) -> *mut ProclaimTheory {
    load(nul_terminated(name), text, len, error_out)
}

/// Loads the theory file at `path` (a NUL-terminated path; `.dfl` is read as DFL, anything else
/// as `.dl`): [`proclaim_theory_load_named`] of its contents, named by `path`. A file that
/// cannot be read is an error like any other: null, with `*error_out` naming the file and
/// saying why ("No such file or directory").
///
/// # Safety
/// `path` is null or a NUL-terminated string; `error_out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn proclaim_theory_load_file(
    path: *const c_char,
    error_out: *mut *mut ProclaimError,
) -> *mut ProclaimTheory {
    let name = nul_terminated(path);
    // Within the bound every source is read within, which says its size where it is larger.
    let read = name.map(|path| {
        let bytes = proclaim_syntax::read_within(path, proclaim_syntax::MAX_SOURCE_BYTES);
        (path, bytes)
    });
    match read {
        Ok((path, Ok(bytes))) => load(Ok(path), bytes.as_ptr().cast(), bytes.len(), error_out),
        Ok((path, Err(why))) => {
            let why = match why {
                proclaim_syntax::Unread::Io(e) => e.to_string(),
                proclaim_syntax::Unread::TooLarge(size) => proclaim_syntax::too_large(size),
            };
            let error = ProclaimError::boxed(path, None, &format!("{path} cannot be read: {why}"));
            hand_out(std::ptr::null_mut(), error, error_out)
        }
        Err(bad) => {
            let error = ProclaimError::boxed(UNNAMED, None, &format!("the path: {bad}"));
            hand_out(std::ptr::null_mut(), error, error_out)
        }
    }
}

unsafe fn load(
    name: Result<&str, BadText>,
    text: *const c_char,
    len: usize,
    error_out: *mut *mut ProclaimError,
) -> *mut ProclaimTheory {
    let outcome = guarded_else(
        || {
            Err(ProclaimError::boxed(
                name.unwrap_or(UNNAMED),
                None,
                "the reasoner panicked while loading the theory (a bug; the panic was stopped \
                 here)",
            ))
        },
        || -> Result<*mut ProclaimTheory, *mut ProclaimError> {
            let name = name.map_err(|bad| {
                ProclaimError::boxed(UNNAMED, None, &format!("the theory's name: {bad}"))
            })?;
            let source = sized(text, len).map_err(|bad| {
                let place = match bad {
                    BadText::Null => None,
                    BadText::NotUtf8 { valid_up_to } => {
                        // The valid prefix is UTF-8, so the place can be counted in characters.
                        let prefix = std::str::from_utf8(std::slice::from_raw_parts(
                            text.cast::<u8>(),
                            valid_up_to,
                        ))
                        .unwrap_or_default();
                        Some(proclaim_syntax::line_column(prefix, valid_up_to))
                    }
                };
                ProclaimError::boxed(name, place, &bad.to_string())
            })?;
            let language = if name.ends_with(".dfl") {
                Language::Dfl
            } else {
                Language::Dl
            };
            match load_named(name, source, language) {
                Ok(theory) => Ok(Box::into_raw(Box::new(ProclaimTheory {
                    engine: Mutex::new(Some(Arc::new(Engine::new(theory)))),
                    tag: NEXT_TAG.fetch_add(1, Ordering::Relaxed),
                }))),
                Err(error) => {
                    let place = error
                        .diagnostics()
                        .first()
                        .map(|d| proclaim_syntax::line_column(source, d.span.start as usize));
                    Err(ProclaimError::boxed(name, place, &error.to_string()))
                }
            }
        },
    );
    match outcome {
        Ok(theory) => hand_out(theory, std::ptr::null_mut(), error_out),
        Err(error) => hand_out(std::ptr::null_mut(), error, error_out),
    }
}

/// A load's outcome as C receives it: `theory`, and `error` (null on success) written to
/// `*error_out`, or deallocated whole when the caller did not ask for it; its message is the
/// thread's last error message too.
///
/// # Safety
/// `error` is null or from [`ProclaimError::boxed`], not handed out yet; `error_out` is null or
/// writable.
unsafe fn hand_out(
    theory: *mut ProclaimTheory,
    error: *mut ProclaimError,
    error_out: *mut *mut ProclaimError,
) -> *mut ProclaimTheory {
    if let Some(message) = error.as_ref().and_then(|e| e.message.as_ref()) {
        crate::detail::set(&std::ffi::CStr::from_ptr(message).to_string_lossy());
    }
    if error_out.is_null() {
        ProclaimError::discard(error);
    } else {
        *error_out = error;
    }
    theory
}

/// Frees a theory: `OK`, or `DEAD_HANDLE` when it was freed already. Sessions made from it keep
/// working (they hold their own reference). Null is ignored (`OK`), as with `free()`.
///
/// What stays allocated is the handle's header (a lock, an empty slot and the theory's
/// identity: a few dozen bytes), so that later calls with the pointer say `DEAD_HANDLE`; it is
/// never reused, so no later theory can be mistaken for this one.
///
/// # Safety
/// `theory` is null or a pointer from [`proclaim_theory_load`] (freed or not).
#[no_mangle]
pub unsafe extern "C" fn proclaim_theory_free(theory: *mut ProclaimTheory) -> ProclaimStatus {
    let Some(theory) = theory.as_ref() else {
        return ProclaimStatus::Ok;
    };
    let engine = theory
        .engine
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .take();
    match engine {
        // Dropped outside the lock: the last reference frees the whole theory.
        Some(engine) => {
            crate::kept::keep(theory);
            guarded(ProclaimStatus::Panic, || {
                drop(engine);
                ProclaimStatus::Ok
            })
        }
        None => reported(ProclaimStatus::DeadHandle),
    }
}
