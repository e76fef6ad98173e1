#!/usr/bin/env python3
"""make bench-ccx: CalculiX 2.20 against subcontact on the same mesh and loads.

What it is responsible for, per element size lc (numbered steps below):

1. mesh the block-on-block scene (scripts/ccx/blocks3d_hex_bench.toml, the model
   of geo/blocks3d_hex.toml plus a top-centre probe) with `subcontact check`:
   structured hex20, the mesh subcontact itself solves;
2. run `subcontact solve` on that mesh, with contact and `--bonded`;
3. write CalculiX decks for the same model (deck.py): bonded (joint nodes
   shared) and frictional contact (joint nodes duplicated, a contact pair):
   - f2f:          face-to-face penalty, K = 50 E (CalculiX's own default for
                   hard contact, the top of the manual's "5 to 50 times the
                   E-modulus"), stick slope lambda = K / 100 (the manual's advice);
   - f2f_stiff:    face-to-face penalty, K = lambda = 500 E: near-rigid stick
                   and penetration, for the accuracy comparison;
   - mortar_stiff: TYPE=MORTAR with K = lambda = 500 E (small meshes only);
   K and lambda are in force / length^3: here MPa / m, with E in MPa;
4. run ccx on each deck under /usr/bin/time -v with OMP_NUM_THREADS (and
   CCX_NPROC_*) = 1 and 2, waiting for the machine to be idle first;
5. compare: top-centre displacement, the whole displacement field off the joint,
   how much of the joint slips; write results/bench_ccx/ccx.{md,csv,json}.

Usage: python3 scripts/ccx/bench_ccx.py [--lc 0.125,0.0833333333,0.0625]
       [--threads 1,2] [--variants f2f,f2f_stiff,mortar_stiff] [--reuse]
Each run's record is kept in results/bench_ccx/lc_<lc>/runs/*.json; --reuse
skips runs whose record exists (e.g. after an interrupted benchmark).
"""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import shutil
import sys
import threading
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.dont_write_bytecode = True       # no __pycache__ in scripts/ccx

import ccxout  # noqa: E402
import deck  # noqa: E402
import report  # noqa: E402
import subcontact_run as sc  # noqa: E402

VARIANTS = deck.CONTACT_VARIANTS
# files ccx 2.20 leaves in its working directory whatever the job's name
CCX_SCRATCH = ("contact.fbd", "slavtan.fbd", "intpoints.out", "slavintmortar.out", "spooles.out")


def parse_args(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--lc", default="0.125,0.0833333333,0.0625",
                   help="element sizes, comma-separated (w / lc divisions per side)")
    p.add_argument("--threads", default="1,2",
                   help="threads for ccx (OMP_NUM_THREADS) and cores for subcontact (taskset)")
    p.add_argument("--variants", default="f2f,f2f_stiff,mortar_stiff",
                   help=f"contact decks among {', '.join(VARIANTS)}")
    p.add_argument("--mortar-max-dofs", type=int, default=60000,
                   help="run mortar only up to this many DOFs")
    p.add_argument("--stiff-threads", default="1",
                   help="thread counts for the *_stiff variants (they are slow)")
    p.add_argument("--out", default="results/bench_ccx")
    p.add_argument("--bin", default="target/release/subcontact")
    p.add_argument("--scene", default=str(HERE / "blocks3d_hex_bench.toml"))
    p.add_argument("--geo", default="geo/blocks3d.geo")
    p.add_argument("--ccx", default="ccx")
    p.add_argument("--reuse", action="store_true", help="keep runs already recorded")
    p.add_argument("--rerun-busy", type=float, default=None, metavar="LOAD",
                   help="with --reuse, run again the records taken while the load average, "
                        "less the run's own threads, averaged more than LOAD")
    p.add_argument("--max-load", type=float, default=0.7,
                   help="wait until the 1-minute load average is below this before a run")
    p.add_argument("--max-wait", type=float, default=900.0,
                   help="seconds to wait for that, then run anyway (and say so)")
    p.add_argument("--timeout", type=float, default=7200.0, help="per ccx run, seconds")
    a = p.parse_args(argv)
    a.lc = [float(x) for x in a.lc.split(",")]
    a.threads = [int(x) for x in a.threads.split(",")]
    a.stiff_threads = [int(x) for x in a.stiff_threads.split(",")]
    a.variants = [v for v in a.variants.split(",") if v]
    for v in a.variants:
        if v not in VARIANTS:
            p.error(f"unknown variant {v!r}: choose among {', '.join(VARIANTS)}")
    for path in (a.bin, a.scene, a.geo):
        if not pathlib.Path(path).exists():
            p.error(f"{path} does not exist (run from the repository root after `make build`)")
    if not pathlib.Path("/usr/bin/time").exists():
        p.error("/usr/bin/time is missing: install the Debian package time")
    if shutil.which(a.ccx) is None:
        p.error(f"{a.ccx} is not on PATH: install the Debian package calculix-ccx")
    return a


def wait_idle(args) -> float:
    """Wait (bounded) for the 1-minute load average to fall below --max-load."""
    start = time.time()
    while os.getloadavg()[0] > args.max_load and time.time() - start < args.max_wait:
        time.sleep(10)
    load = os.getloadavg()[0]
    if load > args.max_load:
        print(f"  note: running with load average {load:.2f} (> {args.max_load})", flush=True)
    return load


class LoadSampler:
    """The 1-minute load average, sampled every few seconds while a run lasts."""

    def __init__(self, every: float = 5.0):
        self.samples: list[float] = []
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._loop, args=(every,), daemon=True)

    def _loop(self, every: float) -> None:
        while not self._stop.wait(every):
            self.samples.append(os.getloadavg()[0])

    def __enter__(self):
        self._thread.start()
        return self

    def __exit__(self, *exc):
        self._stop.set()
        self._thread.join()


def busy(rec: dict, limit: float) -> bool:
    """Did other work share the machine during the run? The load average during
    it, less the run's own threads, above limit (on average)."""
    own = rec.get("threads", 1)
    return rec.get("load_during_mean", 0.0) - own > limit


def recorded(path: pathlib.Path, args, run):
    """The record at path if --reuse and it exists (and, with --rerun-busy, was
    not taken on a busy machine); else run() and record it, with the load."""
    if args.reuse and path.exists():
        rec = json.loads(path.read_text())
        if args.rerun_busy is None or not busy(rec, args.rerun_busy):
            return rec
        print(f"  rerunning {path.stem}: load {rec['load_during_mean']:.2f} during it", flush=True)
    load = wait_idle(args)
    with LoadSampler() as sampler:
        result = run()
    result["load_before"] = load
    result["load_after"] = os.getloadavg()[0]
    if sampler.samples:
        result["load_during_mean"] = float(np.mean(sampler.samples))
        result["load_during_max"] = float(np.max(sampler.samples))
    path.write_text(json.dumps(result, indent=1))
    return result


def field_difference(points_sc, u_sc, mesh: deck.Mesh, u_ccx: dict[int, np.ndarray]) -> dict:
    """max |u_ccx - u_sc| / max |u_sc| and the relative l2 difference, off the joint."""
    index = {tuple(np.round(p, 9)): k for k, p in enumerate(mesh.points)}
    rows = [index[tuple(np.round(p, 9))] for p in points_sc]
    uc = np.array([u_ccx[r + 1] for r in rows])
    d = uc - u_sc
    return {"max_rel": float(np.abs(d).max() / np.abs(u_sc).max()),
            "l2_rel": float(np.linalg.norm(d) / np.linalg.norm(u_sc)), "nodes": len(rows)}


def run_size(args, lc: float, params: dict) -> dict:
    work = pathlib.Path(args.out) / f"lc_{lc:g}"
    (work / "runs").mkdir(parents=True, exist_ok=True)
    binary, template = pathlib.Path(args.bin), pathlib.Path(args.scene)
    print(f"lc = {lc:g}: meshing with `subcontact check`", flush=True)
    msh = work / "mesh.msh"
    if not (args.reuse and msh.exists()):
        msh = sc.make_mesh(binary, template, pathlib.Path(args.geo), work, lc)
    mesh = deck.read_mesh(msh, ("lower", "upper"), ("joint", "base", "top"))
    model = deck.Model(params["young"], params["poisson"], params["traction"], params["friction"])
    top = int(np.argmin(np.linalg.norm(mesh.points - [0.5, 0.5, 1.0], axis=1)))
    if np.linalg.norm(mesh.points[top] - [0.5, 0.5, 1.0]) > 1e-9:
        raise SystemExit(f"error: lc = {lc}: no node at the top centre (use an even w / lc)")
    joint_z = float(mesh.points[mesh.group_nodes("joint"), 2].mean())
    result = {"lc": lc, "divisions": int(round(1.0 / lc)), "elements":
              sum(len(h) for h in mesh.hexes.values()), "mesh_nodes": len(mesh.points),
              "joint_nodes": len(mesh.group_nodes("joint")), "subcontact": {}, "ccx": {}}

    # 2. subcontact, contact and bonded, on one core and on all (args.threads)
    for tag, bonded in (("contact", False), ("bonded", True)):
        for t in args.threads:
            print(f"  subcontact {tag} t{t}", flush=True)
            rec = recorded(work / "runs" / f"subcontact_{tag}_t{t}.json", args,
                           lambda: sc.solve(binary, template, msh, work, lc, bonded, t))
            vtu = pathlib.Path(rec["out"]) / f"scene_{tag}.vtu"
            rec["_field"] = sc.nodal_displacements(vtu, joint_z)
            result["subcontact"][f"{tag}_t{t}"] = rec

    # 3-4. CalculiX decks and runs
    decks = {"bonded": None}
    for v in args.variants:
        opt = VARIANTS[v]
        k = opt["k_over_e"] * params["young"]
        decks[v] = deck.ContactOptions(kind=opt["kind"], stiffness=k,
                                       stick_slope=opt["lambda_over_k"] * k)
    for name, opt in decks.items():
        inp = work / f"{name}.inp"
        facts = deck.write_deck(inp, mesh, model, opt, top, f"{name}, lc = {lc:g}")
        threads = args.stiff_threads if name.endswith("_stiff") else args.threads
        for t in threads:
            if name.startswith("mortar") and facts["equations"] > args.mortar_max_dofs:
                continue
            job = work / f"{name}_t{t}.inp"
            shutil.copyfile(inp, job)
            print(f"  ccx {job.stem} ({facts['equations']} equations)", flush=True)
            rec = recorded(work / "runs" / f"ccx_{job.stem}.json", args,
                           lambda: ccx_run(args, job, t, facts, model, top))
            result["ccx"][job.stem] = {**rec, "variant": name, "options": VARIANTS.get(name)}
            for junk in [job.with_suffix(e) for e in (".frd", ".12d", ".inp")] + \
                    [work / f for f in CCX_SCRATCH]:
                junk.unlink(missing_ok=True)

    # 5. compare with subcontact
    for job, rec in result["ccx"].items():
        ref = result["subcontact"][f"{'bonded' if rec['variant'] == 'bonded' else 'contact'}"
                                   f"_t{args.threads[0]}"]
        if rec.get("top_centre") is None:
            continue
        u, v = np.array(rec["top_centre"]), np.array(ref["top_centre"])
        rec["top_centre_rel_diff"] = float(np.linalg.norm(u - v) / np.linalg.norm(v))
        u_ccx = ccxout.parse_dat_displacements((work / job).with_suffix(".dat"))
        rec["field_diff"] = field_difference(*ref["_field"], mesh, u_ccx)
    for tag in result["subcontact"].values():
        tag.pop("_field", None)
    (work / "result.json").write_text(json.dumps(result, indent=1))
    return result


def ccx_run(args, job: pathlib.Path, threads: int, facts: dict, model, top: int) -> dict:
    """One ccx run and everything read from its files."""
    rec = ccxout.run_ccx(job, threads, args.ccx, args.timeout)
    rec.update({"equations": facts["equations"], "load_resultant": facts["load_resultant"]})
    sta = job.with_suffix(".sta")
    rec["sta"] = ccxout.parse_sta(sta) if sta.exists() else None
    cvg = job.with_suffix(".cvg")
    rec["cvg"] = ccxout.parse_cvg(cvg) if cvg.exists() else []
    rec["converged"] = bool(rec["log_ok"] and rec["exit"] == 0
                            and (rec["sta"] is None or rec["sta"]["reached_end"]))
    dat = job.with_suffix(".dat")
    if rec["converged"] and dat.exists():
        u = ccxout.parse_dat_displacements(dat)
        rec["top_centre"] = u[top + 1].tolist()
        rec["contact_force"] = ccxout.parse_dat_contact_force(dat)
    frd = job.with_suffix(".frd")
    if rec["converged"] and frd.exists() and "bonded" not in job.stem:
        c = ccxout.parse_frd_contact(frd)
        rec["slip"] = ccxout.slip_summary(c, model.friction, facts["joint_nodes"])
    return rec


def main(argv=None) -> int:
    args = parse_args(argv)
    params = sc.scene_params(pathlib.Path(args.scene))
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    results = [run_size(args, lc, params) for lc in args.lc]
    report.write(out, results, params, args)
    print(f"results in {out}/ccx.md, ccx.csv", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
