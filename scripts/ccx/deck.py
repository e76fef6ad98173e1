"""CalculiX decks for the block-on-block scene, from the gmsh mesh subcontact made.

What it is responsible for: reading the hex20 mesh (meshio), checking the node
order CalculiX expects, and writing two decks for the same model:

* bonded: one mesh, the joint's nodes shared by both blocks;
* contact: the upper block's joint nodes duplicated, a face-to-face penalty
  (``TYPE=SURFACE TO SURFACE``) or mortar contact pair on the joint with
  Coulomb friction.

Both: E and nu from the scene, the base held in x, y and z, and the top face
loaded by a uniform traction t as consistent nodal forces (``*CLOAD``):

    f_a = sum over top quad8 faces of  int_face N_a t dA
        = sum_g N_a(xi_g) t |x_xi x x_eta|(xi_g) w_g      (3 x 3 Gauss),

so that sum_a f_a = t * area (checked). Node order: meshio gives hex20 and
quad8 in VTK order, which is Abaqus's (corners, then the mid-edge nodes of
edges 1-2, 2-3, 3-4, 4-1, 5-6, 6-7, 7-8, 8-5, 1-5, 2-6, 3-7, 4-8); this is
verified geometrically (every mid-edge node at its edge's midpoint, det J > 0)
rather than trusted. CalculiX reads fields of at most 20 characters and lines
of limited length: C3D20 lines are split after 16 entries.
"""

from __future__ import annotations

import dataclasses
import pathlib

import numpy as np

# Abaqus/VTK hex20: the mid-edge node k (8..19) sits between these corners.
HEX20_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
               (0, 4), (1, 5), (2, 6), (3, 7)]
# C3D8/C3D20 faces S1..S6 by their corner nodes (CalculiX manual, "C3D8").
HEX_FACES = [(0, 1, 2, 3), (4, 7, 6, 5), (0, 4, 5, 1), (1, 5, 6, 2), (2, 6, 7, 3), (3, 7, 4, 0)]
QUAD8_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0)]


@dataclasses.dataclass
class Mesh:
    """The scene's mesh: 0-based node indices, hex20 and quad8 in Abaqus order."""

    points: np.ndarray                 # (n, 3)
    hexes: dict[str, np.ndarray]       # body name -> (ne, 20)
    faces: dict[str, np.ndarray]       # surface group -> (nf, 8)

    def group_nodes(self, group: str) -> np.ndarray:
        return np.unique(self.faces[group])


@dataclasses.dataclass
class Model:
    """What both decks share: materials, supports, load and contact data."""

    young: float
    poisson: float
    traction: tuple[float, float, float]
    friction: float
    bodies: tuple[str, str] = ("lower", "upper")
    joint: str = "joint"
    base: str = "base"
    top: str = "top"


def read_mesh(path: pathlib.Path, bodies, surfaces) -> Mesh:
    """Read a gmsh .msh with meshio and split it by physical group."""
    import meshio

    m = meshio.read(str(path))
    hexes, faces = {}, {}
    for name in list(bodies) + list(surfaces):
        if name not in m.cell_sets:
            raise SystemExit(f"error: {path}: no physical group {name!r}")
        want = "hexahedron20" if name in bodies else "quad8"
        blocks = [m.cells[i].data[idx] for i, idx in enumerate(m.cell_sets[name])
                  if len(idx) and m.cells[i].type == want]
        if not blocks:
            raise SystemExit(f"error: {path}: group {name!r} has no {want} cells "
                             "(mesh with hex = 1, serendipity = 1, order 2)")
        (hexes if name in bodies else faces)[name] = np.concatenate(blocks).astype(np.int64)
    mesh = Mesh(np.asarray(m.points, dtype=float), hexes, faces)
    check_order(mesh)
    return mesh


def check_order(mesh: Mesh) -> None:
    """Mid-edge nodes at the midpoints of their edges; det J > 0 at the centre."""
    p = mesh.points
    tol = 1e-9 * np.ptp(p, axis=0).max()
    for name, h in mesh.hexes.items():
        for k, (a, b) in enumerate(HEX20_EDGES):
            err = np.abs(p[h[:, 8 + k]] - 0.5 * (p[h[:, a]] + p[h[:, b]])).max()
            if err > tol:
                raise SystemExit(f"error: body {name}: hex20 node {8 + k} is not the midpoint "
                                 f"of edge {a}-{b} (off by {err:g}): unexpected node order")
        c = p[h[:, :8]]
        # d x / d(xi, eta, zeta) at the centre of the trilinear map
        jx = (c[:, 1] + c[:, 2] + c[:, 5] + c[:, 6] - c[:, 0] - c[:, 3] - c[:, 4] - c[:, 7]) / 4
        jy = (c[:, 2] + c[:, 3] + c[:, 6] + c[:, 7] - c[:, 0] - c[:, 1] - c[:, 4] - c[:, 5]) / 4
        jz = (c[:, 4] + c[:, 5] + c[:, 6] + c[:, 7] - c[:, 0] - c[:, 1] - c[:, 2] - c[:, 3]) / 4
        det = np.einsum("ij,ij->i", jx, np.cross(jy, jz))
        if (det <= 0).any():
            raise SystemExit(f"error: body {name}: {(det <= 0).sum()} hex20 with det J <= 0")
    for name, f in mesh.faces.items():
        for k, (a, b) in enumerate(QUAD8_EDGES):
            err = np.abs(p[f[:, 4 + k]] - 0.5 * (p[f[:, a]] + p[f[:, b]])).max()
            if err > tol:
                raise SystemExit(f"error: surface {name}: quad8 node {4 + k} is not the "
                                 f"midpoint of edge {a}-{b}: unexpected node order")


def quad8_shape(xi: float, eta: float) -> tuple[np.ndarray, np.ndarray]:
    """Serendipity quad8 shape functions and their (xi, eta) derivatives."""
    r = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1], [0, -1], [1, 0], [0, 1], [-1, 0]], float)
    n, d = np.zeros(8), np.zeros((8, 2))
    for a, (xa, ea) in enumerate(r):
        if a < 4:
            n[a] = 0.25 * (1 + xi * xa) * (1 + eta * ea) * (xi * xa + eta * ea - 1)
            d[a, 0] = 0.25 * xa * (1 + eta * ea) * (2 * xi * xa + eta * ea)
            d[a, 1] = 0.25 * ea * (1 + xi * xa) * (xi * xa + 2 * eta * ea)
        elif xa == 0:
            n[a] = 0.5 * (1 - xi * xi) * (1 + eta * ea)
            d[a] = [-xi * (1 + eta * ea), 0.5 * ea * (1 - xi * xi)]
        else:
            n[a] = 0.5 * (1 + xi * xa) * (1 - eta * eta)
            d[a] = [0.5 * xa * (1 - eta * eta), -eta * (1 + xi * xa)]
    return n, d


def traction_forces(points: np.ndarray, faces: np.ndarray, t) -> tuple[dict[int, np.ndarray], float]:
    """Consistent nodal forces of a uniform traction t on quad8 faces; and the area."""
    g = np.sqrt(3.0 / 5.0)
    gauss = [(-g, 5 / 9), (0.0, 8 / 9), (g, 5 / 9)]
    t = np.asarray(t, float)
    forces: dict[int, np.ndarray] = {}
    area = 0.0
    for f in faces:
        x = points[f]
        w_node = np.zeros(8)
        for xi, wx in gauss:
            for eta, we in gauss:
                n, d = quad8_shape(xi, eta)
                da = np.linalg.norm(np.cross(d[:, 0] @ x, d[:, 1] @ x)) * wx * we
                w_node += n * da
                area += da
        for a in range(8):
            forces.setdefault(int(f[a]), np.zeros(3))
            forces[int(f[a])] += w_node[a] * t
    return forces, area


def faces_on(hexes: np.ndarray, nodes: set[int]) -> list[tuple[int, int]]:
    """(element row, face number 1..6) of every hex face whose corners all lie in nodes."""
    inside = np.isin(hexes[:, :8], np.fromiter(nodes, dtype=np.int64))
    out = []
    for k, corners in enumerate(HEX_FACES):
        rows = np.nonzero(inside[:, list(corners)].all(axis=1))[0]
        out += [(int(r), k + 1) for r in rows]
    return sorted(out)


def fmt(x: float) -> str:
    """A number in at most 20 characters (CalculiX reads fields with f20.0)."""
    s = f"{x:.12g}"
    assert len(s) <= 20, s
    return s


def _nodes(points: np.ndarray, ids: np.ndarray) -> list[str]:
    out = ["*NODE, NSET=NALL"]
    out += [f"{i},{fmt(x)},{fmt(y)},{fmt(z)}" for i, (x, y, z) in zip(ids, points)]
    return out


def _elements(name: str, hexes: np.ndarray, first_id: int) -> list[str]:
    out = [f"*ELEMENT, TYPE=C3D20, ELSET={name.upper()}"]
    for k, h in enumerate(hexes):
        ids = [str(first_id + k)] + [str(int(n) + 1) for n in h]
        out.append(",".join(ids[:16]) + ",")     # at most 16 entries on a line
        out.append(",".join(ids[16:]))
    return out


def _node_set(name: str, nodes) -> list[str]:
    ids = [str(int(n) + 1) for n in sorted(nodes)]
    return [f"*NSET, NSET={name}"] + [",".join(ids[i:i + 16]) for i in range(0, len(ids), 16)]


# The contact decks compared (K and lambda in force / length^3, as multiples of E):
# f2f follows the CalculiX manual (K "5 to 50 times the E-modulus", 50 E being
# also ccx's default for hard contact; lambda "about 100 times smaller" than K);
# the *_stiff decks make stick and penetration nearly rigid, as in subcontact.
CONTACT_VARIANTS = {
    "f2f": {"kind": "SURFACE TO SURFACE", "k_over_e": 50.0, "lambda_over_k": 0.01},
    "f2f_stiff": {"kind": "SURFACE TO SURFACE", "k_over_e": 500.0, "lambda_over_k": 1.0},
    "mortar_stiff": {"kind": "MORTAR", "k_over_e": 500.0, "lambda_over_k": 1.0},
}


@dataclasses.dataclass
class ContactOptions:
    kind: str = "SURFACE TO SURFACE"   # or MORTAR
    stiffness: float = 1.5e6           # K, pressure per overclosure (F/L^3)
    stick_slope: float = 1.5e4         # lambda, shear stress per tangential slip (F/L^3)
    hard: bool = False                 # mortar only: PRESSURE-OVERCLOSURE=HARD


def write_deck(path: pathlib.Path, mesh: Mesh, model: Model, contact: ContactOptions | None,
               top_centre: int, title: str) -> dict:
    """Write one deck; return facts about it (node/element counts, load resultant)."""
    lower, upper = (mesh.hexes[b] for b in model.bodies)
    points = mesh.points
    joint = set(mesh.group_nodes(model.joint).tolist())
    upper_hexes = upper
    if contact is not None:
        # the upper block gets its own copies of the joint's nodes
        extra = sorted(joint)
        copy = {old: len(points) + k for k, old in enumerate(extra)}
        points = np.vstack([points, mesh.points[extra]])
        remap = np.arange(len(mesh.points))
        remap[extra] = list(copy.values())
        upper_hexes = remap[upper]
    forces, area = traction_forces(mesh.points, mesh.faces[model.top], model.traction)
    resultant = np.sum(list(forces.values()), axis=0)
    lines = [f"** {title}", "** written by scripts/ccx/deck.py from the mesh subcontact made"]
    lines += _nodes(points, np.arange(1, len(points) + 1))
    lines += _elements(model.bodies[0], lower, 1)
    lines += _elements(model.bodies[1], upper_hexes, 1 + len(lower))
    lines += _node_set("NBASE", mesh.group_nodes(model.base))
    lines += _node_set("NTOPC", [top_centre])
    lines += ["*MATERIAL, NAME=CONCRETE", "*ELASTIC", f"{fmt(model.young)},{fmt(model.poisson)}"]
    for b in model.bodies:
        lines += [f"*SOLID SECTION, ELSET={b.upper()}, MATERIAL=CONCRETE"]
    if contact is not None:
        up_ids = set(int(n) for n in upper_hexes[:, :8].ravel()) & set(copy.values())
        for name, hx, first, nodes in (("SLOWER", lower, 1, joint),
                                       ("SUPPER", upper_hexes, 1 + len(lower), up_ids)):
            lines += [f"*SURFACE, NAME={name}, TYPE=ELEMENT"]
            lines += [f"{first + r},S{k}" for r, k in faces_on(hx, nodes)]
        lines += ["*SURFACE INTERACTION, NAME=JOINT"]
        if contact.hard:
            lines += ["*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD"]
        else:
            lines += ["*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", fmt(contact.stiffness)]
        lines += ["*FRICTION", f"{fmt(model.friction)},{fmt(contact.stick_slope)}"]
        # slave: the upper block's faces; master: the lower block's
        lines += [f"*CONTACT PAIR, INTERACTION=JOINT, TYPE={contact.kind}", "SUPPER,SLOWER"]
    lines += ["*STEP, INC=1000", "*STATIC"]
    if contact is not None:
        lines += ["1.0, 1.0, 1e-5, 1.0"]
    lines += ["*BOUNDARY", "NBASE,1,3", "*CLOAD"]
    for n in sorted(forces):
        for d in range(3):
            if forces[n][d] != 0.0:
                lines.append(f"{n + 1},{d + 1},{fmt(forces[n][d])}")
    lines += ["*NODE PRINT, NSET=NALL", "U"]
    if contact is not None:
        lines += ["*CONTACT FILE", "CDIS, CSTR"]
        lines += ["*CONTACT PRINT, SLAVE=SUPPER, MASTER=SLOWER", "CF"]
    lines += ["*END STEP", ""]
    path.write_text("\n".join(lines))
    return {
        "nodes": len(points),
        "elements": len(lower) + len(upper),
        "equations": 3 * (len(points) - len(mesh.group_nodes(model.base))),
        "load_area": area,
        "load_resultant": resultant.tolist(),
        "joint_nodes": len(joint),
    }
