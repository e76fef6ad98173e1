//! Small algebra of 3-vectors (`[f64; 3]`, global or local axes): what the
//! element kernels, the model's contacts, the contact frames and rules and
//! the pictures share. Plane analyses use the same arrays with a zero third
//! component. And, for vectors of any size, which the contact iteration's
//! solvers share: the length, and the power of two to scale one by.

pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// The Euclidean length (see [`length`]).
pub fn norm(a: [f64; 3]) -> f64 {
    length(&a)
}

/// The Euclidean length of any vector, also where the squares of its
/// entries would overflow or underflow (entries near 1e±154 and beyond, as
/// in a scene whose moduli or loads are in units that make them so): there
/// computed on `v` scaled by its largest entry, elsewhere `sqrt(v . v)` to
/// the last bit.
pub fn length(v: &[f64]) -> f64 {
    let squares: f64 = v.iter().map(|x| x * x).sum();
    if squares.is_nan() || (squares.is_finite() && squares >= f64::MIN_POSITIVE / f64::EPSILON) {
        return squares.sqrt();
    }
    let big = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if big == 0.0 || !big.is_finite() {
        return big;
    }
    big * v.iter().map(|x| (x / big) * (x / big)).sum::<f64>().sqrt()
}

/// The power of two that brings the largest entry of `v` nearest to 1 (1
/// for a zero or non-finite `v`): scaling by it is exact, so a computation
/// on the scaled values is the one on `v` to the last bit, without its
/// squares leaving double precision.
pub fn to_one(v: &[f64]) -> f64 {
    match v.iter().fold(0.0f64, |m, x| m.max(x.abs())) {
        big if big > 0.0 && big.is_finite() => 2f64.powi((-big.log2().round()).clamp(-1000.0, 1000.0) as i32),
        _ => 1.0,
    }
}

/// `a` scaled to length 1 (`a` itself when it is zero).
pub fn normalized(a: [f64; 3]) -> [f64; 3] {
    let l = norm(a);
    if l > 0.0 {
        a.map(|x| x / l)
    } else {
        a
    }
}

/// The unit vector along axis `c`.
pub fn unit(c: usize) -> [f64; 3] {
    let mut e = [0.0; 3];
    e[c] = 1.0;
    e
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn length_is_sqrt_of_the_squares_to_the_last_bit_and_beyond_their_range() {
        let v = [0.3, -1.7, 2.9];
        assert_eq!(norm(v), dot(v, v).sqrt());
        for s in [1e-200, 1e200, 1e-300, 1e300] {
            let l = norm([3.0 * s, 0.0, -4.0 * s]);
            assert!((l / (5.0 * s) - 1.0).abs() < 1e-15, "{s:e}: {l:e}");
        }
        assert!(length(&[f64::NAN, 1.0]).is_nan() && length(&[f64::NAN; 3]).is_nan());
        assert_eq!(length(&[f64::INFINITY, 1.0]), f64::INFINITY);
        assert_eq!(length(&[0.0; 4]), 0.0);
    }
}
