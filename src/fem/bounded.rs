//! Eigen- and singular value decompositions of bounded work.
//!
//! nalgebra's `svd`, `symmetric_eigen` and `Schur` iterate until they
//! converge (`max_niter = 0`: no bound). On a matrix with a NaN or an
//! infinity its SVD never ends (nalgebra 0.33.3: a 6 x 6 symmetric matrix
//! with one NaN entry pair, still running after 10 s; the unit test
//! below), and its Schur form loops for ever on some finite matrices
//! (nalgebra issues #611, #764, #1528: a safety search on a 3D rock slope
//! hung 20 minutes in one, docs/corpus.md). Each decomposition here is
//! given [`SWEEPS_PER_VALUE`] sweeps per value, refuses a matrix that is
//! not finite, and is None where it did not converge: the caller says what
//! stands in for it.

use nalgebra::allocator::Allocator;
use nalgebra::{
    Complex, DMatrix, DefaultAllocator, Dim, DimDiff, DimSub, Dyn, OMatrix, Schur, SymmetricEigen, SVD, U1,
};

/// QR sweeps per eigen- or singular value. LAPACK's dhseqr gives 30.
pub const SWEEPS_PER_VALUE: usize = 30;

/// The SVD of `m` (with U and V^T as asked), None where `m` is not finite
/// or the iteration did not converge.
pub fn svd(m: DMatrix<f64>, u: bool, v_t: bool) -> Option<SVD<f64, Dyn, Dyn>> {
    let sweeps = SWEEPS_PER_VALUE * m.nrows().min(m.ncols()).max(1);
    // (nalgebra's own `svd` stops at 5 epsilon)
    finite(m.as_slice()).then(|| SVD::try_new(m, u, v_t, 5.0 * f64::EPSILON, sweeps)).flatten()
}

/// The eigen-decomposition of the symmetric `m` (its lower triangle),
/// None where `m` is not finite or the iteration did not converge.
pub fn symmetric_eigen<D>(m: OMatrix<f64, D, D>) -> Option<SymmetricEigen<f64, D>>
where
    D: Dim + DimSub<U1>,
    DefaultAllocator: Allocator<D, D> + Allocator<DimDiff<D, U1>> + Allocator<D>,
{
    let sweeps = SWEEPS_PER_VALUE * m.nrows().max(1);
    finite(m.as_slice()).then(|| SymmetricEigen::try_new(m, f64::EPSILON, sweeps)).flatten()
}

/// The largest modulus of the eigenvalues of the square `m`, by a Schur
/// decomposition; None where `m` is not finite or it did not converge.
pub fn largest_eigenvalue(m: &DMatrix<f64>) -> Option<f64> {
    Some(eigenvalues(m)?.iter().map(|z| z.norm()).fold(0.0, f64::max))
}

/// The eigenvalues of the square `m`, by a Schur decomposition (none of
/// an empty one); None where `m` is not finite or it did not converge.
pub fn eigenvalues(m: &DMatrix<f64>) -> Option<Vec<Complex<f64>>> {
    if m.is_empty() {
        return Some(Vec::new());
    }
    let sweeps = SWEEPS_PER_VALUE * m.nrows();
    let schur = finite(m.as_slice()).then(|| Schur::try_new(m.clone(), f64::EPSILON, sweeps)).flatten()?;
    Some(schur.complex_eigenvalues().iter().copied().collect())
}

fn finite(values: &[f64]) -> bool {
    values.iter().all(|v| v.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs `f` in a thread and waits at most 20 s for it.
    fn ends<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let _ = tx.send(f());
        });
        rx.recv_timeout(std::time::Duration::from_secs(20)).expect("the decomposition ends")
    }

    /// A symmetric 6 x 6 matrix with one entry pair `x`.
    fn with(x: f64) -> DMatrix<f64> {
        let mut m = DMatrix::from_fn(6, 6, |i, j| ((i * 7 + j * 3) % 5 + (j * 7 + i * 3) % 5) as f64 / 2.0);
        m += DMatrix::identity(6, 6) * 8.0;
        m[(2, 3)] = x;
        m[(3, 2)] = x;
        m
    }

    #[test]
    fn a_matrix_that_is_not_finite_has_no_decomposition_and_ends() {
        for x in [f64::NAN, f64::INFINITY] {
            assert!(ends(move || svd(with(x), true, true).is_none()), "svd of {x}");
            assert!(ends(move || symmetric_eigen(with(x)).is_none()), "eigen of {x}");
            assert!(ends(move || largest_eigenvalue(&with(x)).is_none()), "schur of {x}");
        }
    }

    #[test]
    fn a_finite_matrix_decomposes_as_nalgebra_does() {
        let m = with(1.5);
        let s = svd(m.clone(), true, true).expect("svd");
        let (u, v_t) = (s.u.clone().expect("U"), s.v_t.clone().expect("V^T"));
        let back = &u * DMatrix::from_diagonal(&s.singular_values) * &v_t;
        assert!((back - &m).amax() < 1e-12 * m.amax());
        // to the bit: the same iteration, stopped where nalgebra's stops
        let theirs = m.clone().svd(true, true);
        assert_eq!(s.singular_values, theirs.singular_values);
        assert_eq!(s.u, theirs.u);
        let e = symmetric_eigen(m.clone()).expect("eigen");
        let mut ours: Vec<f64> = e.eigenvalues.iter().copied().collect();
        let mut theirs: Vec<f64> = m.clone().symmetric_eigen().eigenvalues.iter().copied().collect();
        ours.sort_by(f64::total_cmp);
        theirs.sort_by(f64::total_cmp);
        assert_eq!(ours, theirs, "to the bit");
        let top = largest_eigenvalue(&m).expect("schur");
        assert!((top - theirs[5].abs().max(theirs[0].abs())).abs() < 1e-10 * top);
        // a fixed-size matrix too
        let small = nalgebra::Matrix3::new(2.0, 1.0, 0.0, 1.0, 2.0, 0.0, 0.0, 0.0, 1.0);
        assert!(symmetric_eigen(small).is_some());
    }
}
