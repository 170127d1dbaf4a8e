#!/usr/bin/env python3
"""block_two_planes (P1 or P0): two contact pairs, an elastic block between two rigid frictionless
planes (docs/deck.md &contact, docs/output.md "Several contact pairs").

Block [0, L] x [0, H] = [0, 1] x [0, 0.5] mm, E = 7e4 MPa, nu = 0.3, plane strain. Pair 'floor':
the bottom edge on the fixed plane y <= 0; pair 'ram': the top edge under the plane y >= H, which
moves down by delta = 2e-3 mm (velocity -2000, 0 mm/s at 1e-6, 2e-6 s: the exact integral of the
two smooth ramps, 2000 (1e-6)/2 twice); one node of the left edge held in x.
Facts:
- Plane strain uniaxial compression (frictionless planes, free lateral expansion): a uniform
  strain eps_yy = -delta/H, which Q1 represents exactly, so every element's stress is
  (sigma_xx, sigma_yy, sigma_xy) = (0, -p, 0), p = E delta / (H (1 - nu^2)).
- Each plane carries the total normal force p L; the forces on the body, -F_n,i n_i, of the two
  pairs are equal and opposite (the block is in equilibrium with no other load in y).
- The ram's displacement is the closed-form integral of its velocity curve: -delta at the end.
- Output with two pairs: /contact/<name>, /final/contact/<name>, '<name>_<series>' histories whose
  sums are the totals, one contact grid per pair in the sidecar, one summary line per pair.
- block_corner (the same block pressed by tractions q_x = 50, q_y = 100 MPa into the corner of two
  fixed frictionless planes, pairs 'floor' and 'wall', the corner node held in x): uniform biaxial
  compression, every element's stress (-q_x, -q_y, 0); the floor carries q_y L, the wall with the
  corner's reaction q_x H.
- Refusals (exit 1, one line naming the value, no file): two pairs with one name; a node in the
  slave sets of two pairs (named with both pairs); --static with two pairs.
"""
import os

import numpy as np

import c2dtest
import contact2d

E, NU, L, H, DELTA = 7.0e4, 0.3, 1.0, 0.5, 2.0e-3
QX, QY = 50.0, 100.0   # block_corner's tractions [MPa]
P = E * DELTA / (H * (1 - NU * NU))
NAMES = ("floor", "ram")


def refused(t, deck, name, args, words):
    """A refusal: exit 1, one line on stderr holding every word, no output file."""
    run = t.run(deck, *args, name=name)
    t.expect_exit(run, 1, stop=False)
    lines = run.stderr_lines()
    t.check_equal(run, "stderr lines", 1, len(lines))
    text = lines[0] if lines else ""
    t.check(run, "the message names " + ", ".join(words), all(w in text for w in words), words, text)
    t.check(run, "no output file", not os.path.exists(run.h5), "none", "present" if os.path.exists(run.h5) else "none")


def body(t):
    mult = t.args.multiplier
    deck = t.deck("block_two_planes_%s.nml" % mult.lower())
    run = t.run(deck, name="run", quiet=False)
    t.expect_exit(run, 0)
    t.expect_output(run)
    with run.open() as f:
        t.check_equal(run, "converged", 1, int(f.attrs["converged"]))
        stress = f["final/stress"][()]
        t.check_equal(run, "/contact pair_count", 2, int(f["contact"].attrs["pair_count"]))
        t.check_equal(run, "/contact pair names", list(NAMES),
                      [c2dtest.attr_str(f["contact"].attrs["pair_name_%d" % k]) for k in (1, 2)])
        fn = {n: f["final/contact/%s/normal_force" % n][()] for n in NAMES}
        normal = {n: f["contact/%s/normal" % n][()] for n in NAMES}
        hist = {k: f["history/" + k][()] for k in ("normal_force_total", "floor_normal_force_total",
                                                  "ram_normal_force_total", "obstacle_displacement_y",
                                                  "energy_balance_error")}
        mults = [c2dtest.attr_str(f["contact/%s" % n].attrs["multiplier"]) for n in NAMES]

    t.check_equal(run, "each pair's multiplier attribute", [mult, mult], mults)
    # -- uniaxial compression: the exact stress in every element --------------------------------
    t.check_close(run, "sigma_yy = -E delta/(H (1 - nu^2)) in every element [MPa]", -P, stress[:, 1], rtol=1e-8,
                  reason="uniform strain, exact for Q1; converged to tol_residual 1e-12 (measured 4e-12)")
    t.check_close(run, "sigma_xx = 0 in every element [MPa]", 0.0, stress[:, 0], atol=1e-8 * P,
                  reason="free lateral expansion on frictionless planes (measured 1e-11 p)")
    t.check_close(run, "sigma_xy = 0 in every element [MPa]", 0.0, stress[:, 2], atol=1e-8 * P,
                  reason="no shear (measured 5e-12 p)")
    # -- each plane's force p L, the two opposite ------------------------------------------------
    for n in NAMES:
        t.check_close(run, "pair %s: total normal force = p L [N/mm]" % n, P * L, fn[n].sum(), rtol=1e-8,
                      reason="the plane carries the uniform pressure over the length L (measured 1.3e-12)")
    force = {n: -(fn[n][:, None] * normal[n]).sum(axis=0) for n in NAMES}   # normal: (nc, 2)
    t.check_close(run, "floor's force on the body + ram's force on the body = 0 [N/mm]", np.zeros(2),
                  force["floor"] + force["ram"], atol=1e-8 * P * L, reason="equilibrium: no other load in y")
    t.check_ge(run, "floor pushes the body up (+y) [N/mm]", force["floor"][1], 0.999 * P * L)
    # -- history: per-pair series and their sum; the ram's motion ---------------------------------
    t.check_close(run, "normal_force_total = floor_ + ram_normal_force_total at every sample [N/mm]",
                  hist["floor_normal_force_total"] + hist["ram_normal_force_total"], hist["normal_force_total"],
                  rtol=1e-15, reason="the total is the pairs' sum, in pair order")
    t.check_close(run, "obstacle_displacement_y at the end = -delta [mm]", -DELTA, hist["obstacle_displacement_y"][-1],
                  rtol=1e-12, reason="the exact integral of the two ramps")
    t.check_le(run, "energy_balance_error at every sample", hist["energy_balance_error"], 1e-12,
               reason="the moving plane's work is the balance's input (measured 1.3e-15)")
    # -- the summary's energy lines: each pair's terms of the balance -------------------------------
    with run.open() as f:
        wob = {n: float(f["history/%s_obstacle_work" % n][-1]) for n in NAMES}
    for n in NAMES:
        lines = [l for l in run.stdout.splitlines() if l.strip().startswith("pair %s: D_friction" % n)]
        t.check_equal(run, "energy line of pair %s" % n, 1, len(lines))
        if lines:
            printed = float(lines[0].split("W_obstacle =")[1].split()[0])
            t.check_close(run, "pair %s: printed W_obstacle = its last obstacle_work sample [mJ]" % n, wob[n], printed,
                          rtol=1e-3, atol=1e-300, reason="the printed value has 4 digits")
    t.check_equal(run, "the fixed floor does no work", 0.0, wob["floor"])
    t.check(run, "the ram does work on the block", wob["ram"] > 0, "> 0", wob["ram"])

    # -- summary and sidecar: one per pair --------------------------------------------------------
    for n in NAMES:
        lines = [l for l in run.stdout.splitlines() if l.startswith(" contact %s " % n)]
        t.check_equal(run, "summary lines of pair %s" % n, 1, len(lines))
        with open(os.path.splitext(run.h5)[0] + ".xmf") as x:
            xmf = x.read()
        t.check(run, "sidecar grid contact_final_%s" % n, 'Name="contact_final_%s"' % n in xmf, "present",
                "present" if 'Name="contact_final_%s"' % n in xmf else "missing")
        t.check(run, "sidecar polyline of pair %s" % n, ":/contact/%s/coordinates" % n in xmf, "present",
                "present" if ":/contact/%s/coordinates" % n in xmf else "missing")

    # -- the postproc reader: per-pair data, the first by default ----------------------------------
    with contact2d.open_run(run.h5) as r:
        t.check_equal(run, "open_run: pair_names", list(NAMES), r.pair_names)
        t.check(run, "open_run: contact('normal_force') is the first pair's",
                np.array_equal(r.contact("normal_force"), fn["floor"]), "floor's", "same" if
                np.array_equal(r.contact("normal_force"), fn["floor"]) else "different")
        t.check(run, "open_run: contact('normal_force', 'ram') and (.., 2) are the ram's",
                np.array_equal(r.contact("normal_force", "ram"), fn["ram"]) and
                np.array_equal(r.contact("normal_force", 2), fn["ram"]), "ram's", "checked")
        t.check(run, "open_run: history('normal_force_total', pair='ram') is ram_normal_force_total",
                np.array_equal(r.history("normal_force_total", pair="ram"), hist["ram_normal_force_total"]),
                "ram's series", "checked")
        t.check_le(run, "open_run: |contact_gap('floor')| at the end [mm]", np.abs(r.contact_gap("floor")), 1e-12 * DELTA,
                   reason="every node closed on the fixed plane (round-off)")
        t.check_close(run, "open_run: contact_gap('ram') at the end = delta [mm]", DELTA, r.contact_gap("ram"),
                      rtol=1e-9, reason="the gap to the ram's initial place (/contact/ram/gap): every node followed "
                      "the ram down by delta")
        try:
            r.contact("pressure", "wall")
            unknown = "no error"
        except KeyError as exc:
            unknown = str(exc)
        t.check(run, "open_run: an unknown pair is a KeyError naming the pairs", "floor, ram" in unknown,
                "KeyError ... floor, ram", unknown)
    one = t.run(t.deck("patch_compression_%s.nml" % mult.lower()), name="one_pair")
    t.expect_exit(one, 0)
    with contact2d.open_run(one.h5) as r:
        t.check_equal(one, "one pair: pair_names", ["contact"], r.pair_names)
        t.check(one, "one pair: contact('pressure', 'contact') = contact('pressure') = /final/contact/pressure",
                np.array_equal(r.contact("pressure", "contact"), r.read("final/contact/pressure")) and
                np.array_equal(r.contact("pressure"), r.read("final/contact/pressure")), "equal", "checked")

    # -- block_corner: two fixed obstacles, biaxial compression -----------------------------------
    corner = t.run(t.deck("block_corner_%s.nml" % mult.lower()), name="corner")
    t.expect_exit(corner, 0)
    dropped = [l for l in corner.stderr_lines() if "candidate node(s) dropped" in l]
    t.check(corner, "the wall's warning about its dropped corner node names contact#2",
            len(dropped) == 1 and "contact#2: " in dropped[0], "one line with contact#2:", dropped)
    with corner.open() as f:
        t.check_equal(corner, "converged", 1, int(f.attrs["converged"]))
        cs = f["final/stress"][()]
        floor = f["final/contact/floor/normal_force"][()].sum()
        wall = f["final/contact/wall/normal_force"][()].sum()
        rx = f["final/reaction"][()][:, 0].sum()
    t.check_close(corner, "sigma = (-q_x, -q_y, 0) in every element [MPa]", np.array([-QX, -QY, 0.0]) + 0 * cs, cs,
                  atol=1e-8 * QY, reason="uniform biaxial compression, exact for Q1 (measured 4e-12 q_y)")
    t.check_close(corner, "floor: total normal force = q_y L [N/mm]", QY * L, floor, rtol=1e-8,
                  reason="every bottom node on the floor (measured 5e-13)")
    t.check_close(corner, "wall's total normal force + the corner's x reaction = q_x H [N/mm]", QX * H, wall + rx,
                  rtol=1e-8, reason="the corner node, held in x, is dropped from the wall pair (measured 9e-12)")

    # -- refusals ------------------------------------------------------------------------------
    refused(t, deck, "same_name", ["--set", "contact#2:name='floor'"], ["contact#2:name", "floor"])
    refused(t, deck, "shared_node", ["--set", "contact#2:edge='bottom'"], ["node", "'floor'", "'ram'"])
    refused(t, deck, "bad_name", ["--set", "contact#2:name='a b'"], ["contact#2:name", "a b"])
    refused(t, deck, "static", ["--static"], ["one contact pair", "2 &contact groups"])


if __name__ == "__main__":
    c2dtest.Test("block_two_planes: two contact pairs, exact uniaxial compression, per-pair output, refusals",
                 extra_args=[(("--multiplier",), {"choices": ["P1", "P0"], "required": True})]).main(body)
