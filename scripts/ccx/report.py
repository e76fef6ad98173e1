"""The CalculiX comparison's report: results/bench_ccx/ccx.{md,csv,json}.

What it is responsible for: turning the per-size records of bench_ccx.py into
one CSV row per run (subcontact or ccx, variant, threads) and a Markdown
report with two tables per the issue: wall times (ccx bonded and contact, with
iterations and increments; subcontact bonded and contact, total and solve =
condense + interface + recover) and accuracy (top-centre displacement of both
codes and their relative difference |u_ccx - u_sc| / |u_sc|, the largest
nodal difference off the joint over max |u_sc|, the slipping fraction of the
joint's nodes).
"""

from __future__ import annotations

import csv
import datetime
import json
import os
import pathlib
import platform
import subprocess

from deck import CONTACT_VARIANTS

CSV_FIELDS = ["lc", "divisions", "code", "variant", "threads", "dofs", "interface_dofs",
              "wall_s", "solve_s", "max_rss_mb", "iterations", "increments", "converged",
              "top_ux", "top_uy", "top_uz", "top_rel_diff", "field_max_rel_diff",
              "field_l2_rel_diff", "slip_nodes", "joint_nodes", "slip_fraction",
              "max_penetration", "contact_force_x", "contact_force_y", "contact_force_z",
              "load_before", "load_during_mean", "load_after"]


def rows(results: list[dict]) -> list[dict]:
    out = []
    for r in results:
        base = {"lc": r["lc"], "divisions": r["divisions"], "joint_nodes": r["joint_nodes"]}
        for tag, s in r["subcontact"].items():
            row = dict(base, code="subcontact", variant=tag.split("_t")[0],
                       threads=s["threads"], dofs=s["dofs"],
                       interface_dofs=s["interface_dofs"], wall_s=s["wall_s"],
                       solve_s=s["solve_s"], max_rss_mb=s["max_rss_mb"], converged=True,
                       load_before=s.get("load_before"), load_after=s.get("load_after"),
                       load_during_mean=s.get("load_during_mean"))
            row.update(zip(("top_ux", "top_uy", "top_uz"), s["top_centre"]))
            if "contact" in s:
                row["iterations"] = s["contact"]["iterations"]
                row["converged"] = s["contact"]["converged"]
                row["slip_nodes"] = s["slip"]["slip"]
                row["slip_fraction"] = s["slip"]["slip_fraction"]
            out.append(row)
        for job, c in r["ccx"].items():
            row = dict(base, code="ccx", variant=c["variant"], threads=c["threads"],
                       dofs=c["equations"], wall_s=c["wall_s"], max_rss_mb=c["max_rss_mb"],
                       converged=c["converged"], load_before=c.get("load_before"),
                       load_after=c.get("load_after"),
                       load_during_mean=c.get("load_during_mean"))
            if c.get("sta"):
                row["iterations"] = c["sta"]["iterations"]
                row["increments"] = c["sta"]["increments"]
            if c.get("top_centre"):
                row.update(zip(("top_ux", "top_uy", "top_uz"), c["top_centre"]))
                row["top_rel_diff"] = c.get("top_centre_rel_diff")
            if c.get("field_diff"):
                row["field_max_rel_diff"] = c["field_diff"]["max_rel"]
                row["field_l2_rel_diff"] = c["field_diff"]["l2_rel"]
            if c.get("contact_force"):
                row.update(zip(("contact_force_x", "contact_force_y", "contact_force_z"),
                               c["contact_force"]))
            if c.get("slip"):
                row["slip_nodes"] = c["slip"]["slip"]
                row["slip_fraction"] = c["slip"]["slip_fraction"]
                row["max_penetration"] = c["slip"]["max_penetration"]
            out.append(row)
    return out


def _g(x, fmt="{:.3g}"):
    return "–" if x is None or x == "" else fmt.format(x)


def _ccx_cell(r: dict, variant: str, threads) -> str:
    c = r["ccx"].get(f"{variant}_t{threads}")
    if c is None:
        return "–"
    if not c["converged"]:
        return f"failed ({_g(c['wall_s'], '{:.1f}')} s)"
    s = f"{c['wall_s']:.1f}"
    if variant != "bonded" and c.get("sta"):
        s += f" ({c['sta']['iterations']} it, {c['sta']['increments']} inc)"
    return s


def _ratio(t: float, c: dict | None) -> str:
    if c is None or not c["converged"]:
        return "–"
    return f"{t / c['wall_s']:.3f}"


def machine() -> str:
    ccx = subprocess.run(["ccx", "-v"], capture_output=True, text=True).stdout.strip()
    return (f"{platform.node()}, {os.cpu_count()} cores, {platform.machine()}; "
            f"{ccx.splitlines()[-1] if ccx else 'ccx'} (Debian calculix-ccx, SPOOLES)")


def write(out: pathlib.Path, results: list[dict], params: dict, args) -> None:
    table = rows(results)
    with open(out / "ccx.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, CSV_FIELDS, extrasaction="ignore")
        w.writeheader()
        w.writerows(table)
    (out / "ccx.json").write_text(json.dumps(results, indent=1))
    (out / "ccx.md").write_text(markdown(results, params, args))


def _threads_of(args, variant: str) -> list[int]:
    return args.stiff_threads if variant.endswith("_stiff") else args.threads


def _sc_cell(r: dict, tag: str, t: int) -> str:
    s = r["subcontact"].get(f"{tag}_t{t}")
    return "–" if s is None else f"{s['wall_s']:.2f} ({s['solve_s']:.2f})"


def markdown(results: list[dict], params: dict, args) -> str:
    variants = list(args.variants)
    t0 = args.threads[0]
    commits = {s.get("commit") or "?" for r in results for s in r["subcontact"].values()}
    L = ["# CalculiX 2.20 against subcontact: block on block, hex20", "",
         f"Written by `make bench-ccx` (scripts/ccx/bench_ccx.py) on "
         f"{datetime.date.today().isoformat()}; {machine()}; subcontact built from "
         f"{', '.join(sorted(commits))}.", "",
         f"Model: two blocks 1 x 1 x 0.5 (E = {params['young']:g}, nu = {params['poisson']:g}), "
         f"base fixed, top traction {tuple(params['traction'])} per unit area as consistent "
         f"nodal forces (resultant checked), joint friction {params['friction']:g}, no cohesion. "
         "Same gmsh mesh for both codes (`subcontact check`), structured hex20 (C3D20).", "",
         "CalculiX contact decks: `*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR` with "
         "K and `*FRICTION` with mu and the stick slope lambda (both force / length^3, "
         "here MPa / m), one `*STATIC` step (first increment 1.0, automatic cutbacks):", ""]
    for v in variants:
        o = CONTACT_VARIANTS[v]
        L.append(f"- `{v}`: TYPE={o['kind']}, K = {o['k_over_e']:g} E, "
                 f"lambda = {o['lambda_over_k']:g} K")
    L += ["", "Times are wall clock in seconds (`/usr/bin/time -v`). tN = N threads: ccx "
          "with OMP_NUM_THREADS = CCX_NPROC_EQUATION_SOLVER = N (SPOOLES); subcontact "
          "pinned to N cores (taskset; it condenses the two blocks side by side when it "
          "has two). subcontact cells: total (solve), solve = condense + interface + "
          "recover from summary.json; the total also reads the mesh, assembles and "
          "writes the results. ccx contact cells: total (Newton iterations, increments).",
          "", "## Wall time (s)", ""]
    head = ["lc (n)", "DOFs bonded / contact", "interface DOFs"]
    head += [f"subcontact bonded t{t}" for t in args.threads]
    head += [f"subcontact contact t{t}" for t in args.threads]
    head += [f"ccx bonded t{t}" for t in args.threads]
    head += [f"ccx {v} t{t}" for v in variants for t in _threads_of(args, v)]
    L += ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in results:
        sb, scn = r["subcontact"][f"bonded_t{t0}"], r["subcontact"][f"contact_t{t0}"]
        cells = [f"{r['lc']:g} ({r['divisions']})", f"{sb['dofs']:,} / {scn['dofs']:,}",
                 f"{scn['interface_dofs']:,}"]
        cells += [_sc_cell(r, "bonded", t) for t in args.threads]
        cells += [_sc_cell(r, "contact", t) for t in args.threads]
        cells += [_ccx_cell(r, "bonded", t) for t in args.threads]
        cells += [_ccx_cell(r, v, t) for v in variants for t in _threads_of(args, v)]
        L.append("| " + " | ".join(cells) + " |")
    L += ["", "## Against the issue's targets (wall time ratios, same thread count)", "",
          "| lc (n) | threads | sc contact / sc bonded (target <= 2) | sc bonded / ccx "
          "bonded (target <= 1/3) | " + " | ".join(f"sc contact / ccx {v} (target <= 1/10)"
                                                 for v in variants) + " |",
          "|" + "---|" * (4 + len(variants))]
    for r in results:
        for t in args.threads:
            sb = r["subcontact"].get(f"bonded_t{t}")
            scn = r["subcontact"].get(f"contact_t{t}")
            if sb is None or scn is None:
                continue
            cells = [f"{r['lc']:g} ({r['divisions']})", f"{t}",
                     f"{scn['wall_s'] / sb['wall_s']:.2f}",
                     _ratio(sb["wall_s"], r["ccx"].get(f"bonded_t{t}"))]
            cells += [_ratio(scn["wall_s"], r["ccx"].get(f"{v}_t{t}")) for v in variants]
            L.append("| " + " | ".join(cells) + " |")
    L += ["", "## Accuracy against subcontact on the same mesh", "",
          "Top centre = the node at (0.5, 0.5, 1). rel. diff = |u_ccx - u_sc| / |u_sc| there; "
          "field = max over the nodes off the joint of |u_ccx - u_sc| / max |u_sc|. "
          "Slip = joint nodes where the Coulomb bound is reached: subcontact's status "
          "'slip'; CalculiX (which writes no status) |CSHEAR| >= 0.99 mu CPRESS at the "
          "slave nodes (`*CONTACT FILE`). Penetration: CalculiX's largest -COPEN.", "",
          "| lc (n) | run | top ux | top uz | rel. diff | field | slip nodes / joint nodes | "
          "max penetration | iterations |", "|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        n = f"{r['lc']:g} ({r['divisions']})"
        for tag in ("bonded", "contact"):
            s = r["subcontact"][f"{tag}_t{t0}"]
            slip = (f"{s['slip']['slip']} / {r['joint_nodes']} "
                    f"({100 * s['slip']['slip_fraction']:.1f} %)" if "slip" in s else "–")
            it = s["contact"]["iterations"] if "contact" in s else "–"
            L.append(f"| {n} | subcontact {tag} | {s['top_centre'][0]:.5e} | "
                     f"{s['top_centre'][2]:.5e} | ref. | ref. | {slip} | 0 | {it} |")
        seen = set()
        for job, c in r["ccx"].items():
            if c["variant"] in seen or not c.get("converged"):
                continue          # one row per variant: the threads agree
            seen.add(c["variant"])
            sl = c.get("slip")
            slip = (f"{sl['slip']} / {r['joint_nodes']} ({100 * sl['slip_fraction']:.1f} %)"
                    if sl else "–")
            pen = _g(sl["max_penetration"]) if sl else "–"
            it = c["sta"]["iterations"] if c.get("sta") else "–"
            L.append(f"| {n} | ccx {c['variant']} | {c['top_centre'][0]:.5e} | "
                     f"{c['top_centre'][2]:.5e} | {_g(c.get('top_centre_rel_diff'))} | "
                     f"{_g(c.get('field_diff', {}).get('max_rel'))} | {slip} | {pen} | {it} |")
    L += ["", "## Runs that did not converge", ""]
    bad = [f"- lc {r['lc']:g}: {job} (exit {c['exit']}, see {job}.log)"
           for r in results for job, c in r["ccx"].items() if not c["converged"]]
    L += bad or ["none"]
    runs = [c for r in results for c in list(r["ccx"].values()) + list(r["subcontact"].values())]
    extra = [c["load_during_mean"] - c.get("threads", 1) for c in runs if "load_during_mean" in c]
    if extra:
        L += ["", f"Other work on the machine during the runs (1-minute load average "
              f"sampled every 5 s, less the run's own threads, mean per run): "
              f"{min(extra):.2f} to {max(extra):.2f} on 2 cores. Each run first waited up "
              f"to {args.max_wait:g} s for a load below {args.max_load:g}."]
    return "\n".join(L) + "\n"
