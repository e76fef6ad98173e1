//! Slivers merged into a neighbour (top-level `merge_slivers = true`): a
//! block thinner than a tenth of the mesh size there (the sliver `check`
//! warns of, [`super::BlockReport::is_sliver`]) keeps its place in the
//! mesh, but the largest joint face it shares with another block leaves
//! the joint's contact group. Across that face the sliver is bonded to its
//! neighbour (the mesh is conformal there) and moves with it as one block,
//! so no contact pairs hang on a few flat elements between the two; its
//! other joint faces stay contacts. The faces come from what
//! `occ.fragment` returned: the joint pieces ([`super::cut`]'s `kept`).

use std::collections::HashMap;

use super::api::{ApiError, DimTag, Session};
use super::sizes::Sizes;

/// Thickness of a block: 6 V / A in 3D, 4 A / P in 2D (a cube's edge, a
/// square's side), as the report gives it.
pub(super) fn thickness(s: &Session, dim: i32, block: DimTag) -> Result<f64, ApiError> {
    let volume = s.mass(block)?;
    let mut area = 0.0;
    for f in s.boundary(&[block], false)? {
        area += s.mass(f)?;
    }
    let factor = if dim == 3 { 6.0 } else { 4.0 };
    Ok(factor * volume / area.max(f64::MIN_POSITIVE))
}

/// Takes out of `faces` (each joint's faces, `(dim - 1, tag)`) the largest
/// face between each sliver and another block; returns how many slivers
/// were merged so. Thinnest first; a face already taken is not taken twice.
pub(super) fn merge(s: &Session, dim: i32, sizes: &Sizes, faces: &mut [Vec<DimTag>]) -> Result<usize, ApiError> {
    let owner: HashMap<i32, usize> =
        faces.iter().enumerate().flat_map(|(j, f)| f.iter().map(move |&(_, t)| (t, j))).collect();
    let mut slivers = Vec::new();
    for b in s.entities(dim)? {
        let t = thickness(s, dim, b)?;
        let size = sizes.at(s.centre(b)?).unwrap_or(f64::INFINITY);
        if t < size / 10.0 {
            slivers.push((t, b));
        }
    }
    slivers.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut dropped: Vec<i32> = Vec::new();
    for (_, b) in slivers {
        let mut best: Option<(f64, i32)> = None;
        for (_, f) in s.boundary(&[b], false)? {
            let f = f.abs();
            if !owner.contains_key(&f) || dropped.contains(&f) || s.upward(dim - 1, f)?.len() != 2 {
                continue;
            }
            let a = s.mass((dim - 1, f))?;
            if best.is_none_or(|(m, _)| a > m) {
                best = Some((a, f));
            }
        }
        if let Some((_, f)) = best {
            dropped.push(f);
        }
    }
    for f in faces.iter_mut() {
        f.retain(|(_, t)| !dropped.contains(t));
    }
    Ok(dropped.len())
}
