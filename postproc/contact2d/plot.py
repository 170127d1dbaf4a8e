"""Plot one contact2d run: contact fields along Gamma_c and histories against time (PNG).

    python3 postproc/plot.py RUN.h5 [-o PREFIX] [--force]
    PYTHONPATH=postproc python3 -m contact2d plot RUN.h5 [-o PREFIX] [--force]

writes
    PREFIX_contact.png   pressure, shear, gap g_i - u_i.n_i and status of the end state against the
                         abscissa of Gamma_c (runs with contact only)
    PREFIX_history.png   energies, residual and energy balance error, total contact forces against time
PREFIX defaults to RUN without its .h5 (the figures go beside the run). The quantities are those of
docs/output.md; every axis takes its unit from the dataset's `units` attribute.

A figure already there is refused before anything is drawn (one line, exit 2) unless --force; each
figure is written beside its name and moved into place (contact2d.outfile), so an existing file is
never replaced without --force, not even one that appears while the command runs. A missing file, or
one that is not a contact2d output, is one line and exit 2 as well.
"""
import argparse
import os
import sys

import numpy as np

from .h5 import RunFileError, open_run
from .outfile import OutputRefused, check_target, save_figure

STATUS_NAMES = ("separated", "stick", "slip")   # /final/contact/status codes (docs/output.md)
ENERGIES = ("kinetic_energy", "strain_energy", "external_work", "friction_dissipation",
            "damping_dissipation", "normal_contact_work")
FORCES = ("normal_force_total", "tangential_force_total")
ERRORS = ("residual", "energy_balance_error")


def targets(prefix, with_contact=True):
    """The PNG files plot_run writes for `prefix`: [contact (runs with contact),] history."""
    return ([prefix + "_contact.png"] if with_contact else []) + [prefix + "_history.png"]


def _label(run, path, name):
    units = run.units(path)
    return "%s [%s]" % (name, units) if units else name


def _legend_outside(ax):
    """The legend right of the axes, so that it never hides a curve."""
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, fontsize="small")


def contact_figure(run):
    """Figure of the end state along Gamma_c: pressure, shear, gap and status against the abscissa."""
    import matplotlib.pyplot as plt

    s = run.abscissa
    mult = run.attr("multiplier", "")
    # P1 and penalty: nodal values (linear between nodes); P0: one value per dual cell, drawn
    # constant on the cell around its node (SPEC section 3)
    style = dict(drawstyle="steps-mid") if mult == "P0" else dict(marker=".", markersize=4)
    kind = "per dual cell (P0)" if mult == "P0" else "per node"
    fig, axes = plt.subplots(4, 1, sharex=True, figsize=(8.5, 9.0), constrained_layout=True)
    fig.suptitle("%s: contact at the end (t = %.4g s, %s, %s)"
                 % (os.path.basename(run.path), run.attr("final_time", float("nan")), mult, run.status))

    ax = axes[0]
    ax.plot(s, run.contact("pressure"), color="C0", label="pressure p, " + kind, **style)
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_ylabel(_label(run, "final/contact/pressure", "pressure"))
    _legend_outside(ax)

    ax = axes[1]
    ax.plot(s, run.contact("shear"), color="C1", label="shear, " + kind, **style)
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_ylabel(_label(run, "final/contact/shear", "shear"))
    _legend_outside(ax)

    ax = axes[2]
    ax.plot(s, run.contact_gap(), color="C2", marker=".", markersize=4, label="gap g_i - u_i.n_i\n(> 0 open)")
    ax.plot(s, run.contact_setup("gap"), color="0.5", ls="--", lw=0.8, label="initial gap g_i")
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_ylabel(_label(run, "contact/gap", "gap"))
    _legend_outside(ax)

    ax = axes[3]
    status = run.contact("status")
    ax.plot(s, status, color="C3", drawstyle="steps-mid", marker=".", markersize=4, label="status per node")
    ax.set_yticks(range(len(STATUS_NAMES)))
    ax.set_yticklabels(STATUS_NAMES)
    ax.set_ylim(-0.4, len(STATUS_NAMES) - 0.6)
    ax.set_ylabel("status")
    counts = ", ".join("%d %s" % (np.count_nonzero(status == i), n) for i, n in enumerate(STATUS_NAMES))
    ax.plot([], [], " ", label=counts.replace(", ", "\n"))
    _legend_outside(ax)
    ax.set_xlabel(_label(run, "contact/abscissa", "abscissa along the contact boundary"))
    for ax in axes:
        ax.grid(True, lw=0.3)
    for ax in axes[:3]:
        ax.ticklabel_format(axis="y", style="sci", scilimits=(-3, 4))
    return fig


def history_figure(run):
    """Figure of the histories against time: energies, residual and balance error, contact forces."""
    import matplotlib.pyplot as plt

    names = set(run.history_names)
    t = run.history("time")
    panels = [p for p in (ENERGIES, ERRORS, FORCES) if names.intersection(p)]
    fig, axes = plt.subplots(len(panels), 1, sharex=True, figsize=(8.5, 2.9 * len(panels) + 0.6),
                             constrained_layout=True, squeeze=False)
    axes = axes[:, 0]
    fig.suptitle("%s: histories (%d samples, %s, %s)"
                 % (os.path.basename(run.path), len(t), run.attr("multiplier", ""), run.status))
    for ax, panel in zip(axes, panels):
        units = {run.units("history/" + n) for n in panel if n in names}
        log = panel is ERRORS and any((run.history(n) > 0).any() for n in panel if n in names)
        for n in panel:
            if n not in names:
                continue
            y = run.history(n)
            label = n.replace("_", " ")
            if log:
                # log scale: the residual falls by decades; zero values (the first sample, an exact
                # balance) are not drawn, and a series that is zero throughout says so
                label += "" if (y > 0).any() else " (0 at every sample)"
                y = np.where(y > 0, y, np.nan)
            ax.plot(t, y, label=label, lw=1.0, marker="." if len(t) <= 50 else None)   # few samples: each seen
        if log:
            ax.set_yscale("log")
        else:
            ax.ticklabel_format(axis="y", style="sci", scilimits=(-3, 4))
        what = {ENERGIES: "energy", ERRORS: "relative error", FORCES: "contact force"}[panel]
        ax.set_ylabel("%s [%s]" % (what, ", ".join(sorted(units))) if units - {""} else what)
        ax.grid(True, lw=0.3)
        _legend_outside(ax)
    axes[-1].set_xlabel(_label(run, "history/time", "time"))
    return fig


def plot_run(path, prefix=None, force=False):
    """Write the figures of run `path` (targets(prefix)); return their names. RunFileError for a
    file that is not a contact2d run, OutputRefused (before drawing) for a figure already there."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    path = str(path)
    if prefix is None:
        prefix = path[:-3] if path.endswith(".h5") else path
    with open_run(path) as run:
        if "time" not in run.history_names:
            raise RunFileError("%s: no /history/time (not a contact2d output file)" % path)
        with_contact = run.has_contact and run.has("final/contact/pressure")
        out = targets(str(prefix), with_contact)
        for target in out:
            check_target(target, inputs=[path], force=force)
        figs = ([contact_figure(run)] if with_contact else []) + [history_figure(run)]
        try:
            for fig, target in zip(figs, out):
                save_figure(fig, target, force=force, dpi=120)
        finally:
            for fig in figs:
                plt.close(fig)
    return out


def main(argv=None, prog=None):
    ap = argparse.ArgumentParser(prog=prog, description=__doc__.split("\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog="\n".join(__doc__.split("\n")[4:]))
    ap.add_argument("run", help="contact2d output file (.h5)")
    ap.add_argument("-o", "--output", metavar="PREFIX",
                    help="prefix of the figures: PREFIX_contact.png, PREFIX_history.png (default: RUN without .h5)")
    ap.add_argument("--force", action="store_true", help="replace figures that are already there")
    args = ap.parse_args(argv)
    name = ap.prog
    try:
        out = plot_run(args.run, args.output, args.force)
    except RunFileError as e:
        print("%s: error: %s" % (name, e), file=sys.stderr)
        return 2
    except OutputRefused as e:
        print("%s: refused: %s" % (name, e), file=sys.stderr)
        return 2
    for target in out:
        print(target)
    return 0


if __name__ == "__main__":
    sys.exit(main())
