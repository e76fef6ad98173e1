//! The checker of a raw scene: the scene file every error names, the
//! errors it makes, and the checks of single values (required, finite,
//! non-negative, bounded, vectors) that every table's checks use.

use std::fmt;
use std::path::Path;

use crate::fem::Analysis;
use crate::scene::errors::SceneError;

/// A list of names for messages: `"a", "b"`.
pub(super) fn quoted_list<S: AsRef<str>>(items: impl IntoIterator<Item = S>) -> String {
    items.into_iter().map(|s| format!("\"{}\"", s.as_ref())).collect::<Vec<_>>().join(", ")
}

/// A vector as the messages show it: `[1, 2, 0]`.
pub(super) fn fmt_vec(v: &[f64]) -> String {
    format!("[{}]", v.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(", "))
}

/// Checks a raw scene against the rules of each key; `path` is the scene
/// file every error names.
pub(in crate::scene) struct Checker<'a> {
    pub(in crate::scene) path: &'a Path,
}

/// What a check returns.
pub(super) type R<T> = Result<T, SceneError>;

impl Checker<'_> {
    /// An error about `key` whose value is `value` (already formatted).
    pub(super) fn bad(&self, key: impl Into<String>, value: impl fmt::Display, what: impl fmt::Display) -> SceneError {
        SceneError::Invalid {
            path: self.path.to_path_buf(),
            key: key.into(),
            value: Some(value.to_string()),
            message: what.to_string(),
        }
    }

    /// An error about `key` without a value (missing, or about a whole table).
    pub(super) fn err(&self, key: impl Into<String>, what: impl fmt::Display) -> SceneError {
        SceneError::Invalid { path: self.path.to_path_buf(), key: key.into(), value: None, message: what.to_string() }
    }

    pub(super) fn required<T>(&self, v: Option<T>, key: &str, what: &str) -> R<T> {
        v.ok_or_else(|| self.err(key, format!("missing; add `{}` ({what}).", key.rsplit('.').next().unwrap_or(key))))
    }

    pub(super) fn group(&self, v: Option<String>, key: &str, what: &str) -> R<String> {
        let g = self.required(v, key, what)?;
        if g.trim().is_empty() {
            return Err(self.bad(
                key,
                "\"\"",
                format!("the group name is empty; give the name of {what} as written in the .geo."),
            ));
        }
        Ok(g)
    }

    pub(super) fn finite(&self, v: f64, key: &str) -> R<f64> {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.bad(key, v, "must be a finite number."))
        }
    }

    pub(super) fn non_negative(&self, v: Option<f64>, key: &str, what: &str) -> R<f64> {
        let v = self.finite(v.unwrap_or(0.0), key)?;
        if v < 0.0 {
            return Err(self.bad(key, v, format!("{what} must be >= 0 (0 if omitted).")));
        }
        Ok(v)
    }

    /// `n`, unless it is above `max`: then an error naming `key`.
    pub(super) fn at_most(&self, n: usize, max: usize, key: &str, what: &str) -> R<usize> {
        if n > max {
            return Err(self.bad(key, n, format!("at most {max} {what}.")));
        }
        Ok(n)
    }

    pub(super) fn at_least(&self, v: Option<i64>, default: usize, min: i64, key: &str, what: &str) -> R<usize> {
        match v {
            None => Ok(default),
            Some(n) if n >= min => usize::try_from(n).map_err(|_| self.bad(key, n, format!("{what} is too large."))),
            Some(n) => Err(self.bad(key, n, format!("{what} must be at least {min}."))),
        }
    }

    /// A 2- or 3-component vector; 3 required for solid, z = 0 for the 2D analyses.
    pub(super) fn vec3(&self, v: &[f64], key: &str, analysis: Analysis) -> R<[f64; 3]> {
        let shown = fmt_vec(v);
        if analysis == Analysis::Solid && v.len() != 3 {
            return Err(self.bad(key, shown, "a solid analysis needs 3 components [x, y, z]."));
        }
        if v.len() != 2 && v.len() != 3 {
            return Err(self.bad(
                key,
                shown,
                format!("give 2 components [x, y] (or 3 with z = 0) for a {analysis} analysis."),
            ));
        }
        if v.iter().any(|x| !x.is_finite()) {
            return Err(self.bad(key, shown, "all components must be finite numbers."));
        }
        let z = v.get(2).copied().unwrap_or(0.0);
        if analysis.dim() == 2 && z != 0.0 {
            return Err(self.bad(
                key,
                shown,
                format!("a {analysis} analysis lies in the z = 0 plane, so the z component must be 0; drop it or use analysis = \"solid\"."),
            ));
        }
        Ok([v[0], v[1], z])
    }
}
