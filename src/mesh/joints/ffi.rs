//! gmsh's C API (`gmshc.h` of gmsh 4.8), loaded at run time from
//! `libgmsh.so.4.8`: the shared library the Debian `gmsh` package itself
//! runs on (package `libgmsh4.8`, a dependency of `gmsh`), so every machine
//! with the gmsh CLI has it, and the binary builds and runs without it for
//! scenes that cut nothing. The soname fixes the API version: the
//! signatures below are those of 4.8 (later versions changed some, e.g.
//! `gmshInitialize`), so no other version is loaded.
//!
//! Only the functions the joint cutter calls are bound; [`Lib::get`] loads
//! them once per process. Everything here is `unsafe` plumbing: the safe
//! calls are in `api.rs`.

use std::ffi::{c_char, c_int, c_void, CStr};
use std::sync::OnceLock;

/// The library file names tried, in order.
pub(super) const LIBRARY: &[&str] = &["libgmsh.so.4.8", "libgmsh.so.4.8.4"];

macro_rules! gmsh_api {
    ($($name:ident: fn($($arg:ty),* $(,)?) $(-> $ret:ty)?;)*) => {
        /// The bound functions of the gmsh C API.
        #[allow(non_snake_case)]
        pub(super) struct Lib {
            $(pub(super) $name: unsafe extern "C" fn($($arg),*) $(-> $ret)?,)*
        }

        impl Lib {
            /// Looks every function up in the library `handle` (the file
            /// `library`); Err names the first missing one.
            unsafe fn bind(handle: *mut c_void, library: &'static str) -> Result<Lib, LoadError> {
                Ok(Lib {
                    $($name: {
                        let sym = concat!(stringify!($name), "\0");
                        let p = libc::dlsym(handle, sym.as_ptr().cast::<c_char>());
                        if p.is_null() {
                            return Err(LoadError::Missing { library, function: stringify!($name) });
                        }
                        std::mem::transmute::<*mut c_void, unsafe extern "C" fn($($arg),*) $(-> $ret)?>(p)
                    },)*
                })
            }
        }
    };
}

type Ierr = *mut c_int;

gmsh_api! {
    gmshInitialize: fn(c_int, *mut *mut c_char, c_int, Ierr);
    gmshFinalize: fn(Ierr);
    gmshOpen: fn(*const c_char, Ierr);
    gmshWrite: fn(*const c_char, Ierr);
    gmshFree: fn(*mut c_void);
    gmshOptionSetNumber: fn(*const c_char, f64, Ierr);
    gmshOptionGetNumber: fn(*const c_char, *mut f64, Ierr);
    gmshLoggerStart: fn(Ierr);
    gmshLoggerGet: fn(*mut *mut *mut c_char, *mut usize, Ierr);
    gmshLoggerStop: fn(Ierr);
    gmshModelGetEntities: fn(*mut *mut c_int, *mut usize, c_int, Ierr);
    gmshModelGetPhysicalGroups: fn(*mut *mut c_int, *mut usize, c_int, Ierr);
    gmshModelGetEntitiesForPhysicalGroup: fn(c_int, c_int, *mut *mut c_int, *mut usize, Ierr);
    gmshModelGetPhysicalName: fn(c_int, c_int, *mut *mut c_char, Ierr);
    gmshModelAddPhysicalGroup: fn(c_int, *mut c_int, usize, c_int, Ierr) -> c_int;
    gmshModelSetPhysicalName: fn(c_int, c_int, *const c_char, Ierr);
    gmshModelRemovePhysicalGroups: fn(*mut c_int, usize, Ierr);
    gmshModelGetBoundary: fn(*mut c_int, usize, *mut *mut c_int, *mut usize, c_int, c_int, c_int, Ierr);
    gmshModelGetAdjacencies: fn(c_int, c_int, *mut *mut c_int, *mut usize, *mut *mut c_int, *mut usize, Ierr);
    gmshModelGetValue: fn(c_int, c_int, *mut f64, usize, *mut *mut f64, *mut usize, Ierr);
    gmshModelMeshGenerate: fn(c_int, Ierr);
    gmshModelMeshClear: fn(*mut c_int, usize, Ierr);
    gmshModelMeshGetNodes: fn(
        *mut *mut usize, *mut usize, *mut *mut f64, *mut usize, *mut *mut f64, *mut usize, c_int, c_int, c_int, c_int, Ierr,
    );
    gmshModelMeshGetElementsByType: fn(c_int, *mut *mut usize, *mut usize, *mut *mut usize, *mut usize, c_int, usize, usize, Ierr);
    gmshModelMeshGetEmbedded: fn(c_int, c_int, *mut *mut c_int, *mut usize, Ierr);
    gmshModelMeshSetSize: fn(*mut c_int, usize, f64, Ierr);
    gmshModelMeshSetNode: fn(usize, *mut f64, usize, *mut f64, usize, Ierr);
    gmshModelMeshSetTransfiniteAutomatic: fn(*mut c_int, usize, f64, c_int, Ierr);
    gmshModelOccAddPoint: fn(f64, f64, f64, f64, c_int, Ierr) -> c_int;
    gmshModelOccAddLine: fn(c_int, c_int, c_int, Ierr) -> c_int;
    gmshModelOccAddCurveLoop: fn(*mut c_int, usize, c_int, Ierr) -> c_int;
    gmshModelOccAddPlaneSurface: fn(*mut c_int, usize, c_int, Ierr) -> c_int;
    gmshModelOccAddDisk: fn(f64, f64, f64, f64, f64, c_int, Ierr) -> c_int;
    gmshModelOccAddBox: fn(f64, f64, f64, f64, f64, f64, c_int, Ierr) -> c_int;
    gmshModelOccAddRectangle: fn(f64, f64, f64, f64, f64, c_int, f64, Ierr) -> c_int;
    gmshModelOccRotate: fn(*mut c_int, usize, f64, f64, f64, f64, f64, f64, f64, Ierr);
    gmshModelOccTranslate: fn(*mut c_int, usize, f64, f64, f64, Ierr);
    gmshModelOccFragment: fn(
        *mut c_int, usize, *mut c_int, usize, *mut *mut c_int, *mut usize, *mut *mut *mut c_int, *mut *mut usize,
        *mut usize, c_int, c_int, c_int, Ierr,
    );
    gmshModelOccIntersect: fn(
        *mut c_int, usize, *mut c_int, usize, *mut *mut c_int, *mut usize, *mut *mut *mut c_int, *mut *mut usize,
        *mut usize, c_int, c_int, c_int, Ierr,
    );
    gmshModelOccRemove: fn(*mut c_int, usize, c_int, Ierr);
    gmshModelOccSynchronize: fn(Ierr);
    gmshModelOccGetEntities: fn(*mut *mut c_int, *mut usize, c_int, Ierr);
    gmshModelOccGetBoundingBox: fn(c_int, c_int, *mut f64, *mut f64, *mut f64, *mut f64, *mut f64, *mut f64, Ierr);
    gmshModelOccGetMass: fn(c_int, c_int, *mut f64, Ierr);
    gmshModelOccGetCenterOfMass: fn(c_int, c_int, *mut f64, *mut f64, *mut f64, Ierr);
}

// SAFETY: the table holds plain function pointers into a library that is
// never unloaded; gmsh's own global state is guarded by the session lock
// in `api.rs`.
unsafe impl Send for Lib {}
unsafe impl Sync for Lib {}

impl Lib {
    /// The library, loaded on first use; Err says why it could not be.
    pub(super) fn get() -> Result<&'static Lib, LoadError> {
        static LIB: OnceLock<Result<Lib, LoadError>> = OnceLock::new();
        LIB.get_or_init(load).as_ref().map_err(Clone::clone)
    }
}

/// Why gmsh's library could not be loaded.
#[derive(Clone, Debug, thiserror::Error)]
pub enum LoadError {
    /// No file of [`LIBRARY`] could be opened: dlerror's message for each.
    #[error("{}", .0.join("; "))]
    NotFound(Vec<String>),
    /// The library lacks a function of the API.
    #[error("{library} has no function {function}: not gmsh 4.8's C API")]
    Missing { library: &'static str, function: &'static str },
}

fn load() -> Result<Lib, LoadError> {
    let mut why = Vec::new();
    for name in LIBRARY {
        let cname = format!("{name}\0");
        // SAFETY: dlopen takes a NUL-terminated name; RTLD_NOW resolves
        // everything at once, so a broken library fails here.
        let handle = unsafe { libc::dlopen(cname.as_ptr().cast::<c_char>(), libc::RTLD_NOW | libc::RTLD_LOCAL) };
        if handle.is_null() {
            why.push(dl_error());
            continue;
        }
        // SAFETY: the symbols are gmsh 4.8's C API, whose signatures the
        // table declares (the soname pins the version).
        return unsafe { Lib::bind(handle, name) };
    }
    Err(LoadError::NotFound(why))
}

/// dlerror's message, or a generic one.
fn dl_error() -> String {
    // SAFETY: dlerror returns NULL or a NUL-terminated string owned by libc.
    let e = unsafe { libc::dlerror() };
    if e.is_null() {
        "cannot load the library".to_string()
    } else {
        // SAFETY: non-null, NUL-terminated (above).
        unsafe { CStr::from_ptr(e) }.to_string_lossy().into_owned()
    }
}
