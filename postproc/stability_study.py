#!/usr/bin/env python3
"""Where methods fail: penalty against multipliers, inf-sup loss, friction path, friction
only in contact, long undamped runs. The dt sweep is postproc/stability_sweep.py.

    /usr/bin/python3 postproc/stability_study.py all [--out study/stability] [--force]
    /usr/bin/python3 postproc/stability_study.py penalty|infsup|ramp|scope|longrun [--out ...]

Every part prints its figures and writes a CSV and a PNG into --out; docs/stability.md discusses
them. Runs are reused when their .h5 exists (pass --rerun to redo them). The CSVs and PNGs of the
parts asked for already in --out are refused before any run (one line, exit 2) unless --force;
each is written beside its name and moved into place (contact2d.outfile).
"""
import argparse
import csv
import sys

import numpy as np

from contact2d.h5 import Run
from contact2d.runner import ROOT, find_exe, out_dir, run
from contact2d.compare import compare
from contact2d.outfile import refusal_exits, refuse_existing, replacing, save_figure

E, NU, H, DELTA = 7.0e4, 0.3, 0.5, 1.0e-3
PRODUCTS = {"penalty": ("penalty.csv", "penalty.png"), "infsup": ("infsup.csv", "infsup.png"),
            "ramp": ("ramp.csv", "ramp.png"), "scope": ("scope.csv",), "longrun": ("longrun.csv",)}


def plt_module():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def write_csv(ctx, path, rows):
    with replacing(path, ctx.force) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {path}")


def go(ctx, deck, name, sets, allow_fail=False):
    """Run a deck (reusing a finished run) and return the output path."""
    h5 = ctx.out / (name + ".h5")
    res = run(ctx.exe, ROOT / "inputs" / deck, h5, {"output:xdmf": False, **sets}, threads=ctx.threads,
              reuse=not ctx.rerun)
    if res.returncode != 0 and not allow_fail:
        sys.exit(f"{name}: contact2d failed ({res.returncode}): {res.stderr.strip()}")
    return h5, res


# ---- penalty against multipliers ----------------------------------------------------------------

def penalty(ctx):
    """Penetration and stable dt against k_p (patch_compression), beside the multipliers."""
    rows = []
    kps = np.logspace(4, 9, 11)
    for kp in kps:
        h5, _ = go(ctx, "patch_compression_penalty.nml", f"penalty_kp{kp:.0e}", {"contact:penalty_stiffness": float(kp)})
        with Run(h5) as r:
            u = r.displacement
            pen = float(np.max(-u[r.contact_nodes, 1]))
            dtc = float(r.attrs["dt_critical"])
            dts = float(r.attrs["dt_stable_estimate"])
            conv = int(r.attrs["converged"])
        p = E * DELTA / (H * (1 - NU**2) + E / kp)
        rows.append(dict(method="penalty", k_p=kp, penetration=pen, predicted=p / kp, ratio=pen / (p / kp),
                         dt_critical=dtc, dt_power=dts, converged=conv))
    for m in ("p1", "p0"):
        h5, _ = go(ctx, f"patch_compression_{m}.nml", f"penalty_ref_{m}", {})
        with Run(h5) as r:
            u = r.displacement
            d = -u[r.contact_nodes, 1]
            if m == "p0":
                s = r.abscissa
                hseg = np.diff(s)
                dd = 3 * (np.r_[0, hseg] + np.r_[hseg, 0]) / 8
                Dd = dd * d
                Dd[:-1] += hseg / 8 * d[1:]
                Dd[1:] += hseg / 8 * d[:-1]
                pen = float(max(np.max(Dd / r.file["contact/weight"][()]), 0.0))
            else:
                pen = float(max(d.max(), 0.0))
            rows.append(dict(method=m.upper(), k_p=np.nan, penetration=pen, predicted=0.0, ratio=np.nan,
                             dt_critical=float(r.attrs["dt_critical"]), dt_power=float(r.attrs["dt_stable_estimate"]),
                             converged=int(r.attrs["converged"])))
    write_csv(ctx, ctx.out / "penalty.csv", rows)
    print(f"{'method':8s} {'k_p':>9s} {'penetration':>12s} {'p/k_p':>12s} {'ratio':>7s} {'dt_crit':>10s} {'dt_power':>10s}")
    for r in rows:
        print(f"{r['method']:8s} {r['k_p']:9.2e} {r['penetration']:12.4e} {r['predicted']:12.4e} {r['ratio']:7.4f} "
              f"{r['dt_critical']:10.3e} {r['dt_power']:10.3e}")

    # beyond the stable limit at the elastic dt: refused, diverges with the flag, stable when reduced
    dt_el = rows[-1]["dt_critical"] * 0.9
    kp = 1.0e8
    _, r1 = go(ctx, "patch_compression_penalty.nml", "penalty_refused",
               {"contact:penalty_stiffness": kp, "solver:dt": dt_el}, allow_fail=True)
    h5, r2 = go(ctx, "patch_compression_penalty.nml", "penalty_forced",
                {"contact:penalty_stiffness": kp, "solver:dt": dt_el, "solver:allow_unstable": True}, allow_fail=True)
    print(f"\nk_p = {kp:g} at the elastic dt = {dt_el:.3e} s: without the flag exit {r1.returncode} "
          f"({r1.stderr.strip()[:120]}...); with the flag exit {r2.returncode} ({r2.stderr.strip()[:80]}...)")

    plt = plt_module()
    pen_rows = [r for r in rows if r["method"] == "penalty"]
    k = np.array([r["k_p"] for r in pen_rows])
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.3))
    a1.loglog(k, [r["penetration"] for r in pen_rows], "o", label="penalty, measured")
    a1.loglog(k, [r["predicted"] for r in pen_rows], "k-", lw=0.8, label="p/k_p, p = E delta/(H(1-nu^2)+E/k_p)")
    for r, mk in zip([r for r in rows if r["method"] != "penalty"], ("s", "^")):
        a1.axhline(max(r["penetration"], 1e-20), ls=":", color="tab:green" if mk == "s" else "tab:red",
                   label=f"{r['method']} multipliers: {r['penetration']:.1e} mm")
    a1.set_xlabel("k_p [MPa/mm]")
    a1.set_ylabel("penetration [mm]")
    a1.set_title("patch_compression: penetration")
    a1.legend(fontsize=7)
    a2.loglog(k, [r["dt_critical"] for r in pen_rows], "o-", label="penalty dt_critical (nodal bound)")
    a2.loglog(k, [r["dt_power"] for r in pen_rows], "s--", mfc="none", label="penalty, power-iteration limit")
    lm = [r for r in rows if r["method"] == "P1"][0]
    a2.axhline(lm["dt_critical"], color="tab:green", ls=":", label="multipliers: elastic dt_critical")
    a2.axhline(lm["dt_power"], color="tab:green", ls="-.", lw=0.8, label="multipliers: power-iteration limit")
    a2.set_xlabel("k_p [MPa/mm]")
    a2.set_ylabel("stable time step [s]")
    a2.set_title("stable step")
    a2.legend(fontsize=7)
    fig.tight_layout()
    save_figure(fig, ctx.out / "penalty.png", ctx.force, dpi=120)
    print(f"wrote {ctx.out / 'penalty.png'}")


# ---- inf-sup loss -------------------------------------------------------------------------------

def oscillation(p, fraction=0.25):
    """Largest second difference |p_(i-1) - 2 p_i + p_(i+1)| over the first `fraction` of Gamma_c,
    relative to max p, and the number of local extrema there."""
    n = max(4, int(len(p) * fraction))
    q = p[:n]
    d2 = np.abs(q[:-2] - 2 * q[1:-1] + q[2:])
    sign = np.sign(np.diff(q))
    extrema = int(np.sum(sign[1:] * sign[:-1] < 0))
    return float(d2.max() / np.max(p)), extrema


def infsup(ctx):
    rows = []
    curves = {}
    for m in ("p1", "p0"):
        for level in (2, 3, 4, 5):
            for variant, sets in (("touching", {}), ("apart", {"dirichlet#1:ymin": 0.1, "dirichlet#2:ymin": 0.1})):
                h5, _ = go(ctx, f"infsup_loss_{m}.nml", f"infsup_{m}_{variant}_k{level}", {"mesh:level": level, **sets})
                with Run(h5) as r:
                    s, p = r.abscissa, r.contact("pressure")
                osc, ext = oscillation(p)
                rows.append(dict(multiplier=m.upper(), level=level, variant=variant, second_difference=osc,
                                 extrema_first_quarter=ext, p_first=float(p[0]), p_second=float(p[1])))
                curves[m, level, variant] = (s, p, r.attrs["multiplier"])
    write_csv(ctx, ctx.out / "infsup.csv", rows)
    for r in rows:
        print(f"{r['multiplier']} k={r['level']} {r['variant']:9s}: max |second difference| / max p = "
              f"{r['second_difference']:.3f}, local extrema in the first quarter {r['extrema_first_quarter']}")
    plt = plt_module()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.3), sharey=True)
    for ax, m in zip(axes, ("p1", "p0")):
        for level, ls in ((3, "-"), (5, "--")):
            for variant, color in (("touching", "tab:red"), ("apart", "tab:blue")):
                s, p, mult = curves[m, level, variant]
                if mult == "P0":
                    z = np.concatenate([[s[0]], 0.5 * (s[1:] + s[:-1]), [s[-1]]])
                    ax.plot(np.repeat(z, 2)[1:-1], np.repeat(p, 2), ls, color=color,
                            label=f"{variant}, level {level}")
                else:
                    ax.plot(s, p, ls, marker=".", ms=3, color=color, label=f"{variant}, level {level}")
        ax.set_xlim(0, 0.3)
        ax.set_title(f"{m.upper()}: pressure near the clamped corner")
        ax.set_xlabel("abscissa [mm]")
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("contact pressure [MPa]")
    fig.suptitle("Gamma_u touching Gamma_c (red) against the hypothesis of the paper (blue)")
    fig.tight_layout()
    save_figure(fig, ctx.out / "infsup.png", ctx.force, dpi=120)
    print(f"wrote {ctx.out / 'infsup.png'}")


# ---- friction path: end state against the ramp duration ---------------------------------------

def ramp(ctx):
    level = 3
    ramps = [0.25e-6, 0.5e-6, 1e-6, 2e-6, 4e-6, 8e-6, 16e-6, 32e-6]
    rows = []
    for m in ("p1", "p0"):
        files = {}
        for tr in ramps:
            h5, res = go(ctx, f"baillet_sassi_2002_{m}.nml", f"ramp_{m}_t{tr:.2e}",
                         {"mesh:level": level, "solver:t_ramp": tr, "solver:tol_residual": 1e-10})
            files[tr] = (h5, res.seconds)
        ref = files[ramps[-1]][0]
        for tr in ramps[:-1]:
            e = compare(files[tr][0], ref)["errors"]
            with Run(files[tr][0]) as r:
                steps, wall = int(r.attrs["steps"]), float(r.attrs["wall_seconds"])
                st = r.contact("status")
            with Run(ref) as r:
                st_ref = r.contact("status")
            rows.append(dict(multiplier=m.upper(), t_ramp=tr, energy=e["energy"], pressure_l2=e["pressure_l2"],
                             shear_l2=e["shear_l2"], status_differs=int(np.sum(st != st_ref)), steps=steps,
                             wall_seconds=wall))
    write_csv(ctx, ctx.out / "ramp.csv", rows)
    for r in rows:
        print(f"{r['multiplier']} t_ramp = {r['t_ramp']:.2e} s: energy-norm error {r['energy']:.2e}, pressure "
              f"{r['pressure_l2']:.2e}, shear {r['shear_l2']:.2e}, {r['status_differs']} statuses differ, "
              f"{r['steps']} steps")
    plt = plt_module()
    fig, ax = plt.subplots(figsize=(6.5, 4.3))
    for m, color in (("P1", "tab:blue"), ("P0", "tab:orange")):
        rr = [r for r in rows if r["multiplier"] == m]
        t = [r["t_ramp"] for r in rr]
        ax.loglog(t, [r["energy"] for r in rr], "o-", color=color, label=f"{m} displacement (energy norm)")
        ax.loglog(t, [r["shear_l2"] for r in rr], "s--", color=color, mfc="none", label=f"{m} shear (L2)")
    ax.set_xlabel("ramp duration t_ramp [s]")
    ax.set_ylabel(f"relative error against t_ramp = {ramps[-1]:g} s")
    ax.set_title(f"Friction path: paper scene, level {level}")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    fig.tight_layout()
    save_figure(fig, ctx.out / "ramp.png", ctx.force, dpi=120)
    print(f"wrote {ctx.out / 'ramp.png'}")


# ---- friction only where in contact -----------------------------------------------------------

def scope(ctx):
    level = 3
    rows = []
    for m in ("p1", "p0"):
        for sc in ("all", "contact"):
            h5, res = go(ctx, f"baillet_sassi_2002_{m}.nml", f"scope_{m}_{sc}",
                         {"mesh:level": level, "contact:tresca_scope": sc, "solver:t_end": 2.0e-4,
                          "solver:tol_residual": 1e-10}, allow_fail=True)
            with Run(h5) as r:
                t = r.history("time")
                ch = r.history("status_changes")
                tr = float(r.deck["solver"]["t_ramp"])
                late = t > 2 * tr
                rows.append(dict(multiplier=m.upper(), tresca_scope=sc, converged=int(r.attrs["converged"]),
                                 steps=int(r.attrs["steps"]), final_residual=float(r.history("residual")[-1]),
                                 status_changes_total=int(ch.sum()), status_changes_after_2_ramps=int(ch[late].sum()),
                                 last_change_time=float(t[ch > 0].max()) if np.any(ch > 0) else 0.0))
    write_csv(ctx, ctx.out / "scope.csv", rows)
    for r in rows:
        print(f"{r['multiplier']} tresca_scope = {r['tresca_scope']:7s}: converged {r['converged']}, {r['steps']} steps, "
              f"residual {r['final_residual']:.2e}, status changes {r['status_changes_total']} "
              f"({r['status_changes_after_2_ramps']} after t = 2 t_ramp), last at t = {r['last_change_time']:.3e} s")


# ---- long undamped runs --------------------------------------------------------------------------

def longrun(ctx):
    # a fast ramp (a quarter of the lowest period) leaves the undamped body vibrating hard
    level, steps, t_ramp = 1, 1_000_000, 2.5e-7
    rows = []
    for m in ("p1", "p0"):
        # omega_1 of the scene with contact: the automatic damping's estimate at convergence
        h5, _ = go(ctx, f"baillet_sassi_2002_{m}.nml", f"long_{m}_omega", {"mesh:level": level})
        with Run(h5) as r:
            omega1 = float(r.history("damping_alpha")[-1]) / 2
        h5, res = go(ctx, f"baillet_sassi_2002_{m}.nml", f"long_{m}",
                     {"mesh:level": level, "solver:damping": "none", "solver:max_steps": steps, "solver:t_end": 1.0,
                      "solver:t_ramp": t_ramp, "solver:tol_residual": 1e-300, "output:history_interval": 1000})
        with Run(h5) as r:
            t = r.history("time")
            bal = r.history("energy_balance_error")
            ch = r.history("status_changes")
            pen = r.history("penetration_max")
            kin = r.history("kinetic_energy")
            wn = r.history("normal_contact_work")
            wext = r.history("external_work")
            nc = len(r.contact_nodes)
            dt = float(r.attrs["dt"])
            wall = float(r.attrs["wall_seconds"])
        period = 2 * np.pi / omega1
        hold = t > t_ramp                                 # after the ramp: free vibration
        periods = (t[hold][-1] - t[hold][0]) / period
        rows.append(dict(multiplier=m.upper(), steps=int(round(t[-1] / dt)), simulated_time=float(t[-1]),
                         lowest_period=period, periods=periods, wall_seconds=wall,
                         balance_error_max=float(bal.max()), balance_error_end=float(bal[-1]),
                         kinetic_fraction_end=float(kin[-1] / wext[-1]),
                         normal_work_fraction=float(wn[-1] / wext[-1]),
                         flips_per_node_per_period=float(ch[hold].sum() / nc / periods),
                         penetration_first_period=float(pen[hold][t[hold] < t[hold][0] + period].max()),
                         penetration_last_period=float(pen[hold][t[hold] > t[hold][-1] - period].max())))
    write_csv(ctx, ctx.out / "longrun.csv", rows)
    for r in rows:
        print(f"{r['multiplier']}: {r['steps']} undamped steps ({r['periods']:.0f} periods of the lowest mode, "
              f"{r['wall_seconds']:.1f} s): balance error max {r['balance_error_max']:.2e}, kinetic/W_ext at the end "
              f"{r['kinetic_fraction_end']:.3f}, impact losses W_normal/W_ext {r['normal_work_fraction']:.2e}, "
              f"status flips per node per period {r['flips_per_node_per_period']:.3f}, penetration "
              f"{r['penetration_first_period']:.2e} mm (first period) -> {r['penetration_last_period']:.2e} mm (last)")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("part", choices=["penalty", "infsup", "ramp", "scope", "longrun", "all"])
    ap.add_argument("--exe", help="contact2d executable (default build/bin/contact2d)")
    ap.add_argument("--out", default="study/stability", help="output directory")
    ap.add_argument("--threads", type=int, default=1, help="OMP_NUM_THREADS of the runs (default 1)")
    ap.add_argument("--rerun", action="store_true", help="redo runs even if their .h5 exists")
    ap.add_argument("--force", action="store_true",
                    help="replace the parts' CSVs and PNGs already in --out (refused otherwise, before any run)")
    ctx = ap.parse_args()
    ctx.exe = find_exe(ctx.exe)
    ctx.out = out_dir(ctx.out, "stability_study.py")
    parts = list(PRODUCTS) if ctx.part == "all" else [ctx.part]
    refuse_existing("stability_study.py", [ctx.out / name for part in parts for name in PRODUCTS[part]], ctx.force)
    for part in parts:
        print(f"\n=== {part} ===")
        globals()[part](ctx)


if __name__ == "__main__":
    with refusal_exits("stability_study.py"):
        main()
