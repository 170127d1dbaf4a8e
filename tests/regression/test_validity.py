"""Validity warnings at the end of a run: strain beyond the small-strain range, a body moved
further than its own size (docs/output.md, "Validity warnings").

- uniaxial_compression (bottom and left on rollers, the top moved down by delta on a block of
  height ly, plane strain, the right side free): the end state is homogeneous, e_yy = -delta/ly,
  e_xx = nu/(1 - nu) delta/ly (sigma_xx = 0), e_xy = 0, so the largest
  principal strain is delta/ly exactly (the root attribute strain_max, to the run's residual).
  delta/ly = 6 % is warned about (one stderr line naming 6.0 %, the same line in the root
  attribute validity_warnings), 4 % is not; the exit status is that of the run (0).
- patch_rotated_p1 with the top pressure's sign reversed (a pull, `traction#1:values=150`): nothing
  holds the block on the plane, it flies off: the displacement warning (max |u| above the
  bounding-box diagonal, both in the file: displacement_max = max |u| of /final/displacement);
  with material:young in GPa (70 instead of 7e4) the strain warning.
- every shipped deck (inputs/*.nml) at its shipped settings warns about neither: the static
  engine's end state where the deck allows it (the same discrete problem), the explicit run for
  the impact and penalty decks, the moving-obstacle decks, the two-body decks and the decks with
  two contact pairs (which the static engine refuses).
"""
import glob
import math
import os

import numpy as np

import c2dtest

PREFIX = "contact2d: warning: "


def validity_lines(run):
    return [l for l in run.stderr_lines() if l.startswith(PREFIX) and ("largest strain" in l or "largest displacement" in l)]


def body(t):
    # ---- 1. the strain of a homogeneous state --------------------------------------------------
    ly = 0.5
    for delta, warned in ((0.03, True), (0.02, False)):
        run = t.run(t.deck("uniaxial_compression.nml"), "--set", "dirichlet#3:values=%r" % (-delta),
                    name="uniaxial_%g" % delta)
        t.expect_exit(run, 0)
        lines = validity_lines(run)
        with run.open() as f:
            strain_max = float(f.attrs["strain_max"])
            disp_max = float(f.attrs["displacement_max"])
            u = f["final/displacement"][()]
            stored = c2dtest.attr_str(f.attrs["validity_warnings"]) if "validity_warnings" in f.attrs else ""
            converged = int(f.attrs["converged"])
        t.check_equal(run, "converged", 1, converged)
        t.check_close(run, "strain_max = delta / ly (homogeneous uniaxial strain)", delta / ly, strain_max, rtol=1e-8,
                      reason="exact for the linear field Q1 reproduces; the run stops at residual 1e-10")
        t.check_close(run, "displacement_max = max |u| of /final/displacement", float(np.max(np.hypot(u[:, 0], u[:, 1]))),
                      disp_max, rtol=1e-14, reason="the same numbers, round-off")
        if warned:
            t.check_equal(run, "one validity warning (strain)", 1, len(lines))
            line = lines[0] if lines else ""
            t.check(run, "the line names the strain %.1f %% and the 5 %% limit" % (100 * delta / ly),
                    "largest strain" in line and "%.1f %%" % (100 * delta / ly) in line and "over 5 %" in line,
                    "... largest strain ... 6.0 % ... over 5 % ...", line)
            t.check_equal(run, "root attribute validity_warnings = the stderr line", line[len(PREFIX):], stored)
        else:
            t.check_equal(run, "no validity warning at 4 %", [], lines)
            t.check_equal(run, "no validity_warnings attribute", "", stored)

    # ---- 2. the repros: a pull instead of a pressure, E in GPa --------------------------------
    run = t.run(t.deck("patch_rotated_p1.nml"), "--set", "traction#1:values=150", "--set", "solver:max_steps=3000",
                name="pull")
    t.expect_exit(run, 0)
    with run.open() as f:
        x = f["mesh/coordinates"][()]
        u = f["final/displacement"][()]
        disp_max = float(f.attrs["displacement_max"])
        stored = c2dtest.attr_str(f.attrs.get("validity_warnings", ""))
    diag = float(np.hypot(*np.ptp(x, axis=0)))
    umax = float(np.max(np.hypot(u[:, 0], u[:, 1])))
    t.info(run, "max |u| [mm], bounding-box diagonal [mm]", "%.4g, %.4g" % (umax, diag))
    t.check(run, "the block flew off (max |u| > diagonal)", umax > diag, "> %.4g" % diag, umax)
    t.check_close(run, "displacement_max = max |u|", umax, disp_max, rtol=1e-14, reason="round-off")
    lines = [l for l in validity_lines(run) if "largest displacement" in l]
    t.check_equal(run, "one displacement warning", 1, len(lines))
    t.check(run, "it is in validity_warnings", bool(lines) and lines[0][len(PREFIX):] in stored.split("\n"), True,
            stored)
    run = t.run(t.deck("patch_rotated_p1.nml"), "--set", "material:young=70", name="gpa")
    t.expect_exit(run, 0)
    lines = [l for l in validity_lines(run) if "largest strain" in l]
    t.check_equal(run, "one strain warning (E in GPa: strain ~ 150/70)", 1, len(lines))

    # ---- 3. no shipped deck is warned about --------------------------------------------------
    explicit_only = ("impact_bar_p1", "impact_bar_p0", "impact_bar_penalty", "patch_compression_penalty",
                     # a moving obstacle: the static engine refuses it (docs/geometry.md)
                     "block_on_moving_plane_p1", "block_on_moving_plane_p0", "cylinder_sliding_layer",
                     "friction_instability_p1",
                     # contact between two bodies: the static engine refuses it (docs/geometry.md)
                     "bar_impact_two_bodies_p1", "contact_patch_p1",
                     # two contact pairs: the static engine solves one (docs/deck.md &contact)
                     "block_two_planes_p1", "block_two_planes_p0", "block_corner_p1", "block_corner_p0")
    decks = sorted(glob.glob(os.path.join(t.inputs, "*.nml")))
    t.check(t.workdir, "shipped decks found", len(decks) >= 20, ">= 20", len(decks))
    for deck in decks:
        name = os.path.splitext(os.path.basename(deck))[0]
        args = () if name in explicit_only else ("--static",)
        run = t.run(deck, *args, name="shipped_" + name)
        t.expect_exit(run, 0)
        t.check_equal(run, "no validity warning for %s (%s)" % (name, "explicit" if not args else "static"), [],
                      validity_lines(run))
        with run.open() as f:
            t.info(run, "strain_max, displacement_max [mm]", "%.4g, %.4g" % (float(f.attrs["strain_max"]),
                                                                          float(f.attrs["displacement_max"])))


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0]).main(body)
