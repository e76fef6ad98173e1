#!/usr/bin/env python3
"""How far a run's contact.csv is from the contact law, pair by pair.

    scripts/convergence/law.py SCENE.toml RESULTS_DIR

For every pair of contact.csv, with its group's strength from the scene
(friction f, cohesion c, residual_cohesion c_r, tensile_strength f_t), the
residual relative to the largest pair traction |(sigma_n, tau)|:
  stick: max(0, tau - (c - f sigma_n))        (inside the Coulomb cone;
         a cracked pair has c_r: the larger of the two is allowed)
         and max(0, sigma_n - f_t)
  slip:  |tau - max(0, c' - f sigma_n)|       (on the cone, c' = c or c_r)
  open:  |sigma_n| + tau and max(0, -gap / scale of the gaps)
Prints the worst residual per state and per group, exits 1 above --tol.
"""
import csv, json, math, sys
try:
    import tomllib
except ImportError:  # Python < 3.11
    import tomli as tomllib


def strengths(scene_path):
    scene = tomllib.load(open(scene_path, "rb"))
    out = {}
    for c in scene.get("contacts", []) + scene.get("joint_sets", []) + scene.get("joints", []):
        name = c.get("group") or c.get("name") or "+".join(c.get("groups", []))
        out[name] = dict(f=c.get("friction", 0.0), c=c.get("cohesion", 0.0),
                         cr=c.get("residual_cohesion", 0.0), ft=c.get("tensile_strength", 0.0),
                         frictionless=c.get("slip") == "frictionless")
    return out


def check(scene_path, results, tol=1e-6, quiet=False):
    law = strengths(scene_path)
    rows = list(csv.DictReader(open(f"{results}/contact.csv")))
    scale = max((math.hypot(float(r["sigma_n"]), math.hypot(float(r["tau_t"]), float(r["tau_b"]))) for r in rows), default=1.0) or 1.0
    gaps = max((abs(float(r["gap"])) for r in rows), default=1.0) or 1.0
    worst = {}
    for r in rows:
        g = r["contact"]
        s = law.get(g)
        if s is None:
            # a group given as groups = [a, b] is named by its first one
            s = next((v for k, v in law.items() if g in k.split("+")), None)
        if s is None:
            continue
        sn = float(r["sigma_n"]); tau = math.hypot(float(r["tau_t"]), float(r["tau_b"]))
        st = int(r["status"])
        if st == 2:
            cmax = max(s["c"], s["cr"])
            res = max(0.0, tau - (cmax - s["f"] * sn), sn - max(s["ft"], 0.0) if s["ft"] == 0 else 0.0)
            kind = "stick"
        elif st == 1:
            if s["frictionless"]:
                res = tau
            else:
                res = min(abs(tau - max(0.0, c - s["f"] * sn)) for c in (s["c"], s["cr"]))
            res = max(res, max(0.0, sn))
            kind = "slip"
        else:
            res = abs(sn) + tau + max(0.0, -float(r["gap"])) / gaps * scale
            kind = "open"
        res /= scale
        key = (kind, g)
        if res > worst.get(key, (0.0, None))[0] or key not in worst:
            worst[key] = (res, r["pair"])
    top = max((v[0] for v in worst.values()), default=0.0)
    if not quiet:
        for (kind, g), (res, pair) in sorted(worst.items()):
            print(f"  {g:>16} {kind:>5}: worst residual {res:.2e} (pair {pair})")
        print(f"law residual (relative to the largest traction {scale:.4g}): {top:.2e}")
    return top


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    tol = float(next((a.split("=")[1] for a in sys.argv[1:] if a.startswith("--tol=")), "1e-6"))
    r = check(args[0], args[1], tol)
    sys.exit(0 if r <= tol else 1)
