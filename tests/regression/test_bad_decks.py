"""Regression 4: bad input is refused with one clear line, exit 1, and nothing written.

Each case runs in its own empty directory with `-o out.h5`. It must exit with 1 (bad input or
usage), print exactly one line on stderr, starting with 'contact2d: error:' and matching the
case's pattern (the pattern names the problem), and leave no out.h5 and no out.xmf behind (for the
existing-output case: leave the pre-existing out.h5 byte for byte as it was, and write no out.xmf).

The deck-content cases are files in bad_decks/ (the first line of each says what is wrong); the
command-line cases reuse inputs/uniaxial_compression.nml or inputs/patch_compression_p1.nml.
"""
import os
import re

import c2dtest

UNIAXIAL = "uniaxial_compression.nml"

# name: (deck: a file in bad_decks/ or inputs/ or a missing path, extra args, regex for the error line)
CASES = [
    ("unknown_variable", "bad_decks/unknown_variable.nml", [],
     r"&mesh.*\bnz\b"),
    ("misspelled_group", "bad_decks/misspelled_group.nml", [],
     r"unknown group '&materail'.*'material'"),
    ("wrong_type_string", "bad_decks/wrong_type_string.nml", [],
     # the message points at the deck line holding the bad value and quotes it
     # (and no decimal-comma hint: no comma is the cause)
     r"^(?!.*decimal).*:3: &mesh: .*'abc'.*nx = 'abc'"),
    ("wrong_type_real", "bad_decks/wrong_type_real.nml", [],
     # no decimal-comma hint where no comma is the cause
     r"^(?!.*decimal).*:3: &mesh: .*\.5.*nx = 2\.5"),
    ("missing_deck_file", "no_such_deck.nml", [],
     r"no_such_deck\.nml.*(no such file|not found|does not exist)"),
    ("young_zero", "bad_decks/young_zero.nml", [],
     r"material:young = .*must be > 0"),
    ("young_negative", "bad_decks/young_negative.nml", [],
     r"material:young = -.*must be > 0"),
    ("poisson_half", "bad_decks/poisson_half.nml", [],
     r"material:poisson = .*< 0\.5"),
    ("nx_zero", "bad_decks/nx_zero.nml", [],
     r"mesh:nx = 0 must be >= 1"),
    ("dt_above_critical", "inputs/" + UNIAXIAL, ["--set", "solver:dt_factor=1.5"],
     r"dt = .* exceeds dt_critical .*allow_unstable"),
    ("damping_unknown", "bad_decks/damping_unknown.nml", [],
     r"damping = 'fast' is not one of 'auto', 'given', 'none'"),
    ("existing_output", "inputs/" + UNIAXIAL, [],
     r"out\.h5.*exists.*--force"),
    ("threshold_negative", "bad_decks/threshold_negative.nml", [],
     r"contact:threshold = -100 must be >= 0"),
    ("friction_coefficient_negative", "inputs/coulomb_sliding_p1.nml", ["--set", "contact:friction_coefficient=-0.1"],
     r"contact:friction_coefficient = -0\.1 must be finite and >= 0"),
    ("friction_coefficient_without_coulomb", "inputs/tresca_sliding_p1.nml",
     ["--set", "contact:friction_coefficient=0.3"], r"friction_coefficient is set but friction = 'tresca'"),
    ("threshold_with_coulomb", "inputs/coulomb_sliding_p1.nml", ["--set", "contact:threshold=100"],
     r"threshold is given but friction = 'coulomb'"),
    ("multiplier_p2", "bad_decks/multiplier_p2.nml", [],
     r"multiplier = 'P2' is not one of 'P1', 'P0'"),
    ("contact_boundary_empty", "bad_decks/contact_empty.nml", [],
     r"contact: .*candidate boundary.*(no node|empty)"),
    ("set_unknown_group", "inputs/" + UNIAXIAL, ["--set", "solvr:dt_factor=0.5"],
     r"--set 'solvr:dt_factor=0\.5': unknown group 'solvr'"),
    ("set_unknown_variable", "inputs/" + UNIAXIAL, ["--set", "solver:dtfactor=0.5"],
     # a misspelled name is not a text value: no hint about quotes, but the nearest name
     r"--set 'solver:dtfactor=0\.5'.*dtfactor; did you mean 'dt_factor'\?$"),
    ("set_unknown_variable_far", "inputs/" + UNIAXIAL, ["--set", "solver:zzz=0.5"],
     # no name of &solver is near: no suggestion
     r"--set 'solver:zzz=0\.5'.*object name zzz$"),
    ("misspelled_variable", "bad_decks/misspelled_variable.nml", [],
     r":6: &material: .*object name yuong; did you mean 'young'\?"),
    ("set_text_unquoted", "inputs/" + UNIAXIAL, ["--set", "solver:damping=given"],
     r"--set 'solver:damping=given'.*\bgiven; a text value needs quotes"),
    # a decimal comma makes a second value, not a name: no hint about quotes
    ("set_decimal_comma", "inputs/coulomb_sliding_p1.nml", ["--set", "contact:friction_coefficient=0,3"],
     r"^(?!.*quotes)contact2d: error: --set 'contact:friction_coefficient=0,3': .*object name 3; "
     r"more values than the variable holds \(a decimal takes a point: 0\.3, not 0,3\)$"),
    # a --set that would change nothing, set two variables, or leaves a quote open
    ("set_value_empty", "inputs/" + UNIAXIAL, ["--set", "solver:dt_factor="],
     r"--set 'solver:dt_factor=': no value after '='$"),
    ("set_two_variables", "inputs/" + UNIAXIAL, ["--set", "material:young=2.1e5, poisson=0.25"],
     r"--set 'material:young=2\.1e5, poisson=0\.25': sets 2 variables \('young', 'poisson'\); "
     r"give one variable per --set$"),
    ("set_quote_not_closed", "inputs/coulomb_sliding_p1.nml", ["--set", "contact:multiplier='P0"],
     r"--set 'contact:multiplier='P0': the quote opening 'P0 is not closed$"),
    # a value refused by validation names the --set it came from, as well as the deck's group
    ("set_value_blamed", "inputs/" + UNIAXIAL, ["--set", "mesh:nx=3", "--set", "solver:tol_residual=-1"],
     r"solver:tol_residual = -1 must be > 0 \(from --set 'solver:tol_residual=-1'\)$"),
    ("set_range_blamed", "inputs/" + UNIAXIAL,
     ["--set", "dirichlet#3:xmin=3", "--set", "dirichlet#2:ymin=0", "--set", "dirichlet#3:xmax=1"],
     r"line 16: &dirichlet \(#3\): the range needs .*\(from --set 'dirichlet#3:xmin=3', --set 'dirichlet#3:xmax=1'\)$"),
    # the same when the model refuses it, after the deck's checks
    ("set_selection_blamed", "inputs/" + UNIAXIAL, ["--set", "dirichlet#3:xmin=3"],
     r":16: &dirichlet \(#3\): the selection .*holds no node \(from --set 'dirichlet#3:xmin=3'\)$"),
    # and a --set the message is not about is not named
    ("set_not_blamed", "bad_decks/young_zero.nml", ["--set", "solver:tol_residual=1e-7"],
     r"material:young = .*must be > 0$"),
    # a side or curve emptied by --set: the message says what to give, and names the --set
    ("set_boundary_empty", "inputs/hertz_cylinder_p1.nml", ["--set", "contact:boundary=''"],
     r"contact: boundary is empty: give boundary = '<physical curve>' of the Gmsh mesh hertz_cylinder\.geo "
     r"\(from --set 'contact:boundary='''\)$"),
    ("set_edge_empty", "inputs/" + UNIAXIAL, ["--set", "dirichlet#1:edge=''"],
     r"&dirichlet \(#1\): edge is empty: give edge = 'bottom' \| 'right' \| 'top' \| 'left'.*"
     r"\(from --set 'dirichlet#1:edge='''\)$"),
    # the same words whichever optional group the deck lacks
    ("set_contact_without_group", "inputs/" + UNIAXIAL, ["--set", "contact:multiplier='P0'"],
     r"--set 'contact:multiplier='P0'': the deck has no &contact group$"),
    ("set_traction_without_group", "inputs/" + UNIAXIAL, ["--set", "traction:values=1"],
     r"--set 'traction:values=1': the deck has no &traction group$"),
    ("group_not_closed", "bad_decks/group_not_closed.nml", [],
     r"group &solver is not closed by '/'"),
    ("text_outside_groups", "bad_decks/text_outside_groups.nml", [],
     r":5: text outside any namelist group"),
    # a variable given twice in one group: the namelist would keep the last value silently
    ("repeated_variable", "bad_decks/repeated_variable.nml", [],
     r"repeated_variable\.nml:7: &material: young is given twice in this group \(first at line 6\)$"),
    ("repeated_element", "bad_decks/repeated_element.nml", [],
     r":12: &dirichlet: values\(2\) is given twice in this group \(first as values at line 11\)$"),
    # a leading UTF-8 byte-order mark is skipped: the error is the deck's real one
    ("bom_young_zero", "bad_decks/bom_young_zero.nml", [],
     r"bom_young_zero\.nml: material:young = .* must be > 0$"),
    # a real that is not finite or beyond 1e30, a string longer than its variable, half a point
    ("friction_coefficient_nan", "inputs/coulomb_sliding_p1.nml", ["--set", "contact:friction_coefficient=NaN"],
     r"contact:friction_coefficient = NaN must be finite"),
    ("friction_coefficient_huge", "inputs/coulomb_sliding_p1.nml", ["--set", "contact:friction_coefficient=1e200"],
     r"contact:friction_coefficient = 1e200 is out of range"),
    ("dt_limit_too_long", "inputs/" + UNIAXIAL, ["--set", "solver:dt_limit='element is what I want'"],
     r"dt_limit = 'element is what I want' is longer than 8 characters"),
    ("convergence_test_too_long", "inputs/" + UNIAXIAL, ["--set", "solver:convergence_test='off-by-default'"],
     r"convergence_test = 'off-by-default' is longer than 8 characters"),
    ("mesh_file_too_long", "inputs/" + UNIAXIAL, ["--set", "mesh:file='%s.msh'" % ("m" * 300)],
     r"file = 'm{300}\.msh' is longer than 256 characters"),
    ("origin_one_component", "bad_decks/origin_one_component.nml", [],
     r"contact:origin = 0\.25 has one component"),
    # &initial and dynamic runs
    ("initial_velocity_nan", "inputs/impact_bar_p1.nml", ["--set", "initial:velocity=NaN,-1000"],
     r"initial:velocity\(1\) = .*must be finite"),
    # the 'not given' marker +-huge(1.0) typed by the user is out of range like any other value
    # (it passed every check: --static ended 'converged' with NaN displacements)
    ("marker_dirichlet_static", "inputs/" + UNIAXIAL,
     ["--static", "--set", "dirichlet#3:values=-1.7976931348623157e308"],
     r"--set 'dirichlet#3:values=-1\.7976931348623157e308': dirichlet#3:values = -1\.7976931348623157e308 "
     r"is out of range \(\|value\| <= 1e30\)$"),
    ("marker_xmax", "bad_decks/marker_xmax.nml", [],
     r"marker_xmax\.nml:9: dirichlet#2:xmax = 1\.7976931348623157e308 is out of range"),
    ("marker_initial_velocity", "inputs/impact_bar_p1.nml", ["--set", "initial:velocity=0,-1.7976931348623157e308"],
     r"initial:velocity = -1\.7976931348623157e308 is out of range"),
    ("marker_friction_coefficient", "inputs/coulomb_sliding_p1.nml",
     ["--set", "contact:friction_coefficient=1.7976931348623157e308"],
     r"contact:friction_coefficient = 1\.7976931348623157e308 is out of range"),
    ("marker_obstacle_center", "inputs/hertz_indenter_p1.nml",
     ["--set", "contact:obstacle_center=0,1.7976931348623157e308"],
     r"contact:obstacle_center = 1\.7976931348623157e308 is out of range"),
    # a real beyond the double range in the deck (the conversion overflowed and trapped in Debug)
    ("lx_overflow", "bad_decks/lx_overflow.nml", [],
     r"lx_overflow\.nml:3: mesh:lx = 1e999 is out of range \(\|value\| <= 1e30\)$"),
    # settings that were silently ignored
    ("xdmf_fish", "bad_decks/xdmf_fish.nml", [],
     r"xdmf_fish\.nml:15: output:xdmf = fish is not a logical value; give \.true\. or \.false\.$"),
    ("set_progress_yes", "inputs/" + UNIAXIAL, ["--set", "output:progress=yes"],
     r"--set 'output:progress=yes': output:progress = yes is not a logical value"),
    ("obstacle_point_with_circle", "inputs/hertz_indenter_p1.nml", ["--set", "contact:obstacle_point=0,1"],
     r"contact: obstacle_point and obstacle_normal are set but obstacle = 'circle' ignores them.*"
     r"\(from --set 'contact:obstacle_point=0,1'\)$"),
    # control characters are shown escaped, and the message stays one line
    ("set_newline_in_value", "inputs/" + UNIAXIAL, ["--set", "solver:damping='a\nb'"],
     r"--set 'solver:damping='a\\x0ab''"),
    ("escape_in_value", "bad_decks/escape_in_value.nml", [],
     r"^[^\x1b]*solver:damping = '\\x1b\[31m' is not one of"),
    # a pinned node inside the contact boundary is refused (an end node would be dropped with a
    # warning): the kept nodes must form one chain (docs/deck.md, &contact)
    ("pinned_inside_contact", "bad_decks/pinned_inside_contact.nml", [],
     r"contact: node 3 inside the candidate boundary has a prescribed normal displacement; split the boundary "
     r"or free that node$"),
    ("dynamic_without_t_end", "inputs/impact_bar_p1.nml", ["--set", "solver:t_end=0"],
     r"solver:t_end is required for a dynamic run"),
    # a mechanism (docs/static.md "Bodies held by contact"): the frictionless block without its
    # pin is free to slide along x; the static engine has no unique solution, and a load along x
    # drives it in the explicit engine too
    ("mechanism_static", "bad_decks/block_no_pin.nml", ["--static"],
     r"block_no_pin\.nml: body 'body' is free to translate along x: no support and no contact stops it; "
     r"add a &dirichlet or friction$"),
    ("mechanism_compare_static", "bad_decks/block_no_pin.nml", ["--set", "solver:compare_static=.true."],
     r"body 'body' is free to translate along x: no support and no contact stops it; add a &dirichlet or friction$"),
    ("mechanism_driven", "bad_decks/block_no_pin.nml", ["--set", "traction#1:component='tangential'"],
     r"body 'body' is free to translate along x: no support and no contact stops it; add a &dirichlet or friction$"),
    ("mechanism_no_contact", "inputs/uniaxial_compression.nml",
     ["--static", "--set", "dirichlet#1:component='x'", "--set", "dirichlet#3:component='x'",
      "--set", "dirichlet#3:values=0"],
     r"body 'body' is free to translate along y: no support and no contact stops it; add a &dirichlet$"),
    # each separate body is checked on its own: the right block of two (no shared node, no
    # contact) without its x support is a mechanism of that body, named
    ("mechanism_second_body", "bad_decks/separate_right_free.nml", ["--static"],
     r"separate_right_free\.nml: body 'right' is free to translate along x: no support and no contact "
     r"stops it; add a &dirichlet$"),
    # the obstacle's motion (docs/geometry.md "Moving obstacles"): each value checked, named
    ("obstacle_motion_times_decreasing", "inputs/block_on_moving_plane_p1.nml",
     ["--set", "contact:obstacle_motion_times=3e-6, 2e-6"],
     r"contact:obstacle_motion_times must increase strictly \(obstacle_motion_times\(2\) = 2"),
    ("obstacle_velocity_nan", "inputs/block_on_moving_plane_p1.nml",
     ["--set", "contact:obstacle_velocity_x=0, NaN"], r"contact:obstacle_velocity_x\(2\) = NaN must be finite"),
    ("obstacle_velocity_three_values", "inputs/block_on_moving_plane_p1.nml",
     ["--set", "contact:obstacle_velocity_x=0, 500, 1000"],
     r"contact:obstacle_velocity_x needs one value per obstacle_motion_times entry \(2\).*got 3\b"),
    ("obstacle_spin_on_plane", "inputs/block_on_moving_plane_p1.nml",
     ["--set", "contact:obstacle_spin=0, 1"], r"contact:obstacle_spin is set but obstacle = 'plane'"),
    ("obstacle_moving_initial_geometry", "inputs/block_on_moving_plane_p1.nml",
     ["--set", "contact:geometry='initial'"], r"contact:geometry = 'initial' cannot follow a moving obstacle"),
    ("geometry_unknown", "inputs/coulomb_sliding_p1.nml",
     ["--set", "contact:geometry='deformed'"], r"contact:geometry = 'deformed' is not one of 'initial', 'current'"),
    # the static engine refuses a moving obstacle (a dragged frictional contact: path dependent)
    ("static_moving_obstacle", "inputs/block_on_moving_plane_p1.nml", ["--static"],
     r"solver:method = 'static' refuses a moving obstacle"),
    ("static_current_geometry", "inputs/coulomb_sliding_p1.nml", ["--static", "--set", "contact:geometry='current'"],
     r"solver:method = 'static' refuses contact:geometry = 'current'"),
]

# Bytes of the output file that already exists in the 'existing_output' case (not HDF5 on
# purpose: a program that opened and rewrote it would change it).
SENTINEL = b"pre-existing output: must survive a run without --force\n"


def deck_path(t, deck):
    if deck.startswith("bad_decks/"):
        return os.path.join(t.here, deck)
    if deck.startswith("inputs/"):
        return t.deck(deck[len("inputs/"):])
    return os.path.join(t.workdir, deck)   # a file that does not exist


def body(t):
    t.check_ge("bad_decks", "number of cases", len(CASES), 14, reason="every class of bad input the deck reference names, at least 14")
    for name, deck, extra, pattern in CASES:
        print()
        print("## case %s" % name)
        path = deck_path(t, deck)
        if deck.startswith("bad_decks/"):
            with open(path, encoding="utf-8-sig") as fh:
                print("   deck: %s   (%s)" % (deck, fh.readline().strip()))
        cwd = t.subdir(name)
        if name == "existing_output":
            with open(os.path.join(cwd, "out.h5"), "wb") as fh:
                fh.write(SENTINEL)
        before = sorted(os.listdir(cwd))
        run = t.run(path, *extra, cwd=cwd, output="out.h5")
        where = name
        t.check_equal(where, "exit code", 1, run.returncode)
        lines = run.stderr_lines()
        t.check_equal(where, "lines on stderr", 1, len(lines))
        first = lines[0] if lines else ""
        t.check(where, "stderr line starts with 'contact2d: error:'", first.startswith(c2dtest.ERROR_PREFIX),
                "'contact2d: error: ...'", repr(first))
        t.check(where, "error names the problem", re.search(pattern, first) is not None,
                "match /%s/" % pattern, repr(first))
        after = sorted(os.listdir(cwd))
        t.check_equal(where, "files in the run directory afterwards", before, after)
        if name == "existing_output":
            with open(os.path.join(cwd, "out.h5"), "rb") as fh:
                data = fh.read()
            t.check_equal(where, "pre-existing out.h5 unchanged (bytes)", SENTINEL, data)
        else:
            t.check_equal(where, "out.h5 written", False, os.path.exists(os.path.join(cwd, "out.h5")))
        t.check_equal(where, "out.xmf written", False, os.path.exists(os.path.join(cwd, "out.xmf")))


if __name__ == "__main__":
    c2dtest.Test("bad decks: one-line error, exit 1, nothing written").main(body)
