//! The manifest of a result directory, `.subcontact-manifest.json`: which
//! files each writer (a scene's name, or `bench`) put there, and which run
//! committed last. A commit removes only what the manifest says its own
//! writer wrote before; anything else in the directory (a user's notes,
//! another scene's results, the mesh cache) is carried into the new set.
//!
//! ```json
//! { "format": 1, "last": { "run": "4711-1764000000123456789", "writer": "cylinder" },
//!   "writers": { "cylinder": ["cylinder.vtu", "contact.csv", "..."], "bench": ["bench.csv"] } }
//! ```
//!
//! A writer's files are names in the directory, and its mesh cache
//! `mesh/<writer>.msh` and `mesh/<writer>.msh.key`, which a commit takes
//! along like its results. A missing or unreadable manifest is an empty
//! one: files it does not list are never removed.

use std::collections::BTreeMap;
use std::path::Path;

/// The manifest's file name inside the result directory.
pub const MANIFEST: &str = ".subcontact-manifest.json";

/// What each writer put into a result directory.
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    pub format: u32,
    pub last: Option<Last>,
    pub writers: BTreeMap<String, Vec<String>>,
}

/// The run that committed last, and for whom.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Last {
    pub run: String,
    pub writer: String,
}

impl Manifest {
    /// The manifest in `dir` (empty when there is none or it cannot be read).
    pub fn read(dir: &Path) -> Manifest {
        std::fs::read(dir.join(MANIFEST)).ok().and_then(|b| serde_json::from_slice(&b).ok()).unwrap_or_default()
    }

    /// The manifest in the directory opened as `dir` (not following a link).
    pub(super) fn read_at(dir: &super::at::Dir) -> Manifest {
        let mut bytes = Vec::new();
        let read = dir
            .read_file(std::ffi::OsStr::new(MANIFEST))
            .and_then(|mut f| std::io::Read::read_to_end(&mut f, &mut bytes));
        read.ok().and_then(|_| serde_json::from_slice(&bytes).ok()).unwrap_or_default()
    }

    /// The files `writer` wrote.
    pub fn files(&self, writer: &str) -> &[String] {
        self.writers.get(writer).map_or(&[], |v| v.as_slice())
    }

    /// This manifest after run `run` of `writer` wrote `files`: they are
    /// its files now, and no longer another writer's (they were replaced).
    /// With `keep`, the writer's earlier files not written again stay its own.
    pub fn after(&self, run: &str, writer: &str, files: &[String], keep: bool) -> Manifest {
        let mut writers = self.writers.clone();
        for list in writers.values_mut() {
            list.retain(|f| !files.contains(f));
        }
        let mut mine: Vec<String> = if keep { writers.get(writer).cloned().unwrap_or_default() } else { Vec::new() };
        mine.extend(files.iter().cloned());
        writers.insert(writer.to_string(), mine);
        writers.retain(|_, v| !v.is_empty());
        Manifest { format: 1, last: Some(Last { run: run.to_string(), writer: writer.to_string() }), writers }
    }

    pub fn bytes(&self) -> Vec<u8> {
        let mut b = serde_json::to_vec_pretty(self).unwrap_or_default();
        b.push(b'\n');
        b
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(v: &[&str]) -> Vec<String> {
        v.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn a_writer_takes_over_the_files_it_writes_and_drops_its_others() {
        let m = Manifest::default().after("1", "a", &names(&["a.vtu", "contact.csv"]), false);
        let m = m.after("2", "b", &names(&["b.vtu", "contact.csv"]), false);
        assert_eq!(m.files("a"), names(&["a.vtu"]));
        assert_eq!(m.files("b"), names(&["b.vtu", "contact.csv"]));
        let m = m.after("3", "a", &names(&["a2.vtu"]), false);
        assert_eq!(m.files("a"), names(&["a2.vtu"]));
        let m = m.after("4", "a", &names(&["report.md"]), true);
        assert_eq!(m.files("a"), names(&["a2.vtu", "report.md"]));
        assert_eq!(m.last, Some(Last { run: "4".into(), writer: "a".into() }));
        let back: Manifest = serde_json::from_slice(&m.bytes()).unwrap();
        assert_eq!(back, m);
    }
}
