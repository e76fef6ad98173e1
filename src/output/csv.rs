//! CSV fields as RFC 4180 writes them, for every CSV file the tool writes.

/// A CSV field (RFC 4180): quoted when it holds a comma, a quote or a
/// line break, or starts or ends with a space.
pub(crate) fn csv_field(v: &str) -> String {
    if v.contains([',', '"', '\n', '\r']) || v.starts_with(' ') || v.ends_with(' ') {
        format!("\"{}\"", v.replace('"', "\"\""))
    } else {
        v.to_string()
    }
}
