#!/usr/bin/env python3
"""Speed against accuracy: one line per route, the chart a user decides from (docs/performance.md).

    /usr/bin/python3 postproc/speed_accuracy.py [--levels 1-5] [--reference-dir study/paper]
                         [--hertz-levels 0-2] [--hertz-explicit-levels 0-1] [--calculix-levels 0-1]
                         [--penalties 1e8,1e9]
                         [--out study/speed_accuracy] [--figures DIR] [--no-getfem] [--no-hertz]
                         [--no-calculix] [--reuse] [--force]

Paper scene, routes (each run at every mesh level of --levels, P1 and P0 multipliers of
inputs/baillet_sassi_2002_p1.nml / _p0.nml):
  explicit            the shipped deck (tol_residual 1e-8), OMP_NUM_THREADS=1
  explicit tol 1e-10  solver:tol_residual = 1e-10, OMP_NUM_THREADS=1
  explicit tol 1e-3  solver:tol_residual = 1e-3, tol_kinetic = 1e-6 (kinetic energy goes with the
                      square of the out-of-balance), OMP_NUM_THREADS=1; tol 1e-2 likewise (1e-4)
  explicit mass x2    solver:mass_scaling = 2 x dt_critical (dt_critical of the shipped run at that
                      level), OMP_NUM_THREADS=1
  explicit all cores  the shipped deck, OMP_NUM_THREADS unset (every core)
  static              contact2d --static (the exact static solution of the discrete problem), 1 thread
  GetFEM static       postproc/getfem_reference.py on the shipped run's problem (assembly + solve time,
                      Python start-up excluded); left out with --no-getfem
CalculiX cannot pose the paper scene: its *FRICTION is Coulomb's law only, the scene is Tresca.

Two errors per run, both the relative energy-norm distance of the end state (contact2d.compare):
  error_reference  against the finest reference (the level-6 runs of postproc/paper_study.py when
                   --reference-dir has them, otherwise a --static run at level max+1 made here):
                   what a user gets
  error_same_mesh  against the --static run at the same level: what the solver adds to the
                   discretisation error (the static route's error_reference)

Hertz panel (left out with --no-hertz): inputs/hertz_cylinder_p1.nml (half-disk on a rigid plane,
frictionless, P1), routes named hertz_*: hertz_static at --hertz-levels; hertz_explicit (shipped),
hertz_explicit_tol1e-3 and hertz_explicit_mass2 as above at --hertz-explicit-levels (one level more
costs each explicit run 8x: twice the steps on four times the elements); CalculiX's static solve
(ccx, contact2d.calculix: the same mesh, CPE4, the rigid plane a held element layer, frictionless
node-to-surface penalty contact, pressure = slope x penetration) at --calculix-levels (level 2 takes
ccx minutes), one route per slope of --penalties [MPa/mm] (hertz_calculix_1e8, ...), drawn when ccx
is installed (otherwise one line says it is left out; --no-calculix leaves it out); its time is ccx's
wall time on the mesh written out (contact2d's includes meshing the .geo with Gmsh).
Both Hertz errors are relative L2 errors of the contact pressure on Gamma_c (contact2d.chart):
  error_reference  against 2D Hertz p0 sqrt(1 - x^2/a^2) with the run's own total force
  error_same_mesh  against the hertz_static run's pressure on the same mesh
CalculiX's pressure is recovered from its displacement as contact2d's P1 pressure is (M_c^-1 K u).

Filled markers: error_same_mesh < 0.1 x the discretisation error of that level (the static route's
error_reference, per panel).

Writes speed_accuracy.csv (route, multiplier, level, elements, wall_seconds, error_reference,
error_same_mesh) and speed_accuracy.png (wall time, log, against error_reference, log; the Pareto
front dashed) into --figures (default: --out). Those already there are refused before any run (one
line, exit 2) unless --force, and each is written beside its name and moved into place
(contact2d.outfile). --reuse keeps finished runs of the same settings (their timings too) and a
getfem_*.h5 that is a complete, converged reference of the same run's problem
(contact2d.runner.reference_problem); any other is recomputed, one line says why. CalculiX is always
run again.
"""
import argparse
import csv
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

from contact2d import calculix, hertz
from contact2d.chart import FIELDS, HERTZ, hertz_errors, pareto
from contact2d.h5 import Run
from contact2d.runner import ROOT, find_exe, keep_reference, levels_or_exit, out_dir, run
from contact2d.compare import compare
from contact2d.outfile import refusal_exits, refuse_existing, replacing, save_figure

TIGHT = 1e-10
# CalculiX's penalty slopes [MPa/mm]: p0 ~ 2e3 MPa gives 2e-5 and 2e-6 mm of penetration against delta =
# 0.05 mm; the penalty's own error falls as 1/slope
PENALTIES = "1e8,1e9"
# route, label, colour, marker
ROUTES = (("explicit", "explicit, shipped tol 1e-8, 1 thread", "C0", "o"),
          ("explicit_tol1e-10", "explicit, tol 1e-10, 1 thread", "C1", "v"),
          ("explicit_tol1e-3", "explicit, tol 1e-3 (kinetic 1e-6), 1 thread", "C5", "<"),
          ("explicit_tol1e-2", "explicit, tol 1e-2 (kinetic 1e-4), 1 thread", "C6", ">"),
          ("explicit_mass2", "explicit, mass scaling 2 dt_c, 1 thread", "C2", "^"),
          ("explicit_all_cores", "explicit, shipped tol, all cores", "C3", "D"),
          ("static", "contact2d --static, 1 thread", "k", "s"),
          ("getfem_static", "GetFEM static solve", "C4", "P"))
# the Hertz panel: route, label, colour, marker (CalculiX: one route per penalty slope, calculix_route())
HERTZ_ROUTES = (("hertz_explicit", "explicit, shipped tol 1e-8, 1 thread", "C0", "o"),
                ("hertz_explicit_tol1e-3", "explicit, tol 1e-3 (kinetic 1e-6), 1 thread", "C5", "<"),
                ("hertz_explicit_mass2", "explicit, mass scaling 2 dt_c, 1 thread", "C2", "^"),
                ("hertz_static", "contact2d --static, 1 thread", "k", "s"))


def calculix_route(penalty):
    """The CSV route name of CalculiX at one penalty slope [MPa/mm], e.g. hertz_calculix_1e8."""
    return "hertz_calculix_" + slope_text(penalty)


def slope_text(penalty):
    """A penalty slope as 1e8 (one significant digit, no '+0')."""
    return f"{penalty:.0e}".replace("e+0", "e").replace("e+", "e")


def calculix_routes(penalties):
    """The CalculiX routes of the Hertz panel: route, label, colour, marker."""
    return tuple((calculix_route(k), f"CalculiX static, penalty {slope_text(k)} MPa/mm, 1 thread", c, mk)
                 for k, c, mk in zip(penalties, ("C9", "C8", "C7", "C1"), ("X", "d", "h", "p")))


def cpu_name():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown CPU"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", help="contact2d executable (default build/bin/contact2d)")
    ap.add_argument("--levels", default="1-5", help="mesh levels, e.g. 1-5, 1,3 or 2 (default 1-5)")
    ap.add_argument("--reference-dir", default="study/paper", help="where paper_study.py left p1_k6.h5, p0_k6.h5")
    ap.add_argument("--out", default="study/speed_accuracy", help="folder of the runs (and of the products "
                                                                  "without --figures)")
    ap.add_argument("--figures", help="folder of speed_accuracy.csv and .png (default --out), e.g. docs/figures")
    ap.add_argument("--no-getfem", action="store_true")
    ap.add_argument("--hertz-levels", default="0-2", help="levels of hertz_static (default 0-2)")
    ap.add_argument("--hertz-explicit-levels", default="0-1",
                    help="levels of the explicit Hertz routes (default 0-1)")
    ap.add_argument("--calculix-levels", default="0-1", help="levels of the CalculiX routes (default 0-1)")
    ap.add_argument("--penalties", default=PENALTIES,
                    help=f"CalculiX's penalty slopes [MPa/mm], comma-separated, up to 4 (default {PENALTIES})")
    ap.add_argument("--no-hertz", action="store_true", help="leave the Hertz panel out")
    ap.add_argument("--no-calculix", action="store_true", help="leave the CalculiX route out")
    ap.add_argument("--reuse", action="store_true",
                    help="keep runs that finished with the same deck and settings (their timings too), and "
                         "GetFEM references that are complete and converged for the same run's problem")
    ap.add_argument("--force", action="store_true",
                    help="replace speed_accuracy.csv and .png already there (refused otherwise, before any run)")
    args = ap.parse_args()
    exe = find_exe(args.exe)
    levels = levels_or_exit(args.levels, "--levels", "speed_accuracy.py")
    hz_levels = levels_or_exit(args.hertz_levels, "--hertz-levels", "speed_accuracy.py")
    hz_explicit = levels_or_exit(args.hertz_explicit_levels, "--hertz-explicit-levels", "speed_accuracy.py")
    ccx_levels = levels_or_exit(args.calculix_levels, "--calculix-levels", "speed_accuracy.py")
    try:
        penalties = [float(v) for v in args.penalties.split(",")]
    except ValueError:
        penalties = []
    if not penalties or len(penalties) > 4 or not all(math.isfinite(k) and k > 0 for k in penalties):
        print(f"speed_accuracy.py: refused: --penalties '{args.penalties}': one to four finite slopes > 0 "
              "[MPa/mm], comma-separated, e.g. 1e8,1e9", file=sys.stderr)
        sys.exit(2)
    ccx = None if args.no_hertz or args.no_calculix else calculix.available()
    if ccx is None and not args.no_hertz and not args.no_calculix:
        print("CalculiX: ccx not installed (Debian: calculix-ccx), the calculix route is left out", flush=True)
    load_start = os.getloadavg()[0]
    out = out_dir(args.out, "speed_accuracy.py")
    figs = out_dir(args.figures, "speed_accuracy.py", "--figures") if args.figures else out
    refuse_existing("speed_accuracy.py", [figs / "speed_accuracy.csv", figs / "speed_accuracy.png"], args.force)
    all_cores = os.environ.pop("OMP_NUM_THREADS", None)   # unset for the all-cores route
    if all_cores is not None:
        print(f"OMP_NUM_THREADS={all_cores} unset for the all-cores route", flush=True)

    refs = {}
    for m in ("p1", "p0"):
        ref = Path(args.reference_dir) / f"{m}_k6.h5"
        if not ref.is_file() or levels[-1] >= 6:
            ref = out / f"ref_{m}_k{levels[-1] + 1}_static.h5"
            if not ref.is_file():
                print(f"making the reference {ref} (no {args.reference_dir}/{m}_k6.h5)", flush=True)
            res = run(exe, ROOT / "inputs" / f"baillet_sassi_2002_{m}.nml", ref,
                      {"mesh:level": levels[-1] + 1, "output:xdmf": False}, reuse=True, static=True)
            if res.returncode != 0:
                sys.exit(res.stderr)
        refs[m] = ref
    print(f"references: {refs['p1']}, {refs['p0']}", flush=True)

    rows = []
    for m in ("p1", "p0"):
        deck = ROOT / "inputs" / f"baillet_sassi_2002_{m}.nml"
        for k in levels:
            base = {"mesh:level": k, "output:xdmf": False}
            static_h5 = out / f"{m}_k{k}_static.h5"
            shipped_h5 = out / f"{m}_k{k}_explicit.h5"
            todo = [("static", static_h5, base, 1, True),
                    ("explicit", shipped_h5, base, 1, False),
                    ("explicit_tol1e-10", out / f"{m}_k{k}_tol1e-10.h5", {**base, "solver:tol_residual": TIGHT}, 1,
                     False),
                    ("explicit_tol1e-3", out / f"{m}_k{k}_tol1e-3.h5",
                     {**base, "solver:tol_residual": 1e-3, "solver:tol_kinetic": 1e-6}, 1, False),
                    ("explicit_tol1e-2", out / f"{m}_k{k}_tol1e-2.h5",
                     {**base, "solver:tol_residual": 1e-2, "solver:tol_kinetic": 1e-4}, 1, False),
                    ("explicit_mass2", out / f"{m}_k{k}_mass2.h5", None, 1, False),
                    ("explicit_all_cores", out / f"{m}_k{k}_all_cores.h5", base, None, False)]
            for route, h5, sets, threads, static in todo:
                if sets is None:                      # mass scaling: from the shipped run's dt_critical
                    with Run(shipped_h5) as r:
                        sets = {**base, "solver:mass_scaling": 2 * float(r.attrs["dt_critical"])}
                res = run(exe, deck, h5, sets, threads=threads, reuse=args.reuse, static=static)
                if res.returncode != 0:
                    sys.exit(f"{h5}: {res.stderr}")
                rows.append(row(route, m, k, h5, refs[m], static_h5))
            if not args.no_getfem:
                gf = out / f"getfem_{m}_k{k}.h5"
                if not keep_reference(gf, shipped_h5, args.reuse, friction="tresca"):
                    proc = subprocess.run(["/usr/bin/python3", str(ROOT / "postproc" / "getfem_reference.py"),
                                           str(shipped_h5), "-o", str(gf), "--force", "--friction", "tresca"],
                                          capture_output=True, text=True, env={**os.environ, "OMP_NUM_THREADS": "1"})
                    if proc.returncode != 0:
                        print(f"GetFEM {m} k={k}: {proc.stderr.strip()}")
                        continue
                rows.append(row("getfem_static", m, k, gf, refs[m], static_h5))

    if not args.no_hertz:
        rows += hertz_rows(exe, out, sorted(set(hz_levels) | set(hz_explicit) | set(ccx_levels)), hz_explicit,
                           ccx_levels if ccx else [], penalties, args.reuse)
    load = (load_start, os.getloadavg()[0])

    with replacing(figs / "speed_accuracy.csv", args.force) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=FIELDS)
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {figs / 'speed_accuracy.csv'}")
    # the caption's command: --force and --reuse left out (they change no number: a reused run is one
    # of the same settings, with its own timing)
    command = "/usr/bin/python3 postproc/speed_accuracy.py " + " ".join(a for a in sys.argv[1:]
                                                                        if a not in ("--force", "--reuse"))
    ccx_note = ("CalculiX: not drawn (--no-hertz)" if args.no_hertz else
                "CalculiX: not drawn (--no-calculix)" if args.no_calculix else
                "CalculiX: not drawn (no ccx installed)" if ccx is None else
                f"CalculiX {ccx_version()}: penalty " + " and ".join(slope_text(k) for k in penalties) + " MPa/mm")
    plot(rows, figs / "speed_accuracy.png", args.force, command, load, ccx_note, penalties)
    print_advice(rows)


def row(route, m, k, h5, ref, static_h5):
    with Run(h5) as r:
        wall = float(r.attrs["wall_seconds"])
    res = compare(h5, ref)
    err_ref = res["errors"]["energy"]
    elements = res["a"]["nx"] * res["a"]["ny"]
    err_same = compare(h5, static_h5)["errors"]["energy"]
    print(f"{m.upper()} k={k} {route:20s} {wall:9.3f} s  error: reference {err_ref:.3e}, same mesh {err_same:.3e}",
          flush=True)
    return dict(route=route, multiplier=m.upper(), level=k, elements=elements, wall_seconds=f"{wall:.6g}",
                error_reference=f"{err_ref:.6e}", error_same_mesh=f"{err_same:.6e}")


def hertz_rows(exe, out, levels, explicit_levels, ccx_levels, penalties, reuse):
    """The Hertz panel's rows: --static at every level, the explicit routes at explicit_levels,
    CalculiX at ccx_levels, each measured against Hertz and against --static on the same mesh."""
    deck = ROOT / "inputs" / "hertz_cylinder_p1.nml"
    rows = []
    for k in levels:
        base = {"mesh:level": k, "output:xdmf": False}
        static_h5 = out / f"hertz_p1_k{k}_static.h5"
        shipped_h5 = out / f"hertz_p1_k{k}_explicit.h5"
        todo = [("hertz_static", static_h5, base, True)]
        if k in explicit_levels:
            todo += [("hertz_explicit", shipped_h5, base, False),
                     ("hertz_explicit_tol1e-3", out / f"hertz_p1_k{k}_tol1e-3.h5",
                      {**base, "solver:tol_residual": 1e-3, "solver:tol_kinetic": 1e-6}, False),
                     ("hertz_explicit_mass2", out / f"hertz_p1_k{k}_mass2.h5", None, False)]
        for route, h5, sets, static in todo:
            if sets is None:
                with Run(shipped_h5) as r:
                    sets = {**base, "solver:mass_scaling": 2 * float(r.attrs["dt_critical"])}
            res = run(exe, deck, h5, sets, threads=1, reuse=reuse, static=static)
            if res.returncode != 0:
                sys.exit(f"{h5}: {res.stderr}")
            with Run(h5) as r:
                wall = float(r.attrs["wall_seconds"])
            rows.append(hertz_row(route, k, h5, static_h5, wall))
        if k in ccx_levels:
            for penalty in penalties:
                route = calculix_route(penalty)
                folder = out / f"{route[len(HERTZ):]}_k{k}"
                folder.mkdir(exist_ok=True)
                inp = folder / "hertz.inp"
                nnode = calculix.write_hertz_cylinder(static_h5, inp, penalty)
                try:
                    wall, _ = calculix.solve(inp)
                except calculix.CalculixFailed as exc:
                    print(f"CalculiX k={k}: {exc}", flush=True)
                    continue
                u = calculix.read_displacement(folder / "hertz.dat", nnode)
                rows.append(hertz_row(route, k, None, static_h5, wall, u, penalty))
    return rows


def hertz_row(route, k, h5, static_h5, wall, u=None, penalty=None):
    """A Hertz row: pressure errors against Hertz and against --static (contact2d.chart.hertz_errors).
    A contact2d run (h5) gives its own pressure; CalculiX's displacement u gives F_n = (K u)_y at the
    contact nodes and the P1 pressure M_c^-1 F_n."""
    with Run(static_h5) as r:
        x, conn, cn = r.coordinates, r.connectivity - 1, r.contact_nodes
        E, nu, _ = r.material
        p_static = r.contact("pressure")
        elements = int(r.attr("element_count"))
    xc = x[cn]
    if u is None:
        with Run(h5) as r:
            p, fn, kind = r.contact("pressure"), r.contact("normal_force"), str(r.attr("multiplier"))
        mult = kind
    else:
        fn = calculix.internal_forces(x, conn, u, E, nu)[cn, 1]
        p, kind, mult = hertz.p1_pressure(xc, fn), "P1", "penalty"
        print(f"   CalculiX k={k}: largest penetration {max(0.0, float(-np.min(xc[:, 1] + u[cn, 1]))):.3e} mm "
              f"(penalty law: max pressure / penalty = {float(np.max(p)) / penalty:.3e} mm)", flush=True)
    R = float(np.max(x[:, 1]) - np.min(x[:, 1]))          # the half-disk's radius (contact2d.hertz)
    err_ref, err_same = hertz_errors(xc, p, kind, 2 * float(np.sum(fn)), R, E, nu, p_static)
    print(f"HERTZ k={k} {route:24s} {wall:9.3f} s  pressure error: Hertz {err_ref:.3e}, same mesh {err_same:.3e}",
          flush=True)
    return dict(route=route, multiplier=mult, level=k, elements=elements, wall_seconds=f"{wall:.6g}",
                error_reference=f"{err_ref:.6e}", error_same_mesh=f"{err_same:.6e}")


def panel(r):
    """The chart panel of a row: 'P1', 'P0' (paper scene) or 'Hertz'."""
    return "Hertz" if r["route"].startswith(HERTZ) else r["multiplier"]


def discretisation(rows):
    """(panel, level) -> the static route's error against the reference (Hertz: against Hertz)."""
    return {(panel(r), r["level"]): float(r["error_reference"]) for r in rows
            if r["route"] in ("static", HERTZ + "static")}


def resolved(r, disc):
    d = disc.get((panel(r), r["level"]))
    return d is not None and float(r["error_same_mesh"]) < 0.1 * d


def ccx_version():
    try:
        out = subprocess.run([calculix.available(), "-v"], capture_output=True, text=True, timeout=30).stdout
    except (OSError, subprocess.SubprocessError):
        return "?"
    words = out.split()
    return words[words.index("Version") + 1] if "Version" in words else "?"


def print_advice(rows):
    disc = discretisation(rows)
    print("solver error / discretisation error (filled markers: < 0.1):")
    for m in ("P1", "P0", "Hertz"):
        for k in sorted({r["level"] for r in rows if panel(r) == m}):
            parts = [f"{r['route']} {float(r['error_same_mesh']) / disc[(m, k)]:.2e}" for r in rows
                     if panel(r) == m and r["level"] == k and not r["route"].endswith("static") and (m, k) in disc]
            print(f"  {m} k={k} (discretisation {disc.get((m, k), float('nan')):.3e}): " + ", ".join(parts))


def plot(rows, path, force, command, load, ccx_note, penalties):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    disc = discretisation(rows)
    panels = [m for m in ("P1", "P0", "Hertz") if any(panel(r) == m for r in rows)]
    # two by two: the paper scene's panels on top, Hertz below left, the legend below right
    fig = plt.figure(figsize=(14, 12.5))
    axes = []
    for i, m in enumerate(panels):
        share = axes[0] if m != "Hertz" and axes else None
        axes.append(fig.add_subplot(2, 2, i + 1, sharey=share))
    legend_ax = fig.add_subplot(2, 2, 4)
    legend_ax.axis("off")
    handles = {}
    for ax, m in zip(axes, panels):
        pts = []
        for route, label, color, mk in (HERTZ_ROUTES + calculix_routes(penalties) if m == "Hertz" else ROUTES):
            rs = sorted((r for r in rows if r["route"] == route and panel(r) == m), key=lambda r: r["level"])
            if not rs:
                continue
            x = [float(r["wall_seconds"]) for r in rs]
            y = [float(r["error_reference"]) for r in rs]
            pts += list(zip(x, y))
            ax.loglog(x, y, "-", color=color, lw=1.2, alpha=0.8)
            for r, xi, yi in zip(rs, x, y):
                filled = route.endswith("static") or resolved(r, disc)
                ax.loglog([xi], [yi], mk, color=color, ms=7, mfc=color if filled else "white", mew=1.4)
            handles[label] = plt.Line2D([], [], color=color, marker=mk, ms=7, lw=1.2)
            if route.endswith("static") and not route.startswith("getfem"):
                for r, xi, yi in zip(rs, x, y):
                    ax.annotate(f"k={r['level']}", (xi, yi), textcoords="offset points", xytext=(-4, -13),
                                fontsize=8, ha="right")
        front = pareto(pts)
        (h,) = ax.loglog([p[0] for p in front], [p[1] for p in front], "--", color="0.4", lw=2.5, alpha=0.45,
                         zorder=0)
        handles["Pareto front (fastest for its error)"] = h
        if m == "Hertz":
            ax.set_title("Hertz half-disk (P1, frictionless): pressure against Hertz")
            ax.set_ylabel("relative L2 error of the contact pressure against 2D Hertz (log)")
        else:
            ax.set_title(f"Paper scene, {m} multipliers: against the fine reference")
        ax.set_xlabel("wall time [s] (log)")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("relative energy-norm error against the fine reference (log)")
    handles["hollow: solver error > 0.1 x discretisation error"] = plt.Line2D([], [], color="0.3", marker="o",
                                                                               mfc="white", ls="none")
    handles["filled: solver error < 0.1 x discretisation error"] = plt.Line2D([], [], color="0.3", marker="o",
                                                                              ls="none")
    legend_ax.legend(list(handles.values()), list(handles), loc="center left", fontsize=10, frameon=False)
    threads = os.cpu_count()
    hz_levels = ", ".join(f"{name} {min(ks)}-{max(ks)}" for name, ks in
                          (("static", [r["level"] for r in rows if r["route"] == HERTZ + "static"]),
                           ("explicit", [r["level"] for r in rows if r["route"] == HERTZ + "explicit"]),
                           ("CalculiX", [r["level"] for r in rows if r["route"].startswith(HERTZ + "calculix")]))
                          if ks)
    caption = [f"Mesh levels k connected (labels at the static route). {cpu_name()}, {threads} cores, shared: load "
               f"average {load[0]:.1f} at the start, {load[1]:.1f} at the end (timings taken under that load). "
               f"1 thread (OMP_NUM_THREADS=1) except 'all cores' ({threads} threads).",
               "Paper scene (Tresca): errors in the energy norm; Hertz: relative L2 error of the pressure on Gamma_c. "
               "Solver error = distance to --static on the same mesh; discretisation error = the static route's error.",
               f"Hertz: inputs/hertz_cylinder_p1.nml, levels {hz_levels}; error against 2D Hertz with the run's own "
               f"force. {ccx_note} (Hertz only: CalculiX's friction is Coulomb's, the paper scene is Tresca);",
               "CalculiX's time is ccx's on the mesh written out (contact2d's includes meshing the .geo with Gmsh); its "
               "pressure is M_c^-1 K u, as contact2d's P1 pressure.",
               command]
    fig.text(0.01, 0.01, "\n".join(caption),
             fontsize=8, va="bottom")
    fig.tight_layout(rect=(0, 0.075, 1, 1))
    save_figure(fig, path, force, dpi=120)
    print(f"wrote {path}")


if __name__ == "__main__":
    with refusal_exits("speed_accuracy.py"):
        main()
