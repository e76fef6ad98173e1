//! Why a model could not be built or solved ([`ModelError`]): one variant
//! per thing that can be wrong, each carrying its data (the key of the
//! input, group names, element tags, coordinates) and formatting its
//! paragraph in its `#[error(..)]`. The messages about the input start with
//! the key they are about; the scene file's name in front of them is the
//! driver's, added once ([`ModelError::about_input`] says which do). Plain
//! data throughout, so an error travels between MPI ranks intact.

use crate::fem::Analysis;

/// "point", "curve", "surface" or "volume".
pub(super) fn dim_name(d: usize) -> &'static str {
    ["point", "curve", "surface", "volume"][d.min(3)]
}

/// Why a model could not be built from its mesh and description, or its
/// parts not solved.
#[derive(Clone, Debug, thiserror::Error, serde::Serialize, serde::Deserialize)]
pub enum ModelError {
    #[error("{key} = \"{group}\" is not a physical group of the mesh `{mesh}`; it has: {known}. Check the name in the .geo's Physical statements")]
    UnknownGroup { key: String, group: String, mesh: String, known: String },
    #[error("{key} = \"{group}\" is a physical {found}, but a {wanted} is needed here")]
    WrongDimension { key: String, group: String, found: String, wanted: String },
    #[error("{key} = \"{group}\" is a physical {dim} of the mesh `{mesh}` without elements: its Physical statement names no entity that exists (gmsh keeps such a group without a word). Check the entity numbers in the .geo's Physical statement for \"{group}\"")]
    EmptyGroup { key: String, group: String, dim: String, mesh: String },
    /// The bodies `analysis` models need a `needs`-D mesh, the mesh `mesh` is `has`-D.
    #[error("analysis: analysis = \"{analysis}\" needs a {needs}D mesh with the bodies as physical {}s, but the mesh `{mesh}` is {has}D (it has physical {}s): {}", dim_name(*needs), dim_name(*has), if *has == 3 { "use analysis = \"solid\"" } else { "use a plane analysis (plane_strain, plane_stress, axisymmetric), or give the .geo physical volumes" })]
    MeshDimension { analysis: Analysis, needs: usize, mesh: String, has: usize },
    #[error("analysis: plane and axisymmetric analyses need a mesh in the plane z = 0, but element {tag} of body \"{body}\" is not; use analysis = \"solid\" for a 3D mesh")]
    NotInPlane { tag: u64, body: String },
    #[error("analysis: axisymmetric models lie in x = r >= 0, but element {tag} of body \"{body}\" has x < 0")]
    NegativeRadius { tag: u64, body: String },
    #[error("{key}: a geostatic initial stress needs the weight of body \"{body}\": give its material a density > 0 and the scene a gravity = [..]")]
    Weightless { key: String, body: String },
    /// Bodies no support holds (`bodies`, their labels), free to move in
    /// `free`; `lying`: when they lie on another body without sharing its nodes.
    #[error("supports: {} {} not held: no support stops {} {} (contacts counted as closed), so the stiffness matrix is singular. {}", if bodies.len() == 1 { "body" } else { "bodies" }, bodies.join(", "), if bodies.len() == 1 { "its" } else { "their" }, free.join(", "), unheld_advice(bodies.len() == 1, lying))]
    NotHeld { bodies: Vec<String>, free: Vec<String>, lying: Option<Unfused> },
    /// A part whose stiffness matrix is singular.
    #[error("supports: {part} not held: the stiffness matrix is singular. Add a support (or more supports: every rigid-body motion must be stopped) or a contact that stays closed")]
    PartNotHeld { part: PartName },
    /// A part whose factorisation ran out of a resource (`why`, the
    /// factorisation's own words).
    #[error("supports: {part}: {why}")]
    PartFactor { part: PartName, why: String },
    /// The bonded interface system is singular: `unsupported`, the bodies
    /// (labels) no support touches, and `unfused`, the body groups with
    /// nodes on other nodes of themselves (group, how many, the first).
    #[error("supports: the bodies are not held even with every contact stuck (the bonded interface system is singular): add a support{}", not_held_hint(unsupported, unfused))]
    InterfaceNotHeld { unsupported: Vec<String>, unfused: Vec<(String, usize, [f64; 3])> },
    #[error("{key}: \"{group}\" is a physical point, which a pressure or traction (per unit area) cannot load: give the point a force = [..] instead, or load a small patch (a short curve in 2D, a small surface in 3D) with a traction")]
    TractionOnPoint { key: String, group: String },
    #[error("{key}: kh and kv are fractions of the acceleration of gravity, but the scene has none: give it gravity = [..] and its materials a density")]
    SeismicWithoutGravity { key: String },
    #[error("{key}: element {tag} of group \"{group}\" is not on the boundary of any body")]
    LoadOffBoundary { key: String, tag: u64, group: String },
    /// A load's facet between bodies (`bodies`, their labels); `pressure`:
    /// the load is a pressure, which may be meant as water in a joint.
    #[error("{key}: element {tag} of group \"{group}\" lies between bodies {}: loads go on outer boundaries{}", bodies.join(" and "), if *pressure { ". For water in a joint between bodies, make the group a [[contacts]] entry and give it water = { .. } (a uniform pressure, a level, or an uplift diagram): the water then pushes on both its faces" } else { "" })]
    LoadBetweenBodies { key: String, tag: u64, group: String, bodies: Vec<String>, pressure: bool },
    #[error("{key}: the point of \"{group}\" at {at:?} is no node of any body: put it on a body (a point of its geometry, or `Point{{..}} In Surface{{..}}` in the .geo)")]
    PointOffBodies { key: String, group: String, at: [f64; 3] },
    #[error("{key}: the point of \"{group}\" at {at:?} lies on a contact, where each body has its own copy of the node: move it off the contact, or load a small patch of one body's boundary")]
    PointOnContact { key: String, group: String, at: [f64; 3] },
    #[error("{key}: \"{group}\" is a physical {} but no [[bodies]] entry: a force on a {} goes on a body's group", dim_name(*dim), dim_name(*dim))]
    ForceOffBodies { key: String, group: String, dim: usize },
    #[error("{key}: the {} \"{group}\" has no extent to spread the force over", dim_name(*dim))]
    NoExtent { key: String, group: String, dim: usize },
    #[error("{key}: a single point carries no moment: give the moment to a small patch (a short curve in 2D, a small surface in 3D) or to the body (group = its [[bodies]] group), with point = [..] where it acts")]
    MomentOnPoint { key: String },
    #[error("{key}: the nodes of \"{group}\" lie on one line, which carries no moment about itself: give that moment to a patch or to the body")]
    MomentOnLine { key: String, group: String },
    #[error("{key}: element {tag} of group \"{group}\" is also element {other_tag} of contacts[{other}]'s group: a face can be in one contact only; remove it from one of the two Physical groups")]
    FaceInTwoContacts { key: String, tag: u64, group: String, other_tag: u64, other: usize },
    #[error("{key}: element {tag} of group \"{group}\" touches no body: it is not a face of any element of the [[bodies]] groups")]
    ContactOffBodies { key: String, tag: u64, group: String },
    #[error("{key}: element {tag} of group \"{group}\" is a face of {count} elements; a face separates two")]
    FaceOfMany { key: String, tag: u64, group: String, count: usize },
    /// A contact group with `lone` facets on one body (`body`, the first
    /// `tag`) beside `between` facets between two; `dim`: the facets'.
    #[error("{key}: group \"{group}\" takes in {lone} element(s) that touch only one body (element {tag} of body \"{body}\" the first) besides the {between} between two bodies: a contact is the {} the bodies share. Leave its outer faces out of the Physical group", facet_name(*dim))]
    OuterFaces { key: String, group: String, lone: usize, tag: u64, body: String, between: usize, dim: usize },
    /// A contact group whose facets all bound one body (`body`, `lone`
    /// of them, the first `tag`); `near`: the body nearest them.
    #[error("{key}: group \"{group}\" touches only body \"{body}\" (element {tag}{}){}. A contact needs a body on each side sharing the {} (group = ..), or two coincident groups (groups = [..])", if *lone > 1 { format!(" and {} more", lone - 1) } else { String::new() }, near_hint(near), facet_name(*dim))]
    OneSided { key: String, group: String, body: String, tag: u64, lone: usize, near: Option<Box<Near>>, dim: usize },
    /// Both groups of a `groups = [a, b]` contact bound `bound` (a body or block).
    #[error("{key}: both \"{a}\" and \"{b}\" bound {bound}: a contact between a body and itself is not supported; split the body into two physical groups")]
    SelfContact { key: String, a: String, b: String, bound: Box<Bounded> },
    #[error("{key}: pairing the nodes of \"{a}\" with those of \"{b}\": {why}")]
    Unpaired { key: String, a: String, b: String, why: Box<Unpaired> },
    #[error("{key}: group \"{group}\" bounds {first} and {second}: with groups = [..] each group is the face of one body (or block)")]
    SideOfTwo { key: String, group: String, first: Box<Bounded>, second: Box<Bounded> },
    #[error("{key}: element {tag} of group \"{group}\" is not a face of any element of the [[bodies]] groups")]
    SideOffBodies { key: String, tag: u64, group: String },
    #[error("{key}: element {tag} of group \"{group}\" lies between {first} and {second}, which share its nodes: with groups = [..] each group is the face of one body. For a surface the two bodies share, use group = \"{group}\" instead")]
    SideBetween { key: String, tag: u64, group: String, first: Box<Bounded>, second: Box<Bounded> },
    /// A joint with no length along `along` (its nodes all at `s`).
    #[error("{key}: the joint \"{joint}\" has no length along the flow direction along = [{}, {}, {}] (its nodes all lie at s = {s}), so it has no upstream and downstream ends: give `along` as the horizontal direction in which the water flows under the joint", along[0], along[1], along[2])]
    JointNoLength { key: String, joint: String, along: [f64; 3], s: f64 },
    #[error("{key}: the joint \"{joint}\" does not meet the face \"{face}\" (they have no node in common), so no crack of it can fill from that face's water: name the loaded face the joint ends on (a dam's upstream face at the heel, a slope's tension crack)")]
    FaceOffJoint { key: String, joint: String, face: String },
    #[error("{key}: the face \"{face}\" is at the downstream end of the joint \"{joint}\" along the flow direction [{}, {}, {}]: s = x . along must grow away from the face the cracks fill from; turn `along` round", along[0], along[1], along[2])]
    FaceDownstream { key: String, face: String, joint: String, along: [f64; 3] },
    #[error("element {tag} of body \"{body}\" is inverted or degenerate (Jacobian determinant {det_j:.3e}): fix the mesh (node order or a collapsed element)")]
    Inverted { body: String, tag: u64, det_j: f64 },
    #[error("element {tag} ({kind}) of body {body} is folded or inverted: its Jacobian determinant is {det_j:.3e} {}, where it must be positive over the whole element, not only at the integration points. Fix the mesh: corner nodes in the wrong order, or a mid-side node beyond the opposite side (with gmsh: Mesh.HighOrderOptimize = 2, or a finer mesh where the boundary curves)", match node { Some(k) => format!("at its node {k} (gmsh order)"), None => "at its centre".to_string() })]
    Folded { body: String, tag: u64, kind: String, node: Option<usize>, det_j: f64 },
    #[error("every element of body {body} ({cells} of {cells}) is inverted: its Jacobian determinant is negative, so the body's mesh is mirrored, its elements' nodes running the wrong way round{}", if *dim == 2 { ". In a .geo this is a surface whose curve loop runs clockwise: draw the loop counter-clockwise (its curves negated and in reverse order, e.g. Curve Loop(2) = {-4, -3, -2, -1};) or add Reverse Surface{2}; after the surface" } else { ": check the node order of its elements in the .msh (in a .geo, Reverse Volume{..};)" })]
    Mirrored { body: String, cells: usize, dim: usize },
    #[error("element {tag} ({kind}) of body {body} is degenerate: its corner nodes {} and {} (gmsh order) lie at the same point ({:.6}, {:.6}, {:.6}), a collapsed edge where its Jacobian determinant is zero. Remesh it: a {kind} must keep its corners apart (a quadrangle or hexahedron collapsed into a triangle, prism or pyramid is not one; let gmsh make triangles, tetrahedra or prisms there), or check the element's node order in the .msh", corners.0, corners.1, at[0], at[1], at[2])]
    Collapsed { body: String, tag: u64, kind: String, corners: (usize, usize), at: [f64; 3] },
}

impl ModelError {
    /// Whether the message is about the input (a key of the scene), so
    /// that the scene file's name goes in front of it; the mesh's own
    /// faults (inverted, folded, collapsed elements) name the element.
    pub fn about_input(&self) -> bool {
        !matches!(
            self,
            ModelError::Inverted { .. }
                | ModelError::Folded { .. }
                | ModelError::Mirrored { .. }
                | ModelError::Collapsed { .. }
        )
    }
}

/// Bodies nothing holds that lie on another body without sharing its
/// nodes: `nodes` of theirs do, the first at `at`, on the body `on` (its
/// label), in a mesh of dimension `dim`.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct Unfused {
    pub nodes: usize,
    pub at: [f64; 3],
    pub on: String,
    pub dim: usize,
}

/// What a contact group's facets bound: a whole body (its group name), or
/// one block (`number`, from 1) of a body cut into blocks, with its centre.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub enum Bounded {
    Body { name: String },
    Block { number: usize, body: String, centre: [f64; 3] },
}

impl std::fmt::Display for Bounded {
    /// "body "rock"", or "block 3 of body "rock" (centre at (x, y, z))".
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Bounded::Body { name } => write!(f, "body \"{name}\""),
            Bounded::Block { number, body, centre: c } => {
                write!(f, "block {number} of body \"{body}\" (centre at ({:.4}, {:.4}, {:.4}))", c[0], c[1], c[2])
            }
        }
    }
}

/// A part of the model: its bodies (labels) and, when cut into
/// substructures, which piece of how many (from 0).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PartName {
    pub bodies: Vec<String>,
    pub piece: Option<(usize, usize)>,
}

impl std::fmt::Display for PartName {
    /// "body "a"" or "bodies "a", "b"", with the piece when cut.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let what = if self.bodies.len() == 1 { "body" } else { "bodies" };
        write!(f, "{what} {}", self.bodies.join(", "))?;
        match self.piece {
            Some((i, k)) => write!(f, " (substructure {} of {k})", i + 1),
            None => Ok(()),
        }
    }
}

/// What may leave the bodies free when the bonded interface system is
/// singular: bodies no support touches, bodies not fused where their
/// volumes meet.
fn not_held_hint(unsupported: &[String], unfused: &[(String, usize, [f64; 3])]) -> String {
    let mut s = String::new();
    if !unsupported.is_empty() {
        s += &format!(". No support touches {}: each is held only through its contacts", unsupported.join(", "));
    }
    for (group, n, x) in unfused {
        s += &format!(". Body \"{group}\" has {n} nodes on other nodes of itself (the first at ({:.6}, {:.6}, {:.6})): its volumes are not fused there (BooleanFragments or Coherence in the .geo)", x[0], x[1], x[2]);
    }
    s
}

/// The body nearest the facets of a contact group that touches one body.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub enum Near {
    /// Its facet `tag` lies against `body`, `dist` away, which does not share its nodes.
    Against { tag: u64, body: String, dist: f64 },
    /// The nearest other body, `dist` away.
    Nearest { body: String, dist: f64 },
}

/// Why the nodes of two groups do not pair by position.
#[derive(Clone, Debug, thiserror::Error, serde::Serialize, serde::Deserialize)]
pub enum Unpaired {
    #[error("node at {at:?} has {partners} partners within {tol:.1e}: the mesh has duplicate nodes")]
    Duplicate { at: [f64; 3], partners: usize, tol: f64 },
    #[error("{} node(s) find no partner on the other side within {tol:.1e}, first at {}: the two groups must have coincident nodes (same mesh divisions on both curves/surfaces)", lonely.len(), first(lonely))]
    Lonely { lonely: Vec<[f64; 3]>, tol: f64 },
}

/// The first five points of `lonely`, for a message.
fn first(lonely: &[[f64; 3]]) -> String {
    let first: Vec<String> =
        lonely.iter().take(5).map(|p| format!("({:.6}, {:.6}, {:.6})", p[0], p[1], p[2])).collect();
    first.join(", ")
}

/// "curve" for the facets of a 2D mesh (dimension 1), else "surface".
fn facet_name(dim: usize) -> &'static str {
    if dim == 1 {
        "curve"
    } else {
        "surface"
    }
}

/// What to do about bodies nothing holds (`one`: a single body).
fn unheld_advice(one: bool, lying: &Option<Unfused>) -> String {
    let it = if one { "it" } else { "them" };
    let Some(Unfused { nodes: n, at: x, on, dim }) = lying else {
        return format!("Add a support that stops {it} (fix = [..] on a physical point, curve or surface)");
    };
    let (entities, entity) = if *dim == 3 { ("volumes", "Volume") } else { ("surfaces", "Surface") };
    format!(
        "{} on body {on} at {n} node(s) without sharing them (the first at ({:.6}, {:.6}, {:.6})): the {entities} were not fused there, so nothing joins {it} to that body. Fuse them in the .geo so that they share their nodes (OpenCASCADE: BooleanFragments{{ {entity}{{:}}; Delete; }}{{}}; the built-in kernel: Coherence;), give the touching faces a [[contacts]] entry if they should slip or open there, or add a support that stops {it}",
        if one { "It lies" } else { "They lie" },
        x[0],
        x[1],
        x[2]
    )
}

/// The hint of a contact group that touches one body: the body it lies against, or the nearest.
fn near_hint(near: &Option<Box<Near>>) -> String {
    match near.as_deref() {
        Some(Near::Against { tag, body, dist }) => format!(
            "; its element {tag} lies against body \"{body}\" ({dist:.3e} away), which does not share its nodes: the two were meshed apart. Make the mesh conformal (OpenCASCADE: BooleanFragments{{ Volume{{..}}; Delete; }}{{ Volume{{..}}; Delete; }}, or Coherence), or give each side its own group and pair them with groups = [..]"
        ),
        Some(Near::Nearest { body, dist }) => format!("; the nearest other body is \"{body}\", {dist:.3e} away"),
        None => String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::{Bounded, ModelError, PartName};

    #[test]
    fn parts_blocks_and_an_unheld_interface_read_as_their_data_says() {
        let one = PartName { bodies: vec!["\"a\"".into()], piece: None };
        assert_eq!(one.to_string(), "body \"a\"");
        let cut = PartName { bodies: vec!["\"a\"".into(), "\"b\"".into()], piece: Some((1, 3)) };
        assert_eq!(cut.to_string(), "bodies \"a\", \"b\" (substructure 2 of 3)");
        let block = Bounded::Block { number: 3, body: "rock".into(), centre: [1.0, 2.5, 0.0] };
        assert_eq!(block.to_string(), "block 3 of body \"rock\" (centre at (1.0000, 2.5000, 0.0000))");
        let e = ModelError::InterfaceNotHeld {
            unsupported: vec!["\"b\"".into()],
            unfused: vec![("g".into(), 4, [0.5; 3])],
        };
        assert_eq!(
            e.to_string(),
            "supports: the bodies are not held even with every contact stuck (the bonded interface system is \
             singular): add a support. No support touches \"b\": each is held only through its contacts. Body \"g\" \
             has 4 nodes on other nodes of itself (the first at (0.500000, 0.500000, 0.500000)): its volumes are not \
             fused there (BooleanFragments or Coherence in the .geo)"
        );
    }
}
