"""Running CalculiX and reading what it wrote.

What it is responsible for: one ccx run under ``/usr/bin/time -v`` (wall time,
max RSS) with a chosen thread count, and the parsing of its outputs:

* ``.sta``: the increments and the Newton iterations of each (convergence);
* ``.cvg``: the iterations with their residual and number of contact elements;
* ``.dat``: nodal displacements (``*NODE PRINT U``, the last block), and the
  slave surface's total force (``*CONTACT PRINT CF``);
* ``.frd`` (ASCII): the last ``CONTACT`` block at the slave nodes, i.e.
  COPEN, CSLIP1, CSLIP2, CPRESS, CSHEAR1, CSHEAR2 (ccx 2.20 writes no
  contact status). A slave node slips when |CSHEAR| >= 0.99 mu CPRESS with
  CPRESS > 0 (the Coulomb bound reached; below it the penalty stick law
  tau = lambda * slip holds).
"""

from __future__ import annotations

import os
import pathlib
import re
import subprocess

import numpy as np

SLIP_RATIO = 0.99


def run_ccx(job: pathlib.Path, threads: int, ccx: str = "ccx", timeout: float | None = None) -> dict:
    """Run ``ccx -i`` on the deck job (a .inp path) in its directory: wall time, max RSS."""
    env = dict(os.environ)
    for var in ("OMP_NUM_THREADS", "CCX_NPROC_EQUATION_SOLVER", "CCX_NPROC_STIFFNESS",
                "CCX_NPROC_RESULTS"):
        env[var] = str(threads)
    job = job.resolve()
    log = job.with_suffix(".log")
    timing = job.with_suffix(".time")
    with open(log, "w") as out:
        proc = subprocess.run(["/usr/bin/time", "-v", "-o", str(timing), ccx, "-i", job.stem],
                              cwd=job.parent, env=env, stdout=out, stderr=subprocess.STDOUT,
                              timeout=timeout)
    info = parse_time(timing.read_text())
    info["exit"] = proc.returncode
    text = log.read_text(errors="replace")
    info["log_ok"] = "Job finished" in text and "*ERROR" not in text
    m = re.search(r"Total CalculiX Time:\s*([0-9.eE+-]+)", text)
    info["ccx_time_s"] = float(m.group(1)) if m else None
    cpus = re.findall(r"Using up to (\d+) cpu\(s\) for spooles", text)
    info["spooles_cpus"] = int(cpus[-1]) if cpus else None
    info["threads"] = threads
    return info


def parse_time(text: str) -> dict:
    """``/usr/bin/time -v``: elapsed wall time (s) and maximum resident set size (MB)."""
    m = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\):\s*(\S+)", text)
    wall = None
    if m:
        parts = [float(p) for p in m.group(1).split(":")]
        wall = sum(p * 60 ** k for k, p in enumerate(reversed(parts)))
    m = re.search(r"Maximum resident set size \(kbytes\):\s*(\d+)", text)
    return {"wall_s": wall, "max_rss_mb": int(m.group(1)) / 1024 if m else None}


def parse_sta(path: pathlib.Path) -> dict:
    """Increments (converged ones), attempts and iterations from the .sta file."""
    incs = []
    for line in path.read_text().splitlines():
        f = line.split()
        if len(f) == 7 and all(re.fullmatch(r"[0-9.eE+-]+", x) for x in f):
            incs.append({"step": int(f[0]), "inc": int(f[1]), "att": int(f[2]),
                         "iterations": int(f[3]), "step_time": float(f[5])})
    done = bool(incs) and abs(incs[-1]["step_time"] - 1.0) < 1e-9
    return {"increments": len(incs), "iterations": sum(i["iterations"] for i in incs),
            "max_attempt": max((i["att"] for i in incs), default=0), "reached_end": done}


def parse_cvg(path: pathlib.Path) -> list[dict]:
    """Every Newton iteration: increment, attempt, contact elements, residual %."""
    rows = []
    for line in path.read_text().splitlines():
        f = line.split()
        if len(f) == 9 and f[0].isdigit():
            rows.append({"inc": int(f[1]), "att": int(f[2]), "iter": int(f[3]),
                         "contact_elements": int(f[4]), "resid_force_pct": float(f[5]),
                         "corr_disp_pct": float(f[6])})
    return rows


def parse_dat_displacements(path: pathlib.Path) -> dict[int, np.ndarray]:
    """The last ``displacements (vx,vy,vz)`` block of a .dat file: node id -> u."""
    blocks: list[dict[int, np.ndarray]] = []
    current = None
    for line in path.read_text().splitlines():
        if line.lstrip().startswith("displacements (vx,vy,vz)"):
            current = {}
            blocks.append(current)
            continue
        if current is None:
            continue
        f = line.split()
        if len(f) == 4 and f[0].isdigit():
            current[int(f[0])] = np.array([float(x) for x in f[1:]])
        elif f and not f[0].isdigit():
            current = None
    if not blocks:
        raise RuntimeError(f"{path}: no displacement block")
    return blocks[-1]


def parse_dat_contact_force(path: pathlib.Path) -> list[float] | None:
    """The slave surface's total force (fx, fy, fz), last occurrence."""
    lines = path.read_text().splitlines()
    out = None
    for k, line in enumerate(lines):
        if "total surface force (fx,fy,fz)" in line:
            for nxt in lines[k + 1:k + 4]:
                f = nxt.split()
                if len(f) == 6:
                    out = [float(x) for x in f[:3]]
                    break
    return out


def parse_frd_contact(path: pathlib.Path) -> dict[int, np.ndarray]:
    """The last CONTACT block of an ASCII .frd: node id -> (COPEN, CSLIP1, CSLIP2,
    CPRESS, CSHEAR1, CSHEAR2), for every node with a non-zero entry."""
    last: dict[int, np.ndarray] = {}
    current = None
    with open(path, errors="replace") as fh:
        for line in fh:
            if line.startswith(" -4  CONTACT"):
                current = {}
                last = current
            elif current is not None:
                if line.startswith(" -1"):
                    node = int(line[3:13])
                    vals = [float(line[13 + 12 * k:25 + 12 * k]) for k in range(6)]
                    if any(vals):
                        current[node] = np.array(vals)
                elif line.startswith(" -3"):
                    current = None
    return last


def slip_summary(contact: dict[int, np.ndarray], friction: float, joint_nodes: int) -> dict:
    """How much of the joint slips, by the Coulomb bound, at CalculiX's slave nodes."""
    if not contact:
        return {"nodes": 0, "pressed": 0, "slip": 0, "slip_fraction": None}
    c = np.array(list(contact.values()))
    p = c[:, 3]
    tau = np.hypot(c[:, 4], c[:, 5])
    pressed = p > 0
    slipping = pressed & (tau >= SLIP_RATIO * friction * p)
    slip_len = np.hypot(c[:, 1], c[:, 2])
    return {
        "nodes": int(len(c)),
        "pressed": int(pressed.sum()),
        "slip": int(slipping.sum()),
        "slip_fraction": float(slipping.sum() / joint_nodes),
        "open_nodes": int(joint_nodes - pressed.sum()),
        "max_cslip": float(slip_len.max()),
        "max_cpress": float(p.max()),
        "max_penetration": float(-c[:, 0].min()),
    }
