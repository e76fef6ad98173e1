//! Why a scene could not be used ([`SceneError`]), and toml's errors turned
//! into one: one paragraph with the scene file, line, column, the enclosing
//! table as a key path (`contacts[1]`) and a hint on what to do.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Why a scene could not be used. `Display` is one paragraph that starts with
/// the scene file's path.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file could not be read.
    #[error("{}: cannot read the scene file: {source}. Check the path and that the file is readable.", path.display())]
    Read {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// TOML syntax, an unknown key, or a value of the wrong type.
    #[error("{}, line {line}, column {column}{}: {message}", path.display(), table.as_ref().map(|t| format!(" (in {t})")).unwrap_or_default())]
    Toml {
        path: PathBuf,
        line: usize,
        column: usize,
        /// The table the error is in, as a key path (`contacts[1]`), if any.
        table: Option<String>,
        message: String,
    },
    /// A value that parses but is not acceptable.
    #[error("{}: {key}{}: {message}", path.display(), value.as_ref().map(|v| format!(" = {v}")).unwrap_or_default())]
    Invalid {
        path: PathBuf,
        /// Key path, e.g. `materials.rock.nu`.
        key: String,
        /// The offending value as written in TOML, when there is one.
        value: Option<String>,
        /// What is wrong and what to do.
        message: String,
    },
}

impl SceneError {
    /// The key path the error is about, when known.
    pub fn key(&self) -> Option<&str> {
        match self {
            SceneError::Read { .. } => None,
            SceneError::Toml { table, .. } => table.as_deref(),
            SceneError::Invalid { key, .. } => Some(key),
        }
    }
}

/// Turn a toml error into one paragraph with line, column, the enclosing
/// table and a hint on what to do.
pub(super) fn toml_error(text: &str, path: &Path, e: &toml::de::Error) -> SceneError {
    let offset = e.span().map(|s| s.start).unwrap_or(0).min(text.len());
    let before = text.get(..offset).unwrap_or("");
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map(|i| i + 1).unwrap_or(0);
    let column = before[line_start..].chars().count() + 1;
    let line_text = text[line_start..].lines().next().unwrap_or("").trim();

    let msg = e.message().trim().replace('\n', "; ");
    let hint = if msg.starts_with("unknown field") {
        "Unknown keys are errors, not ignored: correct the spelling to one of the expected keys, or remove the line."
    } else if msg.starts_with("unknown variant") {
        "Use one of the listed values."
    } else if msg.starts_with("invalid type") {
        "Give the value the type shown (numbers unquoted, names in quotes, lists in [ ])."
    } else {
        "Fix the TOML syntax at that position."
    };
    let shown = if !line_text.is_empty() && line_text.chars().count() <= 80 {
        format!("`{line_text}`: ")
    } else {
        String::new()
    };
    SceneError::Toml {
        path: path.to_path_buf(),
        line,
        column,
        table: enclosing_table(text, line_start),
        message: format!("{shown}{msg}. {hint}"),
    }
}

/// The key path of the `[table]` or `[[array]]` header that governs the line
/// starting at `line_start` (`contacts[1]`, `materials.rock`), if any.
fn enclosing_table(text: &str, line_start: usize) -> Option<String> {
    let upto = text.get(..line_start + text[line_start..].find('\n').unwrap_or(text.len() - line_start))?;
    let mut current: Option<String> = None;
    let mut counts: BTreeMap<String, usize> = BTreeMap::new();
    for l in upto.lines() {
        let l = l.split('#').next().unwrap_or("").trim();
        let (name, array) = if let Some(inner) = l.strip_prefix("[[").and_then(|s| s.strip_suffix("]]")) {
            (inner.trim(), true)
        } else if let Some(inner) = l.strip_prefix('[').and_then(|s| s.strip_suffix(']')) {
            (inner.trim(), false)
        } else {
            continue;
        };
        // Skip continuation lines of multi-line arrays like `[1.0, 2.0]`.
        let first = name.chars().next();
        if !matches!(first, Some(c) if c.is_ascii_alphabetic() || c == '_' || c == '"' || c == '\'') {
            continue;
        }
        let name: String = name.split('.').map(|p| p.trim()).collect::<Vec<_>>().join(".");
        current = Some(if array {
            let n = counts.entry(name.clone()).or_insert(0);
            *n += 1;
            format!("{name}[{}]", *n - 1)
        } else {
            name
        });
    }
    current
}
