//! The cursor over an MSH file's bytes: how one value of the format is read,
//! in either encoding. ASCII values are whitespace-delimited words; binary
//! values are fixed-width (`int` 4 bytes, `double` 8, `size_t` 4 or 8 as the
//! header says) in the byte order the header's integer 1 gives. The section
//! readers ([`super::sections`]) ask for a `size_t`, an `int` or a `double`
//! and never see which encoding the file uses, so ASCII and binary files go
//! through the same code and read the same.
//!
//! Every failure is an [`MshError::Malformed`] that says what was expected,
//! in which section and at which byte; reading past the end is such a failure,
//! never a panic.

use std::path::Path;

use super::msh_error::MshError;

/// A cursor over the file's bytes that reads the MSH value types in ASCII or
/// binary form.
pub(super) struct Reader<'a> {
    pub(super) path: &'a Path,
    pub(super) buf: &'a [u8],
    pub(super) pos: usize,
    pub(super) binary: bool,
    pub(super) size_t: usize,
    pub(super) little: bool,
    pub(super) section: &'static str,
}

impl<'a> Reader<'a> {
    /// A cursor at the start of `buf`, ASCII until the header says otherwise.
    pub(super) fn new(path: &'a Path, buf: &'a [u8]) -> Self {
        Reader { path, buf, pos: 0, binary: false, size_t: 8, little: true, section: "" }
    }

    pub(super) fn malformed(&self, what: impl std::fmt::Display) -> MshError {
        let place = if self.section.is_empty() {
            format!("at byte {}", self.pos)
        } else {
            format!("in section ${} at byte {}", self.section, self.pos)
        };
        let end = if self.pos >= self.buf.len() { " (end of file)" } else { "" };
        MshError::Malformed { path: self.path.to_path_buf(), detail: format!("{what} {place}{end}") }
    }

    pub(super) fn at_end(&self) -> bool {
        self.pos >= self.buf.len()
    }

    pub(super) fn remaining(&self) -> usize {
        self.buf.len().saturating_sub(self.pos)
    }

    pub(super) fn skip_ws(&mut self) {
        while self.pos < self.buf.len() && self.buf[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
    }

    /// The next whitespace-delimited word (ASCII mode), after skipping whitespace.
    pub(super) fn word(&mut self) -> Option<&'a [u8]> {
        self.skip_ws();
        let start = self.pos;
        while self.pos < self.buf.len() && !self.buf[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        if self.pos > start {
            Some(&self.buf[start..self.pos])
        } else {
            None
        }
    }

    /// The rest of the current line without its end (`\n` or `\r\n`), consuming the end.
    pub(super) fn line(&mut self) -> &'a [u8] {
        let start = self.pos;
        while self.pos < self.buf.len() && self.buf[self.pos] != b'\n' {
            self.pos += 1;
        }
        let mut line = &self.buf[start..self.pos];
        if self.pos < self.buf.len() {
            self.pos += 1;
        }
        if let Some((&b'\r', rest)) = line.split_last() {
            line = rest;
        }
        line
    }

    pub(super) fn bytes(&mut self, n: usize, what: &str) -> Result<&'a [u8], MshError> {
        if self.remaining() < n {
            return Err(self.malformed(format!("expected {what}")));
        }
        let b = &self.buf[self.pos..self.pos + n];
        self.pos += n;
        Ok(b)
    }

    pub(super) fn parse_word<T: std::str::FromStr>(&mut self, what: &str) -> Result<T, MshError> {
        let before = self.pos;
        match self.word() {
            None => Err(self.malformed(format!("expected {what}"))),
            Some(w) => match std::str::from_utf8(w).ok().and_then(|s| s.parse::<T>().ok()) {
                Some(v) => Ok(v),
                None => {
                    self.pos = before;
                    self.skip_ws();
                    let shown: String = String::from_utf8_lossy(&w[..w.len().min(40)]).into();
                    Err(self.malformed(format!("expected {what}, found `{shown}`")))
                }
            },
        }
    }

    /// An MSH `size_t` value.
    pub(super) fn size_t(&mut self, what: &str) -> Result<u64, MshError> {
        if !self.binary {
            return self.parse_word(what);
        }
        let b = self.bytes(self.size_t, what)?;
        Ok(if self.size_t == 4 {
            let a = [b[0], b[1], b[2], b[3]];
            u64::from(if self.little { u32::from_le_bytes(a) } else { u32::from_be_bytes(a) })
        } else {
            let a = [b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]];
            if self.little {
                u64::from_le_bytes(a)
            } else {
                u64::from_be_bytes(a)
            }
        })
    }

    /// A `size_t` count, as usize.
    pub(super) fn count(&mut self, what: &str) -> Result<usize, MshError> {
        let v = self.size_t(what)?;
        usize::try_from(v).map_err(|_| self.malformed(format!("{what} {v} is too large")))
    }

    /// An MSH `int` (4 bytes in binary files).
    pub(super) fn int(&mut self, what: &str) -> Result<i32, MshError> {
        if !self.binary {
            return self.parse_word(what);
        }
        let b = self.bytes(4, what)?;
        let a = [b[0], b[1], b[2], b[3]];
        Ok(if self.little { i32::from_le_bytes(a) } else { i32::from_be_bytes(a) })
    }

    /// An MSH `double`.
    pub(super) fn double(&mut self, what: &str) -> Result<f64, MshError> {
        if !self.binary {
            return self.parse_word(what);
        }
        let b = self.bytes(8, what)?;
        let a = [b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]];
        Ok(if self.little { f64::from_le_bytes(a) } else { f64::from_be_bytes(a) })
    }

    /// A capacity for `count` items of at least `min_bytes` bytes each that the
    /// rest of the file can actually hold.
    pub(super) fn capacity(&self, count: usize, min_bytes: usize) -> usize {
        count.min(self.remaining() / min_bytes.max(1))
    }

    /// Smallest size of one value in the file (a digit and a separator in ASCII).
    pub(super) fn min_value_bytes(&self, binary_size: usize) -> usize {
        if self.binary {
            binary_size
        } else {
            2
        }
    }

    /// Consumes a section's end marker `$End<name>` (after whitespace).
    pub(super) fn end_section(&mut self, name: &str) -> Result<(), MshError> {
        self.skip_ws();
        let marker = format!("$End{name}");
        let line = self.line();
        if line.trim_ascii_end() != marker.as_bytes() {
            return Err(self.malformed(format!("expected `{marker}`")));
        }
        Ok(())
    }
}
