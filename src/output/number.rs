//! Numbers as people read them in tables, titles and legends: a few
//! significant digits, no float noise (`9.6`, not `9.600000000000001`), no
//! trailing zeros, and powers of ten only for the very large and small.

/// `v` with `digits` significant digits: plain in [1e-3, 1e6), else
/// scientific (`1.2e-5`, `3.4e7`); "0" for zero, "n/a" when not finite.
pub fn sig(v: f64, digits: usize) -> String {
    if !v.is_finite() {
        return "n/a".into();
    }
    let digits = digits.max(1);
    let a = v.abs();
    if a == 0.0 {
        return "0".into();
    }
    // the power of ten after rounding to the digits (9.9996 -> 10.00)
    let rounded: f64 = format!("{v:.*e}", digits - 1).parse().unwrap_or(v);
    let exp = rounded.abs().log10().floor() as i32;
    if (-3..6).contains(&exp) {
        let decimals = (digits as i32 - 1 - exp).max(0) as usize;
        return trim(format!("{rounded:.decimals$}"));
    }
    let s = format!("{v:.*e}", digits - 1);
    match s.split_once('e') {
        Some((m, e)) => format!("{}e{e}", trim(m.to_string())),
        None => s,
    }
}

/// Four significant digits: the tables' default.
pub fn num(v: f64) -> String {
    sig(v, 4)
}

/// `v`, or 0 where it is round-off beside `scale` (below 1e-10 of it).
pub fn clean(v: f64, scale: f64) -> f64 {
    if v.abs() <= 1e-10 * scale.abs() {
        0.0
    } else {
        v
    }
}

/// Drops trailing zeros after a decimal point, and the point itself.
fn trim(s: String) -> String {
    if !s.contains('.') {
        return if s == "-0" { "0".into() } else { s };
    }
    let t = s.trim_end_matches('0').trim_end_matches('.');
    if t == "-0" {
        "0".into()
    } else {
        t.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_as_written() {
        assert_eq!(sig(9.600000000000001, 2), "9.6");
        assert_eq!(sig(96.0 * 0.1, 2), "9.6");
        assert_eq!(sig(1234.5678, 4), "1235");
        assert_eq!(sig(0.012345, 3), "0.0123");
        assert_eq!(sig(-2.5, 4), "-2.5");
        assert_eq!(sig(9.9996, 4), "10");
        assert_eq!(sig(123456.0, 3), "123000");
        assert_eq!(sig(2.337e6, 4), "2.337e6");
        assert_eq!(sig(-1.5e-5, 2), "-1.5e-5");
        assert_eq!(sig(0.0, 3), "0");
        assert_eq!(sig(-0.00001, 1), "-1e-5");
        assert_eq!(sig(f64::NAN, 3), "n/a");
        assert_eq!(num(597.04), "597");
        assert_eq!(num(0.7355), "0.7355");
    }
}
