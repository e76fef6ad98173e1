//! Safe calls into gmsh's C API ([`super::ffi`]), one [`Session`] at a
//! time: gmsh keeps one global model, so a session holds a process-wide
//! lock from `gmshInitialize` to `gmshFinalize`. Every call checks gmsh's
//! error flag; a failed call becomes an [`ApiError`] with the call's name
//! and the `Error` lines gmsh logged. Arrays gmsh allocates are copied into
//! vectors and freed at once.

use std::ffi::{c_char, c_int, c_void, CStr, CString};
use std::path::Path;
use std::sync::{Mutex, MutexGuard};

use super::ffi::Lib;

/// An entity: (dimension, tag).
pub(super) type DimTag = (i32, i32);

/// A physical group of the model.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct PhysicalGroup {
    pub dim: i32,
    pub tag: i32,
    pub name: String,
    /// Its entities' tags (of dimension `dim`).
    pub tags: Vec<i32>,
}

/// A failed call into gmsh.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct ApiError {
    /// The C function that failed.
    pub call: &'static str,
    /// gmsh's `Error` lines since the session started, most recent last.
    pub errors: Vec<String>,
}

impl std::fmt::Display for ApiError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.errors.is_empty() {
            write!(f, "{} failed", self.call)
        } else {
            write!(f, "{} failed: {}", self.call, self.errors.join("; "))
        }
    }
}

type R<T> = Result<T, ApiError>;

/// One use of gmsh, from initialisation to finalisation, holding the
/// process-wide lock.
pub(super) struct Session {
    lib: &'static Lib,
    _lock: MutexGuard<'static, ()>,
}

static GMSH: Mutex<()> = Mutex::new(());

/// Copies `n` elements gmsh allocated at `p` and frees them.
unsafe fn take<T: Copy>(lib: &Lib, p: *mut T, n: usize) -> Vec<T> {
    if p.is_null() {
        return Vec::new();
    }
    let v = std::slice::from_raw_parts(p, n).to_vec();
    (lib.gmshFree)(p.cast::<c_void>());
    v
}

/// A gmsh-allocated C string, copied and freed.
unsafe fn take_str(lib: &Lib, p: *mut c_char) -> String {
    if p.is_null() {
        return String::new();
    }
    let s = CStr::from_ptr(p).to_string_lossy().into_owned();
    (lib.gmshFree)(p.cast::<c_void>());
    s
}

fn pairs(flat: &[c_int]) -> Vec<DimTag> {
    flat.chunks_exact(2).map(|c| (c[0], c[1])).collect()
}

fn flat(dim_tags: &[DimTag]) -> Vec<c_int> {
    dim_tags.iter().flat_map(|&(d, t)| [d, t]).collect()
}

fn c_string(s: &str) -> CString {
    // interior NULs cannot reach gmsh: they end the string there
    CString::new(s.replace('\0', "")).unwrap_or_default()
}

impl Session {
    /// Initialises gmsh with command-line `args` (`-setnumber lc 0.5`,
    /// `-clscale 2`, ...), silent, its messages kept for errors. Waits
    /// while another session runs.
    pub(super) fn start(lib: &'static Lib, args: &[String]) -> R<Session> {
        let lock = GMSH.lock().unwrap_or_else(|p| p.into_inner());
        let owned: Vec<CString> =
            std::iter::once("subcontact").chain(args.iter().map(String::as_str)).map(c_string).collect();
        let mut argv: Vec<*mut c_char> = owned.iter().map(|s| s.as_ptr().cast_mut()).collect();
        let mut ierr: c_int = 0;
        // SAFETY: argv holds argc valid C strings that outlive the call.
        unsafe { (lib.gmshInitialize)(argv.len() as c_int, argv.as_mut_ptr(), 0, &mut ierr) };
        if ierr != 0 {
            return Err(ApiError { call: "gmshInitialize", errors: Vec::new() });
        }
        let s = Session { lib, _lock: lock };
        s.set_option("General.Terminal", 0.0)?;
        s.check("gmshLoggerStart", |e| unsafe { (lib.gmshLoggerStart)(e) })?;
        Ok(s)
    }

    /// Runs `f` with an error flag; Err with gmsh's logged errors when it is set.
    fn check<T>(&self, call: &'static str, f: impl FnOnce(*mut c_int) -> T) -> R<T> {
        let mut ierr: c_int = 0;
        let v = f(&mut ierr);
        if ierr == 0 {
            Ok(v)
        } else {
            Err(ApiError { call, errors: self.errors() })
        }
    }

    /// gmsh's `Error` lines since the session started (at most 15, repeats dropped).
    pub(super) fn errors(&self) -> Vec<String> {
        let lib = self.lib;
        let (mut p, mut n, mut ierr): (*mut *mut c_char, usize, c_int) = (std::ptr::null_mut(), 0, 0);
        // SAFETY: out-pointers to locals; the strings and the array are gmsh's to free.
        let lines: Vec<String> = unsafe {
            (lib.gmshLoggerGet)(&mut p, &mut n, &mut ierr);
            take(lib, p, n).into_iter().map(|s| take_str(lib, s)).collect()
        };
        let mut out: Vec<String> = Vec::new();
        for l in lines {
            if let Some(rest) = l.strip_prefix("Error") {
                let msg = rest.trim_start().trim_start_matches(':').trim().to_string();
                if !msg.is_empty() && !out.contains(&msg) {
                    out.push(msg);
                }
            }
        }
        out.truncate(15);
        out
    }

    pub(super) fn set_option(&self, name: &str, value: f64) -> R<()> {
        let (lib, n) = (self.lib, c_string(name));
        self.check("gmshOptionSetNumber", |e| unsafe { (lib.gmshOptionSetNumber)(n.as_ptr(), value, e) })
    }

    pub(super) fn option(&self, name: &str) -> R<f64> {
        let (lib, n, mut v) = (self.lib, c_string(name), 0.0);
        self.check("gmshOptionGetNumber", |e| unsafe { (lib.gmshOptionGetNumber)(n.as_ptr(), &mut v, e) })?;
        Ok(v)
    }

    /// Reads a `.geo` (or any file gmsh opens), as the CLI does.
    pub(super) fn open(&self, path: &Path) -> R<()> {
        let (lib, p) = (self.lib, c_string(&path.to_string_lossy()));
        self.check("gmshOpen", |e| unsafe { (lib.gmshOpen)(p.as_ptr(), e) })
    }

    /// Writes the mesh (format from the extension and the options).
    pub(super) fn write(&self, path: &Path) -> R<()> {
        let (lib, p) = (self.lib, c_string(&path.to_string_lossy()));
        self.check("gmshWrite", |e| unsafe { (lib.gmshWrite)(p.as_ptr(), e) })
    }

    /// The model's entities of dimension `dim` (-1: all).
    pub(super) fn entities(&self, dim: i32) -> R<Vec<DimTag>> {
        let (lib, mut p, mut n) = (self.lib, std::ptr::null_mut(), 0usize);
        self.check("gmshModelGetEntities", |e| unsafe { (lib.gmshModelGetEntities)(&mut p, &mut n, dim, e) })?;
        // SAFETY: gmsh allocated n ints at p.
        Ok(pairs(&unsafe { take(lib, p, n) }))
    }

    /// Every physical group with its entities.
    pub(super) fn physical_groups(&self) -> R<Vec<PhysicalGroup>> {
        let (lib, mut p, mut n) = (self.lib, std::ptr::null_mut(), 0usize);
        self.check("gmshModelGetPhysicalGroups", |e| unsafe {
            (lib.gmshModelGetPhysicalGroups)(&mut p, &mut n, -1, e)
        })?;
        // SAFETY: gmsh allocated n ints at p.
        let groups = pairs(&unsafe { take(lib, p, n) });
        let mut out = Vec::with_capacity(groups.len());
        for (d, t) in groups {
            let mut name: *mut c_char = std::ptr::null_mut();
            self.check("gmshModelGetPhysicalName", |e| unsafe { (lib.gmshModelGetPhysicalName)(d, t, &mut name, e) })?;
            // SAFETY: a gmsh-allocated string.
            let name = unsafe { take_str(lib, name) };
            let (mut q, mut m) = (std::ptr::null_mut(), 0usize);
            self.check("gmshModelGetEntitiesForPhysicalGroup", |e| unsafe {
                (lib.gmshModelGetEntitiesForPhysicalGroup)(d, t, &mut q, &mut m, e)
            })?;
            // SAFETY: gmsh allocated m ints at q.
            out.push(PhysicalGroup { dim: d, tag: t, name, tags: unsafe { take(lib, q, m) } });
        }
        Ok(out)
    }

    pub(super) fn remove_physical_groups(&self) -> R<()> {
        let lib = self.lib;
        self.check("gmshModelRemovePhysicalGroups", |e| unsafe {
            (lib.gmshModelRemovePhysicalGroups)(std::ptr::null_mut(), 0, e)
        })
    }

    /// Adds the physical group `name` of dimension `dim` over `tags`, with tag `tag` (-1: any).
    pub(super) fn add_physical_group(&self, dim: i32, tags: &[i32], tag: i32, name: &str) -> R<()> {
        let (lib, mut t, n) = (self.lib, tags.to_vec(), c_string(name));
        let g = self.check("gmshModelAddPhysicalGroup", |e| unsafe {
            (lib.gmshModelAddPhysicalGroup)(dim, t.as_mut_ptr(), t.len(), tag, e)
        })?;
        self.check("gmshModelSetPhysicalName", |e| unsafe { (lib.gmshModelSetPhysicalName)(dim, g, n.as_ptr(), e) })
    }

    /// The boundary of `dim_tags` (each entity's, not combined, unoriented).
    pub(super) fn boundary(&self, dim_tags: &[DimTag], recursive: bool) -> R<Vec<DimTag>> {
        let (lib, mut f) = (self.lib, flat(dim_tags));
        let (mut p, mut n) = (std::ptr::null_mut(), 0usize);
        self.check("gmshModelGetBoundary", |e| unsafe {
            (lib.gmshModelGetBoundary)(f.as_mut_ptr(), f.len(), &mut p, &mut n, 0, 0, c_int::from(recursive), e)
        })?;
        // SAFETY: gmsh allocated n ints at p.
        Ok(pairs(&unsafe { take(lib, p, n) }))
    }

    /// The entities of dimension dim + 1 that `(dim, tag)` bounds.
    pub(super) fn upward(&self, dim: i32, tag: i32) -> R<Vec<i32>> {
        let lib = self.lib;
        let (mut up, mut nu, mut down, mut nd) = (std::ptr::null_mut(), 0usize, std::ptr::null_mut(), 0usize);
        self.check("gmshModelGetAdjacencies", |e| unsafe {
            (lib.gmshModelGetAdjacencies)(dim, tag, &mut up, &mut nu, &mut down, &mut nd, e)
        })?;
        // SAFETY: gmsh allocated both arrays.
        let (up, _) = unsafe { (take(lib, up, nu), take(lib, down, nd)) };
        Ok(up)
    }

    /// The entities embedded in `(dim, tag)` for meshing.
    pub(super) fn embedded(&self, dim: i32, tag: i32) -> R<Vec<DimTag>> {
        let (lib, mut p, mut n) = (self.lib, std::ptr::null_mut(), 0usize);
        self.check("gmshModelMeshGetEmbedded", |e| unsafe {
            (lib.gmshModelMeshGetEmbedded)(dim, tag, &mut p, &mut n, e)
        })?;
        // SAFETY: gmsh allocated n ints at p.
        Ok(pairs(&unsafe { take(lib, p, n) }))
    }

    /// The coordinates of point `tag`.
    pub(super) fn point(&self, tag: i32) -> R<[f64; 3]> {
        let (lib, mut p, mut n) = (self.lib, std::ptr::null_mut(), 0usize);
        self.check("gmshModelGetValue", |e| unsafe {
            (lib.gmshModelGetValue)(0, tag, std::ptr::null_mut(), 0, &mut p, &mut n, e)
        })?;
        // SAFETY: gmsh allocated n doubles at p.
        let v = unsafe { take(lib, p, n) };
        Ok([v.first().copied().unwrap_or(0.0), v.get(1).copied().unwrap_or(0.0), v.get(2).copied().unwrap_or(0.0)])
    }

    pub(super) fn generate(&self, dim: i32) -> R<()> {
        let lib = self.lib;
        self.check("gmshModelMeshGenerate", |e| unsafe { (lib.gmshModelMeshGenerate)(dim, e) })
    }

    pub(super) fn clear_mesh(&self) -> R<()> {
        let lib = self.lib;
        self.check("gmshModelMeshClear", |e| unsafe { (lib.gmshModelMeshClear)(std::ptr::null_mut(), 0, e) })
    }

    /// Every mesh node: tags and coordinates.
    pub(super) fn nodes(&self) -> R<(Vec<usize>, Vec<[f64; 3]>)> {
        let lib = self.lib;
        let (mut t, mut nt, mut c, mut nc, mut u, mut nu) =
            (std::ptr::null_mut(), 0usize, std::ptr::null_mut(), 0usize, std::ptr::null_mut(), 0usize);
        self.check("gmshModelMeshGetNodes", |e| unsafe {
            (lib.gmshModelMeshGetNodes)(&mut t, &mut nt, &mut c, &mut nc, &mut u, &mut nu, -1, -1, 0, 0, e)
        })?;
        // SAFETY: gmsh allocated the three arrays.
        let (tags, xyz, _) = unsafe { (take(lib, t, nt), take(lib, c, nc), take(lib, u, nu)) };
        Ok((tags, xyz.chunks_exact(3).map(|x| [x[0], x[1], x[2]]).collect()))
    }

    /// The node tags of every element of gmsh type `kind` (1 line, 2 triangle), flat.
    pub(super) fn element_nodes(&self, kind: i32) -> R<Vec<usize>> {
        let lib = self.lib;
        let (mut t, mut nt, mut n, mut nn) = (std::ptr::null_mut(), 0usize, std::ptr::null_mut(), 0usize);
        self.check("gmshModelMeshGetElementsByType", |e| unsafe {
            (lib.gmshModelMeshGetElementsByType)(kind, &mut t, &mut nt, &mut n, &mut nn, -1, 0, 1, e)
        })?;
        // SAFETY: gmsh allocated both arrays.
        let (_, nodes) = unsafe { (take(lib, t, nt), take(lib, n, nn)) };
        Ok(nodes)
    }

    /// Moves node `tag` to `x` (its parametric place, if any, left as it was).
    pub(super) fn set_node(&self, tag: usize, x: [f64; 3]) -> R<()> {
        let (lib, mut c) = (self.lib, x);
        self.check("gmshModelMeshSetNode", |e| unsafe {
            (lib.gmshModelMeshSetNode)(tag, c.as_mut_ptr(), 3, std::ptr::null_mut(), 0, e)
        })
    }

    pub(super) fn set_size(&self, points: &[i32], size: f64) -> R<()> {
        let (lib, mut f) = (self.lib, flat(&points.iter().map(|&p| (0, p)).collect::<Vec<_>>()));
        self.check("gmshModelMeshSetSize", |e| unsafe { (lib.gmshModelMeshSetSize)(f.as_mut_ptr(), f.len(), size, e) })
    }

    /// Structured meshing wherever gmsh can: every four-sided surface and
    /// six-sided volume transfinite and recombined (quadrangles, hexahedra),
    /// the number of nodes from the sizes.
    pub(super) fn structured(&self) -> R<()> {
        let lib = self.lib;
        self.check("gmshModelMeshSetTransfiniteAutomatic", |e| unsafe {
            (lib.gmshModelMeshSetTransfiniteAutomatic)(std::ptr::null_mut(), 0, 2.35, 1, e)
        })
    }

    pub(super) fn add_point(&self, x: [f64; 3]) -> R<i32> {
        let lib = self.lib;
        self.check("gmshModelOccAddPoint", |e| unsafe { (lib.gmshModelOccAddPoint)(x[0], x[1], x[2], 0.0, -1, e) })
    }

    pub(super) fn add_line(&self, a: i32, b: i32) -> R<i32> {
        let lib = self.lib;
        self.check("gmshModelOccAddLine", |e| unsafe { (lib.gmshModelOccAddLine)(a, b, -1, e) })
    }

    /// A plane surface bounded by the closed polygon through `corners`.
    pub(super) fn add_polygon(&self, corners: &[[f64; 3]]) -> R<i32> {
        let lib = self.lib;
        let pts = corners.iter().map(|&x| self.add_point(x)).collect::<R<Vec<i32>>>()?;
        let mut lines =
            (0..pts.len()).map(|i| self.add_line(pts[i], pts[(i + 1) % pts.len()])).collect::<R<Vec<i32>>>()?;
        let mut wire = [self.check("gmshModelOccAddCurveLoop", |e| unsafe {
            (lib.gmshModelOccAddCurveLoop)(lines.as_mut_ptr(), lines.len(), -1, e)
        })?];
        self.check("gmshModelOccAddPlaneSurface", |e| unsafe {
            (lib.gmshModelOccAddPlaneSurface)(wire.as_mut_ptr(), 1, -1, e)
        })
    }

    /// A disc of radius r in the plane through `centre` with unit normal `n`.
    pub(super) fn add_disc(&self, centre: [f64; 3], r: f64, n: [f64; 3]) -> R<i32> {
        let lib = self.lib;
        let d =
            self.check("gmshModelOccAddDisk", |e| unsafe { (lib.gmshModelOccAddDisk)(0.0, 0.0, 0.0, r, r, -1, e) })?;
        let mut f = flat(&[(2, d)]);
        // turn +z onto n about z x n
        let (axis, s) = ([-n[1], n[0], 0.0], (n[0] * n[0] + n[1] * n[1]).sqrt());
        if s > 1e-12 {
            let angle = s.atan2(n[2]);
            self.check("gmshModelOccRotate", |e| unsafe {
                (lib.gmshModelOccRotate)(f.as_mut_ptr(), 2, 0.0, 0.0, 0.0, axis[0], axis[1], axis[2], angle, e)
            })?;
        }
        self.check("gmshModelOccTranslate", |e| unsafe {
            (lib.gmshModelOccTranslate)(f.as_mut_ptr(), 2, centre[0], centre[1], centre[2], e)
        })?;
        Ok(d)
    }

    /// A box from `lo` to `hi` (3D) or a rectangle in z = 0 (`dim` 2).
    pub(super) fn add_box(&self, dim: i32, lo: [f64; 3], hi: [f64; 3]) -> R<DimTag> {
        let lib = self.lib;
        let d = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
        if dim == 3 {
            let t = self.check("gmshModelOccAddBox", |e| unsafe {
                (lib.gmshModelOccAddBox)(lo[0], lo[1], lo[2], d[0], d[1], d[2], -1, e)
            })?;
            Ok((3, t))
        } else {
            let t = self.check("gmshModelOccAddRectangle", |e| unsafe {
                (lib.gmshModelOccAddRectangle)(lo[0], lo[1], 0.0, d[0], d[1], -1, 0.0, e)
            })?;
            Ok((2, t))
        }
    }

    /// OpenCASCADE's general fuse of `objects` with `tools` (both removed):
    /// every result, and for each input (objects, then tools) its pieces.
    pub(super) fn fragment(&self, objects: &[DimTag], tools: &[DimTag]) -> R<(Vec<DimTag>, Vec<Vec<DimTag>>)> {
        self.boolean("gmshModelOccFragment", objects, tools, true)
    }

    /// The parts of `objects` inside `tools` (objects removed, tools too if `remove_tool`).
    pub(super) fn intersect(&self, objects: &[DimTag], tools: &[DimTag], remove_tool: bool) -> R<Vec<DimTag>> {
        Ok(self.boolean("gmshModelOccIntersect", objects, tools, remove_tool)?.0)
    }

    fn boolean(
        &self,
        call: &'static str,
        objects: &[DimTag],
        tools: &[DimTag],
        remove_tool: bool,
    ) -> R<(Vec<DimTag>, Vec<Vec<DimTag>>)> {
        let lib = self.lib;
        let (mut o, mut t) = (flat(objects), flat(tools));
        let (mut out, mut nout) = (std::ptr::null_mut(), 0usize);
        let (mut map, mut map_n, mut map_nn): (*mut *mut c_int, *mut usize, usize) =
            (std::ptr::null_mut(), std::ptr::null_mut(), 0);
        let f = if call == "gmshModelOccFragment" { lib.gmshModelOccFragment } else { lib.gmshModelOccIntersect };
        self.check(call, |e| unsafe {
            f(
                o.as_mut_ptr(),
                o.len(),
                t.as_mut_ptr(),
                t.len(),
                &mut out,
                &mut nout,
                &mut map,
                &mut map_n,
                &mut map_nn,
                -1,
                1,
                c_int::from(remove_tool),
                e,
            )
        })?;
        // SAFETY: gmsh allocated `out`, the array of map_nn arrays and their lengths.
        unsafe {
            let out = pairs(&take(lib, out, nout));
            let lens = take(lib, map_n, map_nn);
            let rows = take(lib, map, map_nn);
            let map = rows.into_iter().zip(lens).map(|(p, n)| pairs(&take(lib, p, n))).collect();
            Ok((out, map))
        }
    }

    pub(super) fn remove(&self, dim_tags: &[DimTag], recursive: bool) -> R<()> {
        let (lib, mut f) = (self.lib, flat(dim_tags));
        self.check("gmshModelOccRemove", |e| unsafe {
            (lib.gmshModelOccRemove)(f.as_mut_ptr(), f.len(), c_int::from(recursive), e)
        })
    }

    pub(super) fn synchronize(&self) -> R<()> {
        let lib = self.lib;
        self.check("gmshModelOccSynchronize", |e| unsafe { (lib.gmshModelOccSynchronize)(e) })
    }

    /// OpenCASCADE's entities of dimension `dim` (empty for a built-in-kernel model).
    pub(super) fn occ_entities(&self, dim: i32) -> R<Vec<DimTag>> {
        let (lib, mut p, mut n) = (self.lib, std::ptr::null_mut(), 0usize);
        self.check("gmshModelOccGetEntities", |e| unsafe { (lib.gmshModelOccGetEntities)(&mut p, &mut n, dim, e) })?;
        // SAFETY: gmsh allocated n ints at p.
        Ok(pairs(&unsafe { take(lib, p, n) }))
    }

    /// The bounding box [xmin, ymin, zmin, xmax, ymax, zmax] of an entity.
    pub(super) fn bounding_box(&self, (dim, tag): DimTag) -> R<[f64; 6]> {
        let (lib, mut b) = (self.lib, [0.0; 6]);
        let [x0, y0, z0, x1, y1, z1] = &mut b;
        self.check("gmshModelOccGetBoundingBox", |e| unsafe {
            (lib.gmshModelOccGetBoundingBox)(dim, tag, x0, y0, z0, x1, y1, z1, e)
        })?;
        Ok(b)
    }

    /// Length, area or volume of an entity.
    pub(super) fn mass(&self, (dim, tag): DimTag) -> R<f64> {
        let (lib, mut m) = (self.lib, 0.0);
        self.check("gmshModelOccGetMass", |e| unsafe { (lib.gmshModelOccGetMass)(dim, tag, &mut m, e) })?;
        Ok(m)
    }

    pub(super) fn centre(&self, (dim, tag): DimTag) -> R<[f64; 3]> {
        let (lib, mut c) = (self.lib, [0.0; 3]);
        let [x, y, z] = &mut c;
        self.check("gmshModelOccGetCenterOfMass", |e| unsafe {
            (lib.gmshModelOccGetCenterOfMass)(dim, tag, x, y, z, e)
        })?;
        Ok(c)
    }
}

impl Drop for Session {
    fn drop(&mut self) {
        let (lib, mut ierr) = (self.lib, 0);
        // SAFETY: the session initialised gmsh; errors here change nothing.
        unsafe {
            (lib.gmshLoggerStop)(&mut ierr);
            (lib.gmshFinalize)(&mut ierr);
        }
    }
}
