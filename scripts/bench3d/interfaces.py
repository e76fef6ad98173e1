#!/usr/bin/env python3
"""make bench-interface: the dense and the iterative interface on the same scenes.

Each scene is solved twice, `--interface dense` and `--interface iterative`
(2 threads), and the table of docs/bench3d.md ("Dense or iterative
interface") is written from the runs' summary.json: DOFs, interface DOFs,
contact iterations, total time, peak memory (the process's peak resident
set), applications of S, and the largest difference of the two runs'
contact stresses (contact.csv) relative to the largest stress.

Scenes: block on block (hex20, hex27, tet10 at 1.65e5 DOFs) and the 1.09e6-DOF
strip (its dense run alone takes about 9 minutes and 21.5 GB). The column cut
into substructures is in `make scaling`. About 20 minutes.

Usage: python3 scripts/bench3d/interfaces.py [--only NAME,...] [--modes dense,iterative]
Writes results/bench3d/interfaces.{md,json}; runs not rerun are kept.
"""

from __future__ import annotations

import argparse
import csv
import json
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
BIN = ROOT / "target/release/subcontact"
SCENES = [
    ("blocks3d_hex", "geo/blocks3d_hex.toml"),
    ("blocks3d_hex27", "scripts/bench3d/blocks3d_hex27.toml"),
    ("blocks3d_tet10", "scripts/bench3d/blocks3d_tet10.toml"),
    ("strip", "scripts/bench3d/strip.toml"),
]
MODES = ("dense", "iterative")


def run(name: str, scene: str, mode: str, out: pathlib.Path) -> dict:
    d = out / f"{name}_{mode}"
    cmd = [str(BIN), "solve", scene, "--quiet", "--threads", "2", "--interface", mode, "--out", str(d)]
    print(" ".join(cmd), flush=True)
    r = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if r.returncode != 0:
        return {"failed": r.stderr.strip().splitlines()[-1] if r.stderr.strip() else f"exit {r.returncode}"}
    s = json.loads((d / "summary.json").read_text())
    return {
        "dofs": s["dofs"]["total"],
        "interface_dofs": s["dofs"]["interface"],
        "iterations": s["contact"]["iterations"],
        "total_s": s["timings_s"]["total"],
        "peak_gb": max(r["peak_memory_bytes"] for r in s["ranks"]) / 1e9,
        "applications": s["counters"].get("interface_applications", 0),
        "per_solve": s["counters"].get("interface_applications_per_solve", []),
        "contact_csv": str(d / "contact.csv"),
    }


def stress_difference(a: str, b: str) -> float:
    """Largest difference of sigma_n, tau_t, tau_b between two contact.csv, relative to the largest."""
    rows = [list(csv.DictReader(open(p))) for p in (a, b)]
    keys = ("sigma_n", "tau_t", "tau_b")
    scale = max(abs(float(r[k])) for r in rows[0] for k in keys) or 1.0
    return max(abs(float(x[k]) - float(y[k])) for x, y in zip(*rows) for k in keys) / scale


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--out", default=str(ROOT / "results/bench3d"))
    p.add_argument("--only", default=None, help="comma-separated scene names")
    p.add_argument("--modes", default=",".join(MODES), help="comma-separated: dense, iterative")
    a = p.parse_args(argv)
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    old = out / "interfaces.json"
    results = json.loads(old.read_text()) if old.exists() else {}
    only = set(a.only.split(",")) if a.only else None
    for name, scene in SCENES:
        if only and name not in only:
            continue
        entry = results.setdefault(name, {})
        for mode in a.modes.split(","):
            entry[mode] = run(name, scene, mode, out)
        dense, it = entry.get("dense", {"failed": "not run"}), entry.get("iterative", {"failed": "not run"})
        entry.pop("stress_difference", None)
        if "failed" not in dense and "failed" not in it:
            entry["stress_difference"] = stress_difference(dense["contact_csv"], it["contact_csv"])
        old.write_text(json.dumps(results, indent=1))
    (out / "interfaces.md").write_text(markdown(results))
    print(f"results in {out / 'interfaces.md'}")
    return 0


def markdown(results: dict) -> str:
    lines = [
        "# Dense or iterative interface",
        "",
        "Written by `make bench-interface` (scripts/bench3d/interfaces.py): each scene solved with `--interface dense` and `--interface iterative`, 2 threads. Peak = the process's peak resident set.",
        "",
        "| scene | DOFs | interface DOFs | contact iterations | dense: total (s) / peak (GB) | iterative: total (s) / peak (GB) | applications of S (per contact iteration) | iterative / dense | contact stresses differ by |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for name, r in results.items():
        dense, it = r.get("dense", {"failed": "not run"}), r.get("iterative", {"failed": "not run"})
        ref = it if "failed" not in it else dense
        if "failed" in ref:
            lines.append(f"| {name} | – | – | – | {dense.get('failed', '')} | {it.get('failed', '')} | – | – | – |")
            continue
        cell = lambda x: x["failed"] if "failed" in x else f"{x['total_s']:.1f} / {x['peak_gb']:.2f}"
        ratio = f"{it['total_s'] / dense['total_s']:.2f}" if "failed" not in dense and "failed" not in it else "–"
        apps = f"{it.get('applications', 0)} ({', '.join(map(str, it.get('per_solve', [])))})" if "failed" not in it else "–"
        diff = f"{r['stress_difference']:.1e}" if "stress_difference" in r else "–"
        lines.append(
            f"| {name} | {ref['dofs']:,} | {ref['interface_dofs']:,} | {ref['iterations']} | {cell(dense)} | {cell(it)} | {apps} | {ratio} | {diff} |"
        )
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    sys.exit(main())
