#!/usr/bin/env python3
"""make scaling: the measurements behind docs/scaling.md (issue 11, item 4).

One 3D scene (scripts/scaling/column.toml: a column on a column, hex8,
5.7e5 DOFs) run

- serially with 1 and 2 threads (the two parts condensed one after the other
  or side by side),
- on 1 and 2 MPI ranks (`mpirun -np N`, one thread per rank; needs the binary
  built with the cargo feature mpi, which `make scaling` builds),
- cut into K = 2, 4 substructures per body (`--substructures K`) with the
  dense interface, and 8 with --try-all: on this machine (24 GB) K = 8 was
  killed by the kernel at 24.4 GB while factorising its joins (a
  2.6e8-nonzero sparse matrix);
- cut into K = 2, 4, 8 with the iterative interface (no S formed, GMRES
  through the pieces' interior factors), serially and K = 8 on 2 MPI ranks.

From each run's summary.json: DOFs, interface DOFs, contact iterations, the
stage timings, the peak memory and bytes sent per rank. Writes
results/scaling/scaling.{md,json}; each run's results stay in
results/scaling/<run>/.

Usage: python3 scripts/scaling/scaling.py [--scene S] [--only NAME,...] [--try-all]
Runs already in results/scaling/scaling.json and not rerun are kept.
"""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
SERIAL = ROOT / "target/release/subcontact"
MPI = ROOT / "target/mpi/release/subcontact"
MPIRUN = ["mpirun", "--allow-run-as-root", "--oversubscribe", "--bind-to", "none"]
# runs made only with --try-all, and why
TOO_BIG = {"sub8_t2": "killed by the kernel at 24.4 GB on this machine (24 GB), factorising its joins"}


def runs(scene: str):
    """(name, command) of every run, in the order they are made."""
    solve = ["solve", scene, "--quiet"]
    yield "serial_t1", [str(SERIAL), *solve, "--threads", "1"]
    yield "serial_t2", [str(SERIAL), *solve, "--threads", "2"]
    yield "mpi_np1", [*MPIRUN, "-np", "1", str(MPI), *solve, "--threads", "1"]
    yield "mpi_np2", [*MPIRUN, "-np", "2", str(MPI), *solve, "--threads", "1"]
    for k in (2, 4, 8):
        yield f"sub{k}_t2", [str(SERIAL), *solve, "--threads", "2", "--substructures", str(k), "--interface", "dense"]
    for k in (2, 4, 8):
        yield f"sub{k}_iterative_t2", [str(SERIAL), *solve, "--threads", "2", "--substructures", str(k), "--interface", "iterative"]
    yield "mpi_np2_sub8_iterative", [*MPIRUN, "-np", "2", str(MPI), *solve, "--threads", "1", "--substructures", "8", "--interface", "iterative"]


def record(name: str, out: pathlib.Path, wall: float) -> dict:
    s = json.loads((out / "summary.json").read_text())
    ranks = s.get("ranks", [])
    return {
        "run": name,
        "wall_s": round(wall, 2),
        "dofs": s["dofs"]["total"],
        "interface_dofs": s["dofs"]["interface"],
        "parts": s["parts"]["total"],
        "iterations": s["contact"]["iterations"],
        "timings_s": s["timings_s"],
        "applications": s["counters"].get("interface_applications", 0),
        "ranks": ranks,
    }


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--scene", default=str(ROOT / "scripts/scaling/column.toml"))
    p.add_argument("--out", default=str(ROOT / "results/scaling"))
    p.add_argument("--only", default=None, help="comma-separated run names")
    p.add_argument("--try-all", action="store_true", help="also the runs known not to fit this machine")
    a = p.parse_args(argv)
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    only = set(a.only.split(",")) if a.only else None
    old = out / "scaling.json"
    kept = {r["run"]: r for r in json.loads(old.read_text())["runs"]} if old.exists() else {}
    table = []
    skipped = []
    for name, cmd in runs(a.scene):
        if only and name not in only:
            if name in kept:
                table.append(kept[name])
            continue
        if name in TOO_BIG and not a.try_all:
            skipped.append((name, TOO_BIG[name]))
            print(f"{name}: not run, {TOO_BIG[name]} (--try-all runs it)", flush=True)
            continue
        run_out = out / name
        cmd = [*cmd, "--out", str(run_out)]
        print(f"{name}: {' '.join(cmd)}", flush=True)
        t = time.perf_counter()
        r = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        wall = time.perf_counter() - t
        if r.returncode != 0:
            print(f"{name}: failed ({r.returncode})\n{r.stderr}", flush=True)
            skipped.append((name, f"failed with exit status {r.returncode}"))
            continue
        rec = record(name, run_out, wall)
        table.append(rec)
        print(f"  {wall:.1f} s, {rec['interface_dofs']} interface DOFs, {rec['iterations']} iterations", flush=True)
    (out / "scaling.json").write_text(json.dumps({"runs": table, "skipped": skipped}, indent=1))
    (out / "scaling.md").write_text(markdown(table, skipped))
    print(f"results in {out / 'scaling.md'}")
    return 0


def gb(b) -> str:
    return f"{b / 1e9:.2f}"


def markdown(table, skipped) -> str:
    lines = [
        "# Scaling runs: column on column, hex8",
        "",
        "Written by `make scaling` (scripts/scaling/scaling.py). Times in seconds (wall clock of the whole command; stages from summary.json), memory = peak resident set per rank (GB), bytes = sent by each rank (to rank 0: condensed operators and loads; from rank 0 at recovery: interface displacements; with the iterative interface, each application of S: the pieces' interface displacements out, S d back), applications = of every piece's S by the iterative interface (0: dense).",
        "",
        "| run | DOFs | interface DOFs | iterations | applications | wall | assemble | condense | interface | recover | peak memory per rank (GB) | bytes sent per rank (MB) | per contact iteration (MB) |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in table:
        t = r["timings_s"]
        ranks = r["ranks"]
        mem = " / ".join(gb(x["peak_memory_bytes"]) for x in ranks)
        sent = " / ".join(f"{x['bytes_sent'] / 1e6:.1f}" for x in ranks)
        per_it = " / ".join(f"{x['bytes_sent_per_contact_iteration'] / 1e6:.1f}" for x in ranks)
        lines.append(
            f"| {r['run']} | {r['dofs']:,} | {r['interface_dofs']:,} | {r['iterations']} | {r.get('applications', 0)} | {r['wall_s']:.1f} | "
            f"{t.get('assemble', 0):.1f} | {t.get('condense', 0):.1f} | {t.get('interface', 0):.1f} | {t.get('recover', 0):.1f} | {mem} | {sent} | {per_it} |"
        )
    if skipped:
        lines += ["", "Not run:", ""]
        for name, why in skipped:
            lines.append(f"- {name}: {why}")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    sys.exit(main())
