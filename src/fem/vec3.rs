//! Small algebra of 3-vectors (`[f64; 3]`, global or local axes): what the
//! element kernels, the model's contacts, the contact frames and rules and
//! the pictures share. Plane analyses use the same arrays with a zero third
//! component.

pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// The Euclidean length.
pub fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
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
