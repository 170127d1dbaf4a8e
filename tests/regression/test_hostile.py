"""Regression 14: hostile input, table-driven. Every case is refused with exit 1 and
exactly one line on stderr, 'contact2d: error: ...', naming the bad item (the case's pattern),
and leaves the run's folder exactly as it was (same names, kinds, sizes, contents, link
targets): nothing created, nothing modified, not even a lock or temporary file.

Classes: output names (the deck itself and its Gmsh mesh file, also through hard and symbolic links; the sidecar;
directories, devices, FIFOs, dangling links, link loops, missing or non-folder parents, names too long,
existing files and sidecars), lock files planted beside the output (a symbolic link to the user's
file, dangling or looping, a hard link, a file with other content, a FIFO, a directory: refused,
left as they are, the link's target untouched), deck files (directory, device, FIFO, oversized,
missing, link loop), the deck's Gmsh mesh file a link loop, deck text
(over-long lines, over-long string values, '&end', a group opened inside another, over-long
--set), every real NaN / Inf / out of range (via --set, so each variable is named), and a mesh
that does not fit in the memory the process may use (RLIMIT_AS).

Each case runs in its own folder holding a copy of its deck (deck.nml) and whatever the case
prepares. The same table runs on the Debug build, where NaN must be refused, not trapped.
"""
import hashlib
import os
import re
import resource
import shutil
import subprocess
import sys

import c2dtest

UNIAXIAL = "uniaxial_compression.nml"
CONTACT = "patch_compression_p1.nml"
CONTACT_TRESCA_PROFILE = None  # threshold profile cases use --set on the contact deck


def snapshot(folder):
    """Everything observable about a folder's entries (not following links)."""
    state = {}
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        st = os.lstat(path)
        if os.path.islink(path):
            state[name] = ("link", os.readlink(path))
        elif os.path.isdir(path):
            state[name] = ("dir", snapshot(path))
        elif os.path.isfile(path):
            with open(path, "rb") as fh:
                state[name] = ("file", st.st_size, st.st_mtime_ns, hashlib.sha256(fh.read()).hexdigest())
        else:
            state[name] = ("special", st.st_mode)
    return state


# Each case: (name, base deck or None, extra args, prepare(folder) or None, pattern, options)
# base deck: 'u' uniaxial, 'c' contact (P1 patch), or a callable writing deck.nml itself.
# The deck is always passed as 'deck.nml' unless options['deck'] says otherwise; the output is
# 'out.h5' unless the args contain -o.

def write(folder, name, text, mode="w"):
    with open(os.path.join(folder, name), mode) as fh:
        fh.write(text)


def deck_text(t, base):
    with open(t.deck(UNIAXIAL if base == "u" else CONTACT)) as fh:
        return fh.read()


def edit(base, old, new):
    """A deck = the base deck with one text replacement."""
    def make(t, folder):
        text = deck_text(t, base)
        assert old in text, old
        write(folder, "deck.nml", text.replace(old, new, 1))
    return make


def gmsh_deck(t, folder):
    """The shipped Hertz cylinder deck and its geometry (mesh:file = 'hertz_cylinder.geo') as deck.nml."""
    shutil.copy(t.deck("hertz_cylinder_p1.nml"), os.path.join(folder, "deck.nml"))
    shutil.copy(t.deck("hertz_cylinder.geo"), os.path.join(folder, "hertz_cylinder.geo"))


def plant_link(name, target):
    """prepare(): a symbolic link `name` -> `target` in the case's folder."""
    return lambda f: os.symlink(target, os.path.join(f, name))


def plant_precious(how, name):
    """prepare(): the user's precious.txt, and under the lock name `name` a symbolic link to it
    (how = 'symlink') or a second hard link (how = 'hardlink')."""
    def make(f):
        write(f, "precious.txt", "the user's data\n")
        if how == "symlink":
            os.symlink("precious.txt", os.path.join(f, name))
        else:
            os.link(os.path.join(f, "precious.txt"), os.path.join(f, name))
    return make


def loop(a, b):
    """prepare(): a symbolic link loop a -> b -> a (stat gives ELOOP)."""
    def make(f):
        os.symlink(b, os.path.join(f, a))
        os.symlink(a, os.path.join(f, b))
    return make


def gmsh_loop_deck(t, folder):
    """The shipped Hertz cylinder deck with mesh:file = 'l.geo', a link loop made by prepare()."""
    with open(t.deck("hertz_cylinder_p1.nml")) as fh:
        text = fh.read()
    assert "'hertz_cylinder.geo'" in text
    write(folder, "deck.nml", text.replace("'hertz_cylinder.geo'", "'l.geo'", 1))


def gmsh_grid_deck(t, folder):
    """tests/regression/geometry/base.nml as deck.nml on a 40 x 25 quad grid written as grid.msh."""
    with open(os.path.join(t.here, "geometry", "base.nml")) as fh:
        text = fh.read()
    write(folder, "deck.nml", text.replace("'square_quads.geo'", "'grid.msh'"))
    c2dtest.write_grid_msh(os.path.join(folder, "grid.msh"), 40, 25)


def nan_cases():
    """(name, base, --set, pattern): every real of every group, NaN, Inf or beyond 1e30."""
    rows = [
        ("young_nan", "u", "material:young=nan", r"material:young = NaN"),
        ("young_inf", "u", "material:young=inf", r"material:young = \+Inf"),
        ("young_1e308", "u", "material:young=1e308", r"material:young = 1e308 is out of range"),
        ("density_1e-308", "u", "material:density=1e-308", r"material:density = 1e-308 is out of range"),
        ("density_nan", "u", "material:density=nan", r"material:density = NaN"),
        ("poisson_nan", "u", "material:poisson=nan", r"material:poisson = NaN"),
        ("lx_1e308", "u", "mesh:lx=1e308", r"mesh:lx = 1e308 is out of range"),
        ("lx_nan", "u", "mesh:lx=nan", r"mesh:lx = NaN"),
        ("ly_minus_inf", "u", "mesh:ly=-inf", r"mesh:ly = -Inf"),
        ("ly_1e-40", "u", "mesh:ly=1e-40", r"mesh:ly = 1e-40 is out of range"),
        ("dirichlet_values_nan", "u", "dirichlet#3:values=nan", r"dirichlet#3:values\(1\) = NaN"),
        ("dirichlet_values_inf", "u", "dirichlet#3:values=-inf", r"dirichlet#3:values\(1\) = -Inf"),
        ("dirichlet_times_nan", "u", "dirichlet#3:times=nan", r"dirichlet#3:times\(1\) = NaN"),
        ("dirichlet_xmin_nan", "u", "dirichlet#1:xmin=nan", r"dirichlet#1:xmin = NaN"),
        ("dirichlet_values_1e31", "u", "dirichlet#3:values=1e31", r"dirichlet#3:values\(1\) = 1e31 is out of range"),
        ("t_ramp_nan", "u", "solver:t_ramp=nan", r"solver:t_ramp = NaN"),
        ("t_end_inf", "u", "solver:t_end=inf", r"solver:t_end = \+Inf"),
        ("dt_nan", "u", "solver:dt=nan", r"solver:dt = NaN"),
        ("dt_factor_nan", "u", "solver:dt_factor=nan", r"solver:dt_factor = NaN"),
        ("alpha_inf", "u", "solver:alpha=inf", r"solver:alpha = \+Inf"),
        ("tol_residual_nan", "u", "solver:tol_residual=nan", r"solver:tol_residual = NaN"),
        ("tol_kinetic_inf", "u", "solver:tol_kinetic=inf", r"solver:tol_kinetic = \+Inf"),
        ("snapshot_nan", "u", "output:snapshot_times=nan", r"output:snapshot_times\(1\) = NaN"),
        ("obstacle_normal_nan", "c", "contact:obstacle_normal=nan,1", r"contact:obstacle_normal\(1\) = NaN"),
        ("obstacle_point_inf", "c", "contact:obstacle_point=0,inf", r"contact:obstacle_point\(2\) = \+Inf"),
        ("origin_nan", "c", "contact:origin=nan,0", r"contact:origin\(1\) = NaN"),
        ("threshold_nan", "c", "contact:threshold=nan", r"contact:threshold = NaN"),
        ("threshold_profile_nan", "c", "contact:threshold_abscissa=0,nan",
         r"contact:threshold_abscissa\(2\) = NaN"),
        ("threshold_values_inf", "c", "contact:threshold_values=inf", r"contact:threshold_values\(1\) = \+Inf"),
        ("penalty_stiffness_nan", "c", "contact:penalty_stiffness=nan", r"contact:penalty_stiffness = NaN"),
        ("contact_xmax_nan", "c", "contact:xmax=nan", r"contact:xmax = NaN"),
        # beyond the double range (the conversion overflows: trapped in Debug) and the 'not given'
        # marker +-huge(1.0) typed by the user: both out of range, in every group
        ("lx_1e999", "u", "mesh:lx=1e999", r"mesh:lx = 1e999 is out of range"),
        ("young_minus_1e400", "u", "material:young=-1e400", r"material:young = -1e400 is out of range"),
        ("t_end_1d999", "u", "solver:t_end=1d999", r"solver:t_end = 1d999 is out of range"),
        ("snapshot_2x1e999", "u", "output:snapshot_times=1e-6, 2*1e999", r"output:snapshot_times = 1e999 is out of range"),
        ("values_marker", "u", "dirichlet#3:values=-1.7976931348623157e308",
         r"dirichlet#3:values = -1\.7976931348623157e308 is out of range"),
        ("xmax_marker", "u", "dirichlet#1:xmax=1.7976931348623157e308",
         r"dirichlet#1:xmax = 1\.7976931348623157e308 is out of range"),
        ("velocity_marker", "u", "initial:velocity=1.7976931348623157e308,0",
         r"initial:velocity = 1\.7976931348623157e308 is out of range"),
        ("dt_marker", "u", "solver:dt=1.7976931348623157e308", r"solver:dt = 1\.7976931348623157e308 is out of range"),
        ("obstacle_point_marker", "c", "contact:obstacle_point=-1.7976931348623157e308,0",
         r"contact:obstacle_point = -1\.7976931348623157e308 is out of range"),
        ("origin_marker", "c", "contact:origin=1.7976931348623157e308,1.7976931348623157e308",
         r"contact:origin = 1\.7976931348623157e308 is out of range"),
        ("threshold_minus_1e999", "c", "contact:threshold=-1e999", r"contact:threshold = -1e999 is out of range"),
        # a tiny bad value keeps its exponent letter in the message (es12.5 printed -1.00000-200)
        ("young_minus_1e-200", "u", "material:young=-1e-200", r"material:young = -1e-200 must be > 0"),
    ]
    return [(name, base, ["--set", s], None, pat, {}) for name, base, s, pat in rows]


def cases():
    big = 2 * 1024 * 1024
    rows = [
        # ---- output names ----
        ("out_is_deck", "u", ["-o", "deck.nml", "--force"], None, r"'deck\.nml' is the deck", {}),
        ("out_is_deck_hard_link", "u", ["-o", "same.h5", "--force"],
         lambda f: os.link(os.path.join(f, "deck.nml"), os.path.join(f, "same.h5")), r"'same\.h5' is the deck", {}),
        ("out_is_deck_symlink", "u", ["-o", "sym.h5", "--force"],
         lambda f: os.symlink("deck.nml", os.path.join(f, "sym.h5")), r"'sym\.h5' is the deck", {}),
        ("out_is_deck_via_dotdot", "u", ["-o", "../%s/deck.nml", "--force"], None, r"is the deck", {"dotdot": True}),
        # the deck's Gmsh geometry is an input too (a new user's -o onto it replaced it with HDF5)
        ("out_is_mesh_file", gmsh_deck, ["-o", "hertz_cylinder.geo", "--force", "--set", "output:xdmf=.false."],
         None, r"'hertz_cylinder\.geo' is the deck's mesh:file 'hertz_cylinder\.geo' itself", {}),
        ("out_is_mesh_file_symlink", gmsh_deck, ["-o", "mesh.h5", "--force"],
         lambda f: os.symlink("hertz_cylinder.geo", os.path.join(f, "mesh.h5")),
         r"'mesh\.h5' is the deck's mesh:file", {}),
        ("out_named_xmf", "u", ["-o", "result.xmf"], None, r"'result\.xmf' would be overwritten by its own XDMF", {}),
        ("sidecar_exists", "u", [], lambda f: write(f, "out.xmf", "mine\n"), r"sidecar 'out\.xmf' exists.*--force", {}),
        ("sidecar_is_deck", "u", ["-o", "run.h5", "--force"], None, r"sidecar 'run\.xmf' is the deck",
         {"deck": "run.xmf"}),
        ("sidecar_is_directory", "u", ["--force"], lambda f: os.mkdir(os.path.join(f, "out.xmf")),
         r"sidecar 'out\.xmf' is a directory", {}),
        ("out_dev_null", "u", ["-o", "/dev/null", "--force"], None, r"'/dev/null' is a device", {}),
        ("out_directory", "u", ["-o", "sub", "--force"], lambda f: os.mkdir(os.path.join(f, "sub")),
         r"'sub' is a directory", {}),
        ("out_trailing_slash", "u", ["-o", "sub/"], lambda f: os.mkdir(os.path.join(f, "sub")),
         r"'sub/' names a directory", {}),
        ("out_missing_folder", "u", ["-o", "nodir/out.h5"], None, r"nodir/.*No such file or directory", {}),
        ("out_parent_is_file", "u", ["-o", "deck.nml/out.h5"], None, r"deck\.nml/out\.h5.*Not a directory", {}),
        ("out_dangling_link", "u", ["-o", "dl.h5"], lambda f: os.symlink("nowhere.h5", os.path.join(f, "dl.h5")),
         r"'dl\.h5' is a dangling symbolic link", {}),
        ("out_name_too_long", "u", ["-o", "a" * 300 + ".h5"], None, r"File name too long", {}),
        ("out_name_5000_chars", "u", ["-o", "/".join(["b" * 200] * 25) + ".h5"], None,
         r"(File name too long|No such file)", {}),
        ("out_fifo", "u", ["-o", "f.h5", "--force"], lambda f: os.mkfifo(os.path.join(f, "f.h5")), r"'f\.h5' is a FIFO", {}),
        ("out_exists", "u", [], lambda f: write(f, "out.h5", "pre-existing\n"), r"'out\.h5' exists.*--force", {}),
        ("out_symlink_loop", "u", ["-o", "l.h5"], loop("l.h5", "m.h5"),
         r"'l\.h5': Too many levels of symbolic links", {}),
        # ---- lock files: created without following links; a planted link or another file is
        # refused and left as it is (its target untouched); a stale lock is taken over (test_faults)
        ("lock_symlink", "u", [], plant_precious("symlink", ".out.h5.lock"),
         r"output 'out\.h5': its lock file '\.out\.h5\.lock' is a symbolic link", {}),
        ("xlock_symlink", "u", [], plant_precious("symlink", ".out.xmf.lock"),
         r"sidecar 'out\.xmf': its lock file '\.out\.xmf\.lock' is a symbolic link", {}),
        ("lock_dangling_symlink", "u", [], plant_link(".out.h5.lock", "made_by_the_run"),
         r"lock file '\.out\.h5\.lock' is a symbolic link", {}),
        ("lock_symlink_loop", "u", [], loop(".out.h5.lock", ".other.lock"),
         r"lock file '\.out\.h5\.lock' is a symbolic link", {}),
        ("lock_hard_link", "u", [], plant_precious("hardlink", ".out.h5.lock"),
         r"lock file '\.out\.h5\.lock' has other hard links", {}),
        ("lock_holds_text", "u", [], lambda f: write(f, ".out.h5.lock", "my notes\n"),
         r"lock file '\.out\.h5\.lock' holds something else than a lock", {}),
        ("lock_fifo", "u", [], lambda f: os.mkfifo(os.path.join(f, ".out.h5.lock")),
         r"lock file '\.out\.h5\.lock' is not a regular file", {}),
        ("lock_directory", "u", [], lambda f: os.mkdir(os.path.join(f, ".out.h5.lock")),
         r"lock file '\.out\.h5\.lock' is not a regular file", {}),
        ("out_empty_name", "u", ["-o", ""], None, r"output file name is empty", {}),
        # ---- deck files ----
        ("deck_directory", None, [], lambda f: os.mkdir(os.path.join(f, "d.nml")), r"'d\.nml' is a directory",
         {"deck": "d.nml"}),
        ("deck_dev_zero", None, [], None, r"'/dev/zero' is a device", {"deck": "/dev/zero"}),
        ("deck_fifo", None, [], lambda f: os.mkfifo(os.path.join(f, "p.nml")), r"'p\.nml' is a FIFO", {"deck": "p.nml"}),
        ("deck_oversized", None, [], lambda f: write(f, "big.nml", "!" * big + "\n"), r"'big\.nml' has \d+ bytes",
         {"deck": "big.nml"}),
        ("deck_missing", None, [], None, r"missing\.nml.*no such file", {"deck": "missing.nml"}),
        ("deck_dangling_link", None, [], lambda f: os.symlink("gone.nml", os.path.join(f, "l.nml")),
         r"'l\.nml'.*dangling", {"deck": "l.nml"}),
        ("deck_symlink_loop", None, [], loop("l.nml", "m.nml"), r"'l\.nml': Too many levels of symbolic links",
         {"deck": "l.nml"}),
        # the deck's Gmsh mesh:file a link loop: the system's reason, not "no such file"
        ("mesh_symlink_loop", gmsh_loop_deck, [], loop("l.geo", "m.geo"),
         r"mesh:file = 'l\.geo': Too many levels of symbolic links", {}),
        # ---- deck text ----
        ("line_1100_blanks", edit("u", "lx = 1.0, ly = 0.5, nx = 8, ny = 4", "lx = 1.0, ly = 0.5, nx = 8, ny = 4," +
                                  " " * 1100 + "level = 3"), [], None, r"deck\.nml:9: line has \d+ characters", {}),
        ("method_too_long", "c", ["--set", "contact:method='penalty method'"], None,
         r"method = 'penalty method' is longer than 8", {}),
        ("method_too_long_in_deck", edit("c", "friction = 'frictionless'", "friction = 'frictionless'\n   method = 'lagrange multipliers'"),
         [], None, r"method = 'lagrange multipliers' is longer than 8", {}),
        ("multiplier_too_long", "c", ["--set", "contact:multiplier='P0000'"], None, r"multiplier = 'P0000' is longer than 4", {}),
        ("edge_too_long", "c", ["--set", "contact:edge='bottom_and_more_than_16'"], None, r"edge = 'bottom_and_more_than_16'", {}),
        ("damping_too_long", "u", ["--set", "solver:damping='automatic'"], None, r"damping = 'automatic' is longer than 8", {}),
        ("component_too_long", "u", ["--set", "dirichlet#1:component='tangential_component'"], None,
         r"component = 'tangential_component' is longer than 16", {}),
        # a real beyond the double range inside the deck (overflowed in the namelist read, Debug trapped)
        ("lx_1e999_in_deck", edit("u", "lx = 1.0, ly = 0.5", "lx = 1e999, ly = 0.5"), [], None,
         r"deck\.nml:9: mesh:lx = 1e999 is out of range", {}),
        ("amp_end", edit("u", "   lx = 1.0, ly = 0.5, nx = 8, ny = 4\n/", "   lx = 1.0, ly = 0.5, nx = 8, ny = 4\n&end"),
         [], None, r"deck\.nml:10: '&end' does not close a group", {}),
        ("group_inside_group", edit("u", "   lx = 1.0, ly = 0.5, nx = 8, ny = 4\n/", "   lx = 1.0, ly = 0.5, nx = 8, ny = 4\n"),
         [], None, r"deck\.nml:11: '&' inside group &mesh", {}),
        ("set_5000_chars", "u", ["--set", "solver:dt_factor=0.5" + " " * 5000 + "x"], None,
         r"--set argument .* longer than the 4096", {}),
        # ---- memory ----
        ("mesh_does_not_fit", "u", ["--set", "mesh:nx=4000", "--set", "mesh:ny=3000"], None,
         r"mesh 12000000 elements, \d+ nodes: cannot allocate the \d+ MiB", {"rlimit_as": 3 * 1024 ** 3}),
        # Gmsh out of memory while refining (1000 quads to level 6: 4.1e6, under the element cap; about
        # 150 MiB of address space go to loading libgmsh): Gmsh's failure, or its crash in refining or
        # in gmshFinalize, or its exit() on the failed allocation (which of the three depends on
        # where the allocation fails, so on the load of the machine), is one line naming the
        # refinement (today's main: SIGSEGV, exit 139, a 150-line backtrace)
        ("gmsh_out_of_memory", gmsh_grid_deck, ["--set", "mesh:level=6"], None,
         r"mesh:file = 'grid\.msh'(: Gmsh refinement \d failed|: the Gmsh library crashed while refining"
         r"|: Gmsh ended the program while refining it \(refinement \d of \d\) \(exit\(\) called by Gmsh: a fatal "
         r"Gmsh error, such as running out of memory)",
         {"rlimit_as": 320 * 1024 ** 2}),
        # ---- derived and cross-checks ----
        ("dt_factor_1e100", "u", ["--set", "solver:dt_factor=1e100", "--set", "solver:allow_unstable=.true."], None,
         r"solver:dt_factor = 1e100 is out of range", {}),
        ("dt_factor_above_critical", "u", ["--set", "solver:dt_factor=1.5"], None, r"exceeds dt_critical", {}),
        ("unknown_option", "u", ["--frce"], None, r"unknown option '--frce' \(usage: contact2d --help\)", {}),
        ("two_decks", "u", ["deck.nml"], None, r"more than one deck given", {}),
    ]
    if os.geteuid() != 0:
        rows.append(("out_readonly_folder", "u", ["-o", "ro/out.h5"], lambda f: (os.mkdir(os.path.join(f, "ro")),
                                                                                os.chmod(os.path.join(f, "ro"), 0o555)),
                     r"Permission denied", {}))
    else:
        print("NOTE: running as root: the read-only folder case is skipped (root may write anywhere)")
    return rows + nan_cases()


def body(t):
    table = cases()
    t.check_ge("hostile", "number of cases", len(table), 60, reason="the hostile classes of docs/output.md, at least 60 inputs")
    for name, base, extra, prepare, pattern, opts in table:
        print()
        print("## case %s" % name)
        folder = t.subdir(name)
        deck = opts.get("deck", "deck.nml")
        if callable(base):
            base(t, folder)
        elif base is not None:
            write(folder, deck, deck_text(t, base))
        if prepare:
            prepare(folder)
        args = [a % name if opts.get("dotdot") and "%s" in a else a for a in extra]
        if "-o" not in args:
            args = ["-o", "out.h5"] + args
        before = snapshot(folder)
        limit = opts.get("rlimit_as")

        def preexec(limit=limit):
            if limit:
                resource.setrlimit(resource.RLIMIT_AS, (limit, limit))

        cmd = [t.exe, deck] + args + ["-q"]
        proc = subprocess.run(cmd, cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=120,
                              preexec_fn=preexec, env={**os.environ, "OMP_NUM_THREADS": "1"})
        err = [line for line in proc.stderr.decode("utf-8", "replace").splitlines() if line.strip()]
        print("   exit %d; stderr: %s" % (proc.returncode, " | ".join(e[:300] for e in err)))
        t.check_equal(name, "exit code", 1, proc.returncode)
        t.check_equal(name, "lines on stderr", 1, len(err))
        first = err[0] if err else ""
        t.check(name, "one line 'contact2d: error:' naming the bad item",
                first.startswith(c2dtest.ERROR_PREFIX) and re.search(pattern, first) is not None,
                "match /%s/" % pattern, repr(first[:400]))
        t.check(name, "the run's folder unchanged", snapshot(folder) == before, "unchanged",
                "changed: %s" % sorted(set(os.listdir(folder)) ^ set(before)))


if __name__ == "__main__":
    c2dtest.Test("hostile input: exit 1, one line naming the item, nothing created or modified").main(body)
