#!/usr/bin/env python3
"""make safety: the factor of safety against sliding by strength reduction
(issue 18) beside the closed forms, for docs/safety.md and the README.

- The rock wedge in a V-groove (geo/wedge.toml) on its default mesh
  (lc = 1) and a coarser one (lc = 2), and on its sharp crease (h0 = 0,
  no crevice, lc = 1), all with the bisection tolerance lowered to 1e-4,
  against Hoek & Bray's rigid-block factor
  F = sin(beta) / sin(xi / 2) * tan(phi) / tan(psi) (beta = 90 degrees for
  the symmetric wedge; xi = 90 degrees, the .geo's default; phi from the
  joints' friction; psi, the plunge of the line of intersection, from the
  turned gravity vector).
- The gravity dam (geo/dam.toml, `subcontact safety`: the scene has no
  [safety] table, so the defaults) against its base's limit equilibrium by
  hand from the base pairs of its own contact.csv at F = 1:
  F = (c A + N tan(phi)) / T, with N = -sum(sigma_n area) and T the
  magnitude of sum(tau area) over the closed pairs of the contact "base".

Each run's results stay in results/safety/<run>/; the table goes to stdout
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


def run(args: list[str]) -> dict:
    """Runs subcontact ARGS --out results/safety/<name> --quiet; its summary."""
    name = args[-1]
    out = OUT / pathlib.Path(name).stem
    cmd = [str(BIN), args[0], name, "--out", str(out), "--quiet"]
    print("$", " ".join(cmd[:3]), "...", file=sys.stderr)
    subprocess.run(cmd, cwd=ROOT, check=True)
    return json.loads((out / "summary.json").read_text())


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


def dam_by_hand(summary: dict) -> float:
    """(c A + N tan phi) / T of the dam's base from its contact.csv."""
    scene = tomllib.loads((ROOT / "geo/dam.toml").read_text())
    base = next(c for c in scene["contacts"] if c.get("group") == "base")
    n, t, area = 0.0, [0.0, 0.0], 0.0
    path = OUT / "dam/contact.csv"
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


def main() -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    rigid = rigid_wedge()
    rows = []
    for lc in (2.0, 1.0):
        summary = run(["solve", wedge_scene(lc)])
        rows.append(row(f"wedge in a V-groove, tet10 lc = {lc:g}", summary, rigid, "Hoek & Bray"))
    summary = run(["solve", wedge_scene(1.0, crease=True)])
    rows.append(row("wedge on its sharp crease (h0 = 0), tet10 lc = 1", summary, rigid, "Hoek & Bray"))
    dam = run(["safety", "geo/dam.toml"])
    rows.append(row("gravity dam, base", dam, dam_by_hand(dam), "f N / T by hand"))
    head = (
        "| scene | DOFs | F (holds) | fails at | closed form | F / closed - 1 | trials | contact iterations per trial | s per trial | factorisations |\n"
        "|---|---|---|---|---|---|---|---|---|---|"
    )
    table = "\n".join([head, *rows])
    print(table)
    (OUT / "safety.md").write_text("# make safety\n\n" + table + "\n")
    print(f"written to {OUT / 'safety.md'}", file=sys.stderr)


if __name__ == "__main__":
    main()
