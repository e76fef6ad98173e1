#!/usr/bin/env python3
"""make safety: the factor of safety by strength reduction (issue 18) and
the load factor (issue 34) beside the closed forms, with the mechanism
named (issue 29), for docs/safety.md and the README.

- The rock wedge in a V-groove (geo/wedge.toml) on its default mesh
  (lc = 1) and a coarser one (lc = 2), and on its sharp crease (h0 = 0,
  no crevice, lc = 1), all with the bisection tolerance lowered to 1e-4,
  against Hoek & Bray's rigid-block factor
  F = sin(beta) / sin(xi / 2) * tan(phi) / tan(psi) (beta = 90 degrees for
  the symmetric wedge; xi = 90 degrees, the .geo's default; phi from the
  joints' friction; psi, the plunge of the line of intersection, from the
  turned gravity vector).
- The same wedge (lc = 2) with a uniform water pressure u = 0.01 MPa on
  both planes (issue 30), the water held while the strength is reduced,
  against Hoek & Bray's factor with the uplift: scripts/water/water.py's
  scene and closed form (tests/water.rs asserts it within 1 %).
- The gravity dam (geo/dam.toml, `subcontact safety`: the scene has no
  [safety] table, so the defaults) against its base's limit equilibrium by
  hand from the base pairs of its own contact.csv at F = 1:
  F = (c A + N tan(phi)) / T, with N = -sum(sigma_n area) and T the
  magnitude of sum(tau area) over the closed pairs of the contact "base".

- Hoek & Bray's planar slope (geo/planar_slope.toml, dry tension crack,
  c = 25 kPa, the scene silent on residual_cohesion) against
  F = (c A + W cos(psi) tan(phi)) / (W sin(psi)), the peak cohesion kept
  over the whole plane; the factor with residual strength beside it.
- The dam with a cohesive base kept (c = 0.1 MPa = residual_cohesion):
  every trial converged, against (c A + N tan(phi)) / T over the closed
  base by hand.
- Goodman & Bray's block on a plane at 20 degrees (tests/geo/topple.geo,
  tan(phi) = 0.84), 2D and 3D, on both sides of b/h = tan(theta): b/h =
  0.30 topples (the mechanism named), b/h = 0.45 stands with its toppling
  margin (b/h) / tan(theta) and slides at tan(phi) / tan(theta).
- The gravity wall (geo/wall.toml, `[safety] load`): the load factor
  against M_r / M_o (overturning about the toe) and, with tan(phi) = 0.4,
  against W tan(phi) / H (sliding).

Each run's results stay in results/safety/<run>/; the tables go to stdout
and to results/safety/safety.md.

Usage: python3 scripts/safety/safety.py
"""

from __future__ import annotations

import csv
import json
import math
import pathlib
import subprocess
import sys
import tomllib

ROOT = pathlib.Path(__file__).resolve().parents[2]
BIN = ROOT / "target/release/subcontact"
OUT = ROOT / "results/safety"
sys.path.insert(0, str(ROOT / "scripts/water"))
import water  # noqa: E402  (the wedge's water and its closed form, as make water has them)


def run(args: list[str], fails: bool = False) -> dict:
    """Runs subcontact ARGS --out results/safety/<name> --quiet; its summary
    (`fails`: the run is expected to end with exit status 1 after writing
    its results)."""
    name = args[-1]
    out = OUT / pathlib.Path(name).stem
    cmd = [str(BIN), args[0], name, "--out", str(out), "--quiet"]
    print("$", " ".join(cmd[:3]), "...", file=sys.stderr)
    done = subprocess.run(cmd, cwd=ROOT, check=not fails, stderr=subprocess.PIPE if fails else None, text=True)
    if fails and done.returncode != 1:
        sys.exit(f"{name}: expected exit status 1, got {done.returncode}: {done.stderr}")
    return json.loads((out / "summary.json").read_text())


def scene_copy(repo_path: str, name: str, edits: list[tuple[str, str]]) -> str:
    """A repository scene edited into results/safety/NAME.toml (its mesh
    path made relative to there); its path from the repository root."""
    text = (ROOT / repo_path).read_text()
    for old, new in edits:
        assert old in text, f"{repo_path} no longer contains {old!r}: update scripts/safety/safety.py"
        text = text.replace(old, new, 1)
    path = OUT / f"{name}.toml"
    path.write_text(text)
    return str(path.relative_to(ROOT))


def wedge_scene(lc: float, crease: bool = False) -> str:
    """geo/wedge.toml at element size lc and tolerance 1e-4 (on the sharp
    crease: h0 = 0), written into results/safety/ (its mesh path made
    relative to there)."""
    text = (ROOT / "geo/wedge.toml").read_text()
    size = f"lc = {lc}, h0 = 0 }}" if crease else f"lc = {lc} }}"
    for old, new in [('mesh = "wedge.geo"', 'mesh = "../../geo/wedge.geo"'), ("lc = 1.0 }", size), ("tolerance = 1.0e-3", "tolerance = 1.0e-4")]:
        assert old in text, f"geo/wedge.toml no longer contains {old!r}: update scripts/safety/safety.py"
        text = text.replace(old, new, 1)
    path = OUT / f"wedge_lc{lc:g}{'_crease' if crease else ''}.toml"
    path.write_text(text)
    return str(path.relative_to(ROOT))


def rigid_wedge() -> float:
    """Hoek & Bray's factor for geo/wedge.toml (xi = 90 degrees)."""
    scene = tomllib.loads((ROOT / "geo/wedge.toml").read_text())
    phi = math.atan(scene["contacts"][0]["friction"])
    g = scene["gravity"]
    psi = math.atan2(-g[1], -g[2])
    return 1.0 / math.sin(math.radians(45.0)) * math.tan(phi) / math.tan(psi)


def dam_by_hand(scene_path: str = "geo/dam.toml") -> float:
    """(c A + N tan phi) / T of the dam's base from its contact.csv (A the
    closed length)."""
    scene = tomllib.loads((ROOT / scene_path).read_text())
    base = next(c for c in scene["contacts"] if c.get("group") == "base")
    n, t, area = 0.0, [0.0, 0.0], 0.0
    path = OUT / pathlib.Path(scene_path).stem / "contact.csv"
    for row in csv.DictReader(path.open()):
        if row["contact"] != "base" or row["status"] == "0":
            continue
        a = float(row["area"])
        n -= float(row["sigma_n"]) * a
        t[0] += float(row["tau_x"]) * a
        t[1] += float(row["tau_y"]) * a
        area += a
    return (base.get("cohesion", 0.0) * area + n * base["friction"]) / math.hypot(*t)


def row(what: str, summary: dict, exact: float, form: str) -> str:
    s = summary["safety"]
    f, fails = s["factor"], s["fails_at"]
    cost = s["cost"]
    per = cost["contact_iterations"] / max(cost["trials"], 1)
    return (
        f"| {what} | {summary['dofs']['total']:,} | {f:.5f} | {fails:.5f} | {exact:.5f} ({form}) | {100 * (f / exact - 1):+.3f} % "
        f"| {cost['trials']} | {per:.1f} | {cost['search_s'] / max(cost['trials'], 1):.3f} | {summary['counters']['factorisations']} |"
    )


def planar_slope() -> float:
    """Hoek & Bray's F for geo/planar_slope.geo's default figures."""
    h, face, psi, xc = 20.0, math.radians(60), math.radians(35), 20.0
    scene = tomllib.loads((ROOT / "geo/planar_slope.toml").read_text())
    plane = scene["contacts"][0]
    gamma = scene["materials"]["rock"]["density"] * -scene["gravity"][1]
    pts = [(0.0, 0.0), (xc, xc * math.tan(psi)), (xc, h), (h / math.tan(face), h)]
    area = 0.5 * abs(sum(pts[i][0] * pts[(i + 1) % 4][1] - pts[(i + 1) % 4][0] * pts[i][1] for i in range(4)))
    w, a = area * gamma, xc / math.cos(psi)
    return (plane["cohesion"] * a + w * math.cos(psi) * plane["friction"]) / (w * math.sin(psi))


def topple_scene(b: float, solid: bool) -> str:
    """Goodman & Bray's block b x 2 on a plane at 20 degrees, tan(phi) = 0.84."""
    s, c = math.sin(math.radians(20)), math.cos(math.radians(20))
    gravity = f"[{10 * s}, {-10 * c}, 0.0]" if solid else f"[{10 * s}, {-10 * c}]"
    fix = '["x", "y", "z"]' if solid else '["x", "y"]'
    text = f"""title = "a block b/h = {b / 2.0:g} on a plane at 20 degrees"
mesh = "../../tests/geo/topple.geo"
analysis = "{'solid' if solid else 'plane_strain'}"
gravity = {gravity}

[gmsh]
order = 2
setnumber = {{ b = {b}, h = 2.0, solid = {int(solid)}, n = 4 }}

[materials.rock]
E = 1000.0
nu = 0.25
density = 1.0

[[bodies]]
group = "base"
material = "rock"

[[bodies]]
group = "block"
material = "rock"

[[contacts]]
group = "joint"
friction = 0.84

[[supports]]
group = "base_bottom"
fix = {fix}

[safety]
"""
    path = OUT / f"topple_{b:g}_{'3d' if solid else '2d'}.toml"
    path.write_text(text)
    return str(path.relative_to(ROOT))


def mechanism_row(what: str, summary: dict, expected: str, margin: tuple[float, float] | None) -> str:
    s = summary["safety"]
    m = (s.get("failure") or {}).get("mechanism") or {}
    got = m.get("kind", "–")
    if margin:
        f, exact = margin
        cell = f"{f:.5f} against {exact:.5f} ({100 * (f / exact - 1):+.3f} %)"
    else:
        cell = "–"
    ok = "yes" if got == expected else "NO"
    return f"| {what} | {expected} | {got} ({m.get('description', '')}) | {ok} | {cell} |"


def block_margin(name: str) -> float:
    rows = list(csv.DictReader((OUT / name / "blocks.csv").open()))
    return float(next(r for r in rows if r["body"] == "block")["toppling_margin"])


def main() -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    rigid = rigid_wedge()
    rows = []
    for lc in (2.0, 1.0):
        summary = run(["solve", wedge_scene(lc)])
        rows.append(row(f"wedge in a V-groove, tet10 lc = {lc:g}", summary, rigid, "Hoek & Bray"))
    summary = run(["solve", wedge_scene(1.0, crease=True)])
    rows.append(row("wedge on its sharp crease (h0 = 0), tet10 lc = 1", summary, rigid, "Hoek & Bray"))
    wet = scene_copy("geo/wedge.toml", "wedge_water", [('mesh = "wedge.geo"', 'mesh = "../../geo/wedge.geo"'), *water.WEDGE_EDITS])
    u = water.WEDGE_U
    rows.append(row(f"wedge with water u = {u} MPa on both planes, tet10 lc = 2", run(["solve", wet]), water.wedge_closed(u), "Hoek & Bray, with U"))
    dam = run(["safety", scene_copy("geo/dam.toml", "dam", [('mesh = "dam.geo"', 'mesh = "../../geo/dam.geo"')])])
    rows.append(row("gravity dam, base", dam, dam_by_hand("results/safety/dam.toml"), "f N / T by hand"))
    cohesive = scene_copy(
        "geo/dam.toml",
        "dam_cohesion",
        [
            ('mesh = "dam.geo"', 'mesh = "../../geo/dam.geo"'),
            ('group = "base"\nfriction = 0.75\ncohesion = 0.0', 'group = "base"\nfriction = 0.75\ncohesion = 0.1\nresidual_cohesion = 0.1'),
        ],
    )
    dam_c = run(["safety", cohesive])
    converged = all(t["failure"] != "not_converged" for t in dam_c["safety"]["trials"])
    rows.append(row(f"gravity dam, base c = 0.1 MPa kept (every trial converged: {converged})", dam_c, dam_by_hand(cohesive), "(c A + N f) / T by hand"))
    slope = run(["safety", scene_copy("geo/planar_slope.toml", "planar_slope", [('mesh = "planar_slope.geo"', 'mesh = "../../geo/planar_slope.geo"')])])
    other = slope["safety"]["other"]["factor"]
    rows.append(row(f"planar slope, peak strength (residual: {other:.5f})", slope, planar_slope(), "Hoek & Bray"))
    tan = math.tan(math.radians(20))
    mech = []
    for solid in (False, True):
        dim = "3D hex20" if solid else "2D quad9"
        slender = run(["solve", topple_scene(0.6, solid)], fails=True)
        mech.append(mechanism_row(f"block b/h = 0.30 < tan 20 = {tan:.4f}, {dim}", slender, "toppling", None))
        name = topple_scene(0.9, solid)
        stout = run(["solve", name])
        mech.append(mechanism_row(f"block b/h = 0.45 > tan 20, {dim}: toppling margin", stout, "sliding", (block_margin(pathlib.Path(name).stem), 0.45 / tan)))
        rows.append(row(f"block b/h = 0.45 on a 20 degree plane, tan(phi) = 0.84, {dim}", stout, 0.84 / tan, "tan(phi) / tan(theta)"))
    wall_w, wall_h = 2.4 * 9.81 * 2.0 * 4.0, 10.0 * 4.0
    wall = run(["solve", scene_copy("geo/wall.toml", "wall", [('mesh = "wall.geo"', 'mesh = "../../geo/wall.geo"')])])
    rows.append(row("gravity wall, load factor (tips about its toe)", wall, (wall_w * 1.0) / (wall_h * 2.0), "M_r / M_o"))
    mech.append(mechanism_row("gravity wall, load factor, tan(phi) = 1", wall, "toppling", None))
    wall_s = run(["solve", scene_copy("geo/wall.toml", "wall_sliding", [('mesh = "wall.geo"', 'mesh = "../../geo/wall.geo"'), ("friction = 1.0", "friction = 0.4")])])
    rows.append(row("gravity wall, load factor, tan(phi) = 0.4 (slides)", wall_s, wall_w * 0.4 / wall_h, "W tan(phi) / H"))
    mech.append(mechanism_row("gravity wall, load factor, tan(phi) = 0.4", wall_s, "sliding", None))
    head = (
        "| scene | DOFs | F (holds) | fails at | closed form | F / closed - 1 | trials | contact iterations per trial | s per trial | factorisations |\n"
        "|---|---|---|---|---|---|---|---|---|---|"
    )
    mhead = "| scene | expected | named | agrees | toppling margin (blocks.csv) against (b/h) / tan(theta) |\n|---|---|---|---|---|"
    table = "\n".join([head, *rows]) + "\n\n" + "\n".join([mhead, *mech])
    print(table)
    (OUT / "safety.md").write_text("# make safety\n\n" + table + "\n")
    print(f"written to {OUT / 'safety.md'}", file=sys.stderr)


if __name__ == "__main__":
    main()
