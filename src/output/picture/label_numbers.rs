//! Numbers as the pictures print them on scales, titles and labels.

/// A number with four significant digits, scientific outside [1e-3, 1e5).
pub(super) fn num(v: f64) -> String {
    if !v.is_finite() {
        return "n/a".into();
    }
    let a = v.abs();
    if a == 0.0 {
        return "0".into();
    }
    if (1e-3..1e5).contains(&a) {
        let decimals = (3 - a.log10().floor() as i32).clamp(0, 6) as usize;
        let s = format!("{v:.decimals$}");
        if s.contains('.') {
            return s.trim_end_matches('0').trim_end_matches('.').to_string();
        }
        return s;
    }
    format!("{v:.2e}")
}

/// A magnification with two significant digits.
pub(super) fn sig2(v: f64) -> String {
    if (1.0..1e4).contains(&v) {
        // 9.6, not 96 × 0.1 = 9.600000000000001
        return crate::output::number::sig(v, 2);
    }
    if (0.01..1.0).contains(&v) {
        return num((v * 100.0).round() / 100.0);
    }
    format!("{v:.1e}")
}
