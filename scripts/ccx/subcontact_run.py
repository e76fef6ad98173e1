"""The subcontact side of the CalculiX comparison.

What it is responsible for: writing the per-size scene files (the template
scripts/ccx/blocks3d_hex_bench.toml with its `mesh` and `lc` rewritten),
meshing them with `subcontact check` (so the mesh is the one subcontact makes),
running `subcontact solve` with and without `--bonded` under ``/usr/bin/time -v``,
and reading summary.json, probes.csv, contact.csv and the bodies' VTU.

The joint slips where the pair's status is 1 (slip); for the same test as on
CalculiX's side, also where tau >= 0.99 mu |sigma_n| with sigma_n < 0.
"""

from __future__ import annotations

import csv
import json
import os
import pathlib
import re
import shutil
import subprocess
import tomllib

import numpy as np

from ccxout import SLIP_RATIO, parse_time


def scene_params(template: pathlib.Path) -> dict:
    """E, nu, friction and the top traction, read from the scene (not restated)."""
    s = tomllib.loads(template.read_text())
    (mat,) = s["materials"].values()
    (contact,) = s["contacts"]
    (load,) = [ld for ld in s["loads"] if ld["group"] == "top"]
    return {"young": mat["E"], "poisson": mat["nu"], "friction": contact["friction"],
            "traction": tuple(load["traction"]), "lc": s["gmsh"]["setnumber"]["lc"]}


def write_scene(template: pathlib.Path, dest: pathlib.Path, mesh: pathlib.Path, lc: float) -> None:
    """The template with `mesh` pointing at mesh (relative to dest) and lc set
    (the [gmsh] table dropped when mesh is a ready .msh)."""
    text = template.read_text()
    rel = os.path.relpath(mesh.resolve(), dest.parent.resolve())
    text, n1 = re.subn(r'(?m)^mesh = ".*"$', f'mesh = "{rel}"', text)
    text, n2 = re.subn(r"lc = [0-9.eE+-]+", f"lc = {lc!r}", text)
    if (n1, n2) != (1, 1):
        raise SystemExit(f"error: {template}: expected one `mesh = ...` line and one lc")
    if mesh.suffix == ".msh":
        # a ready mesh takes no [gmsh] options
        text = re.sub(r"(?ms)^\[gmsh\]\n.*?(?=^\[)", "", text)
    dest.write_text(text)


def make_mesh(binary: pathlib.Path, template: pathlib.Path, geo: pathlib.Path,
              workdir: pathlib.Path, lc: float) -> pathlib.Path:
    """Mesh the scene at lc exactly as subcontact does (`subcontact check`)."""
    scene = workdir / "scene_geo.toml"
    write_scene(template, scene, geo, lc)
    subprocess.run([str(binary.resolve()), "check", scene.name], cwd=workdir, check=True,
                   stdout=subprocess.DEVNULL)
    made = workdir / "results" / scene.stem / "mesh" / f"{scene.stem}.msh"
    msh = workdir / "mesh.msh"
    shutil.copyfile(made, msh)
    shutil.copyfile(made.with_suffix(".msh.key"), workdir / "mesh.msh.key")
    shutil.rmtree(workdir / "results")
    return msh


def solve(binary: pathlib.Path, template: pathlib.Path, msh: pathlib.Path,
          workdir: pathlib.Path, lc: float, bonded: bool, threads: int) -> dict:
    """One `subcontact solve` on the given mesh; wall time, RSS and its summary.
    subcontact takes as many threads as the process may use cores (it condenses
    the parts side by side), so threads = 1 pins it to one core (taskset)."""
    tag = "bonded" if bonded else "contact"
    scene = workdir / f"scene_{tag}.toml"
    write_scene(template, scene, msh, lc)
    out = workdir / f"subcontact_{tag}_t{threads}"
    cmd = [str(binary.resolve()), "solve", scene.name, "--out", out.name, "--quiet"]
    if bonded:
        cmd.append("--bonded")
    cores = sorted(os.sched_getaffinity(0))
    if threads > len(cores):
        raise SystemExit(f"error: {threads} threads asked for subcontact, {len(cores)} cores here")
    pin = ["taskset", "-c", ",".join(str(c) for c in cores[:threads])]
    timing = (workdir / f"subcontact_{tag}_t{threads}.time").resolve()
    subprocess.run(pin + ["/usr/bin/time", "-v", "-o", str(timing)] + cmd, cwd=workdir,
                   check=True)
    info = parse_time(timing.read_text())
    info["threads"] = threads
    summary = json.loads((out / "summary.json").read_text())
    t = summary["timings_s"]
    info.update({
        "dofs": summary["dofs"]["total"],
        "interface_dofs": summary["dofs"]["interface"],
        "timings_s": t,
        "solve_s": t["condense"] + t["interface"] + t["recover"],
        "top_centre": top_centre(out / "probes.csv"),
        "out": str(out),
        "commit": git_commit(binary),
    })
    if not bonded:
        c = summary["contact"]
        info["contact"] = {"iterations": c["iterations"], "converged": c["converged"],
                           "states": c["states"], "pairs": c["pairs"]}
        info["slip"] = slip_summary(out / "contact.csv", scene_params(template)["friction"])
    return info


def git_commit(binary: pathlib.Path) -> str | None:
    """The last commit that changed the code the binary was built from (src/,
    Cargo.*) in the checkout it sits in, with -dirty if src/ has local edits."""
    def git(*a):
        return subprocess.run(["git", *a], capture_output=True, text=True, check=True,
                              cwd=binary.resolve().parent).stdout.strip()
    try:
        commit = git("log", "-1", "--format=%h", "--", ":/src", ":/Cargo.toml", ":/Cargo.lock")
        dirty = git("status", "--porcelain", "--", ":/src", ":/Cargo.toml", ":/Cargo.lock")
        return (commit + ("-dirty" if dirty else "")) or None
    except (OSError, subprocess.CalledProcessError):
        return None


def top_centre(probes: pathlib.Path) -> list[float]:
    """The displacement at (0.5, 0.5, 1) from the `top_centre` probe."""
    with open(probes) as fh:
        for row in csv.DictReader(fh):
            x = (float(row["x"]), float(row["y"]), float(row["z"]))
            if row["probe"] == "top_centre" and np.allclose(x, (0.5, 0.5, 1.0)):
                if row["found"] != "true":
                    raise SystemExit(f"error: {probes}: the top-centre probe was not found")
                return [float(row["ux"]), float(row["uy"]), float(row["uz"])]
    raise SystemExit(f"error: {probes}: no top_centre probe at (0.5, 0.5, 1)")


def slip_summary(contact_csv: pathlib.Path, friction: float) -> dict:
    """Slipping pairs by status and by the Coulomb bound, over all joint pairs."""
    with open(contact_csv) as fh:
        rows = list(csv.DictReader(fh))
    status = np.array([int(r["status"]) for r in rows])
    sn = np.array([float(r["sigma_n"]) for r in rows])
    tau = np.hypot([float(r["tau_t"]) for r in rows], [float(r["tau_b"]) for r in rows])
    bound = (sn < 0) & (tau >= SLIP_RATIO * friction * -sn)
    return {"pairs": len(rows), "slip": int((status == 1).sum()),
            "slip_fraction": float((status == 1).mean()),
            "slip_by_bound": int(bound.sum()), "open": int((status == 0).sum())}


def nodal_displacements(vtu: pathlib.Path, joint_z: float) -> tuple[np.ndarray, np.ndarray]:
    """Points and displacements of the bodies' VTU, the joint plane left out
    (there each body has its own copy of the node)."""
    import meshio

    m = meshio.read(str(vtu))
    keep = np.abs(m.points[:, 2] - joint_z) > 1e-9
    return m.points[keep], np.asarray(m.point_data["displacement"])[keep]
