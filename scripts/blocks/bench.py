#!/usr/bin/env python3
"""make bench-blocks: a jointed rock mass of 64, 512 and 1,000 blocks.

geo/rockmass.{geo,toml}: a 10 m cube cut by three orthogonal joint sets
into n^3 blocks (n = 4, 8, 10), transfinite hex20 (m elements per block
edge: 5 for 64 blocks, 2 for 512 and 1,000), one body group and one
contact group per joint set; gravity, then pressure with a shear on the
top (partial slip on many joints). Each size is
solved twice: with its contacts (the default interface, which takes the
sparse interface for many small blocks) and bonded (`--bonded`: one sparse
factorisation of the whole mesh, the reference cost). The table of
docs/blocks.md is written from the runs' summary.json: DOFs, interface
DOFs, parts, contact iterations per load step, the solve time (assembly,
condensation, interface and recovery: the run less meshing, model building
and output) of both runs and their ratio, the GMRES applications and the
peak memory (the process's peak resident set).

The 1,000-block mesh takes gmsh about a minute (OpenCASCADE fragments the
cube by 27 planes); both runs of a size share the directory OUT/n, so the
second reuses the first's mesh, and the contact run's results are kept.
About 8 minutes.

Usage: python3 scripts/blocks/bench.py [--sizes 4:5,8:2,10:2] [--out results/bench_blocks]
Writes OUT/blocks.{md,json}.
"""

from __future__ import annotations

import argparse
import json
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
BIN = ROOT / "target/release/subcontact"
SCENE = ROOT / "geo/rockmass.toml"
SETNUMBER = "setnumber = { n = 4, m = 2, hex = 1, serendipity = 1 }"


def scene_for(n: int, m: int, out: pathlib.Path) -> pathlib.Path:
    """geo/rockmass.toml at n blocks per edge and m elements per block edge, written in `out`."""
    text = SCENE.read_text()
    if SETNUMBER not in text:
        sys.exit(f"{SCENE} no longer sets {SETNUMBER!r}: update scripts/blocks/bench.py")
    text = text.replace(SETNUMBER, f"setnumber = {{ n = {n}, m = {m}, hex = 1, serendipity = 1 }}")
    text = text.replace('mesh = "rockmass.geo"', f'mesh = "{(ROOT / "geo/rockmass.geo").as_posix()}"')
    text = text.replace("64 blocks", f"{n ** 3} blocks")
    path = out / f"rockmass_{n}.toml"
    path.write_text(text)
    return path


def run(scene: pathlib.Path, out: pathlib.Path, extra: list[str]) -> dict:
    cmd = [str(BIN), "solve", str(scene), "--quiet", "--out", str(out), *extra]
    print(" ".join(cmd), flush=True)
    r = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if r.returncode != 0:
        return {"failed": r.stderr.strip()}
    s = json.loads((out / "summary.json").read_text())
    t = s["timings_s"]
    steps = [st["contact"]["iterations"] for st in s["steps"] if "contact" in st]
    return {
        "dofs": s["dofs"]["total"],
        "interface_dofs": s["dofs"]["interface"],
        "parts": s["parts"]["total"],
        "interface_solver": s.get("interface_solver", ""),
        "iterations": steps,
        "pairs": s.get("contact", {}).get("pairs", 0),
        "states": s.get("contact", {}).get("states", {}),
        "solve_s": t["assemble"] + t["condense"] + t["interface"] + t["recover"],
        "interface_s": t["interface"],
        "total_s": t["total"],
        "applications": s["counters"].get("interface_applications", 0),
        "peak_gb": max(r["peak_memory_bytes"] for r in s["ranks"]) / 1e9,
    }


def table(rows: list[dict]) -> str:
    lines = [
        "| blocks | DOFs (bonded) | interface DOFs | pairs | stick / slip / open | contact iterations per step | contact solve (s) | bonded solve (s) | ratio | GMRES applications | peak memory contact / bonded (GB) |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        c, b = r["contact"], r["bonded"]
        if "failed" in c or "failed" in b:
            lines.append(f"| {r['blocks']} | failed: {c.get('failed') or b.get('failed')} |||||||||")
            continue
        st = c["states"]
        lines.append(
            f"| {r['blocks']} | {c['dofs']:,} ({b['dofs']:,}) | {c['interface_dofs']:,} | {c['pairs']:,} | {st.get('stick', 0):,} / {st.get('slip', 0):,} / {st.get('open', 0):,} "
            f"| {' / '.join(map(str, c['iterations']))} | {c['solve_s']:.1f} | {b['solve_s']:.1f} | {c['solve_s'] / b['solve_s']:.1f} "
            f"| {c['applications']} | {c['peak_gb']:.2f} / {b['peak_gb']:.2f} |"
        )
    return "\n".join(lines) + "\n"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="4:5,8:2,10:2", help="n:m pairs: blocks per edge and elements per block edge")
    ap.add_argument("--out", default="results/bench_blocks")
    ap.add_argument("--table", action="store_true", help="only write the table again from OUT/blocks.json")
    args = ap.parse_args()
    out = ROOT / args.out
    out.mkdir(parents=True, exist_ok=True)
    if args.table:
        write(out, json.loads((out / "blocks.json").read_text()))
        return
    rows = []
    for nm in args.sizes.split(","):
        n, m = (int(x) for x in nm.split(":"))
        scene = scene_for(n, m, out)
        # bonded first: the contact run then reuses its cached mesh and its results stay
        bonded = run(scene, out / f"{n}", ["--bonded"])
        contact = run(scene, out / f"{n}", [])
        rows.append({"blocks": n ** 3, "n": n, "m": m, "contact": contact, "bonded": bonded})
        print(table(rows[-1:]), flush=True)
    write(out, rows)


def write(out: pathlib.Path, rows: list[dict]) -> None:
    (out / "blocks.json").write_text(json.dumps(rows, indent=1))
    md = "# A jointed rock mass of many blocks (make bench-blocks)\n\n" + table(rows)
    (out / "blocks.md").write_text(md)
    print(md)


if __name__ == "__main__":
    main()
