#!/usr/bin/env python3
"""Stability sweep: where does each method stop being stable?

Runs the paper scene (SPEC section 7) undamped over a fixed simulated time for dt/dt_critical
from 0.5 to 1.4, for the elastic body (no contact), P1 and P0 contact, frictionless, Tresca and
Coulomb (mu = 0.3), and the penalty method, and records whether each run stays bounded: exit status (the blow-up
guard stops a run whose kinetic energy exceeds 1000 x the work put in), the largest kinetic
energy over the largest external work, and max |u|. Writes stability.csv and stability.png in
--out; those already there are refused before any run (one line, exit 2) unless --force, and each is
written beside its name and moved into place (contact2d.outfile).

    /usr/bin/python3 postproc/stability_sweep.py [--level 2] [--out study/stability] [--reuse] [--force]

dt_critical is the element bound 2/omega_max (penalty: the penalty-adjusted bound); the power
iteration's estimate of the true limit is marked on the chart.
"""
import argparse
import csv
import sys

import numpy as np

from contact2d.h5 import Run
from contact2d.runner import ROOT, find_exe, out_dir, run, strip_group
from contact2d.outfile import refusal_exits, refuse_existing, replacing, save_figure

PROG = "stability_sweep.py"
METHODS = {
    # name: (deck, extra --set values, strip &contact)
    "elastic": ("baillet_sassi_2002_p1.nml", {}, True),
    "P1 frictionless": ("baillet_sassi_2002_p1.nml", {"contact:friction": "frictionless", "contact:threshold": 0.0}, False),
    "P1 Tresca": ("baillet_sassi_2002_p1.nml", {}, False),
    "P0 frictionless": ("baillet_sassi_2002_p0.nml", {"contact:friction": "frictionless", "contact:threshold": 0.0}, False),
    "P0 Tresca": ("baillet_sassi_2002_p0.nml", {}, False),
    "P1 Coulomb mu=0.3": ("baillet_sassi_2002_p1.nml", {"contact:friction": "coulomb", "contact:threshold": 0.0,
                                                       "contact:friction_coefficient": 0.3}, False),
    "P0 Coulomb mu=0.3": ("baillet_sassi_2002_p0.nml", {"contact:friction": "coulomb", "contact:threshold": 0.0,
                                                       "contact:friction_coefficient": 0.3}, False),
    "penalty k_p=1e6": ("baillet_sassi_2002_p1.nml", {"contact:method": "penalty", "contact:penalty_stiffness": 1.0e6,
                                                     "contact:friction": "frictionless", "contact:threshold": 0.0}, False),
}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", help="contact2d executable (default build/bin/contact2d)")
    ap.add_argument("--level", type=int, default=2, help="mesh level of the paper scene (default 2)")
    ap.add_argument("--time", type=float, default=2.0e-5, help="simulated time of each run [s] (default 2e-5)")
    ap.add_argument("--ratios", default="0.5:1.4:0.05", help="dt/dt_critical as start:stop:step")
    ap.add_argument("--out", default="study/stability", help="output directory")
    ap.add_argument("--reuse", action="store_true", help="keep finished runs")
    ap.add_argument("--methods", help="comma-separated subset of the method names (default: all)")
    ap.add_argument("--force", action="store_true",
                    help="replace stability.csv and stability.png already in --out (refused otherwise, before any run)")
    args = ap.parse_args()

    exe = find_exe(args.exe)
    out = out_dir(args.out, PROG)
    refuse_existing(PROG, [out / "stability.csv", out / "stability.png"], args.force)
    a, b, s = (float(x) for x in args.ratios.split(":"))
    ratios = np.round(np.arange(a, b + s / 2, s), 4)

    methods = METHODS
    if args.methods:
        wanted = [m.strip() for m in args.methods.split(",")]
        unknown = [m for m in wanted if m not in METHODS]
        if unknown:
            sys.exit("unknown method(s) %s; valid: %s" % (", ".join(unknown), ", ".join(METHODS)))
        methods = {m: METHODS[m] for m in wanted}
    rows = []
    for name, (deck, sets, strip) in methods.items():
        deck_path = ROOT / "inputs" / deck
        if strip:
            deck_path = out / ("elastic_" + deck)
            deck_path.write_text(strip_group((ROOT / "inputs" / deck).read_text(), "contact"))
        for r in ratios:
            tag = name.replace(" ", "_").replace("=", "") + f"_r{r:.2f}"
            h5 = out / f"{tag}.h5"
            all_sets = {"mesh:level": args.level, "solver:dt_factor": float(r), "solver:allow_unstable": True,
                        "solver:damping": "none", "solver:t_end": args.time, "solver:tol_residual": 1e-300,
                        "output:xdmf": False, "output:history_interval": 5, **sets}
            res = run(exe, deck_path, h5, all_sets, threads=1, reuse=args.reuse)
            if res.returncode not in (0, 2):
                sys.exit(f"{name} at {r}: contact2d failed: {res.stderr.strip()}")
            with Run(h5) as f:
                wext = np.abs(f.history("external_work"))
                # the staggered strain energy turns negative in an unstable mode: use the kinetic one
                growth = float(np.max(f.history("kinetic_energy")) / max(np.max(wext), 1e-300))
                umax = float(np.max(np.abs(f.displacement)))
                status = f.status
                limit = float(f.attr("dt_stable_estimate", np.nan) / f.attr("dt_critical"))
                steps = int(f.attr("steps"))
            bounded = status != "blow-up" and np.isfinite(growth)
            rows.append(dict(method=name, ratio=float(r), bounded=int(bounded), status=status, steps=steps,
                             kinetic_over_work=growth, max_abs_u=umax, power_limit=limit))
            print(f"{name:18s} dt/dt_crit = {r:4.2f}: {'bounded ' if bounded else 'BLOW-UP '} "
                  f"steps {steps:6d}  max E_kin / max W_ext = {growth:9.3e}  max|u| = {umax:9.3e} mm")

    csv_path = out / "stability.csv"
    with replacing(csv_path, args.force) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {csv_path}")
    print("\nlargest bounded dt/dt_critical and power-iteration limit per method:")
    for name in methods:
        rr = [r for r in rows if r["method"] == name]
        ok = [r["ratio"] for r in rr if r["bounded"]]
        print(f"  {name:18s} last bounded {max(ok) if ok else float('nan'):.2f}   "
              f"first blow-up {min([r['ratio'] for r in rr if not r['bounded']], default=float('nan')):.2f}   "
              f"power iteration {rr[0]['power_limit']:.3f}")
    plot(rows, out / "stability.png", args)


def plot(rows, path, args):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = list(dict.fromkeys(r["method"] for r in rows))
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8.5, 8), sharex=True)
    for k, name in enumerate(names):
        rr = [r for r in rows if r["method"] == name]
        x = np.array([r["ratio"] for r in rr])
        ok = np.array([r["bounded"] for r in rr], bool)
        ax1.scatter(x[ok], np.full(ok.sum(), k), marker="o", color="tab:green", s=30)
        ax1.scatter(x[~ok], np.full((~ok).sum(), k), marker="x", color="tab:red", s=40)
        lim = rr[0]["power_limit"]
        ax1.plot([lim, lim], [k - 0.35, k + 0.35], color="k", lw=2)
        g = np.array([r["kinetic_over_work"] for r in rr])
        ax2.semilogy(x, g, marker=".", label=name)
    ax1.set_yticks(range(len(names)), names)
    ax1.axvline(1.0, color="grey", ls=":")
    ax1.set_title(f"Paper scene, level {args.level}, undamped, {args.time:g} s: "
                  "o bounded, x blow-up, | power-iteration limit")
    ax2.axvline(1.0, color="grey", ls=":")
    ax2.set_xlabel("dt / dt_critical (element bound; penalty: penalty-adjusted)")
    ax2.set_ylabel("max kinetic energy / max |external work|")
    ax2.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, path, args.force, dpi=120)
    print(f"wrote {path}")


if __name__ == "__main__":
    with refusal_exits(PROG):
        main()
