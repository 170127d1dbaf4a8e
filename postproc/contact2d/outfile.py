"""The scripts' own output files: nothing a user owns is overwritten silently (module, no script).

    from contact2d.outfile import OutputRefused, check_target, replacing
    check_target("out.json", inputs=["a.h5", "b.h5"], force=args.force)   # before any work
    with replacing("out.json", force=args.force) as tmp:                   # after the work
        write the whole file to tmp (a temporary file beside the target)
    # on success tmp is moved onto the target in one step (os.replace); on failure it is removed

check_target refuses (OutputRefused, a one-line message): one of the command's inputs (always,
--force or not), an existing file unless force, a directory, a folder that does not exist or is
not writable. Only the standard library.

The study scripts (paper_study.py, hertz_study.py, ...) check their products (tables, figures,
reports) before any run and write each one through replacing:

    refuse_existing("paper_study.py", [out / "convergence.csv", ...], force=args.force)  # or exit 2
    save_figure(fig, out / "convergence.png", force=args.force, dpi=130)

and run their main() in `with refusal_exits("paper_study.py"):`, so that a product that appeared
while the study ran is one line and exit 2 as well.
"""
import contextlib
import os
import sys
import tempfile


class OutputRefused(Exception):
    """The output target cannot or may not be written (one-line message)."""


def _same(a, b):
    try:
        return os.path.samefile(a, b)
    except OSError:
        return os.path.realpath(a) == os.path.realpath(b)


def check_target(path, inputs=(), force=False):
    """Refuse a target that is an input, exists (unless force), or sits in a missing folder."""
    path = str(path)
    for inp in inputs:
        if inp is not None and _same(path, str(inp)):
            raise OutputRefused("%s is an input of this command; it is never overwritten" % path)
    if os.path.isdir(path):
        raise OutputRefused("%s is a directory" % path)
    if os.path.lexists(path) and not force:
        raise OutputRefused("%s exists (pass --force to replace it)" % path)
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise OutputRefused("%s: folder %s does not exist" % (path, folder))
    if not os.access(folder, os.W_OK | os.X_OK):
        raise OutputRefused("%s: folder %s is not writable" % (path, folder))


@contextlib.contextmanager
def replacing(path, force=False):
    """Yield a temporary file name beside path; move it onto path when the block succeeds.

    Without force the move never replaces a file that appeared meanwhile (OutputRefused)."""
    path = str(path)
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(dir=folder, prefix="." + os.path.basename(path) + ".", suffix=".tmp")
    os.close(fd)
    try:
        mask = os.umask(0)
        os.umask(mask)
        os.chmod(tmp, 0o666 & ~mask)   # the mode an ordinary open() would give
        yield tmp
        with open(tmp, "rb+") as fh:
            os.fsync(fh.fileno())
        if force:
            os.replace(tmp, path)
        else:
            try:
                os.link(tmp, path)     # fails if path exists: no silent replacement
            except FileExistsError:
                raise OutputRefused("%s appeared while this command ran; not replaced" % path)
            except OSError:            # no hard links here: check, then replace
                if os.path.lexists(path):
                    raise OutputRefused("%s appeared while this command ran; not replaced" % path)
                os.replace(tmp, path)
    finally:
        if os.path.lexists(tmp):
            os.unlink(tmp)


def refuse_existing(prog, paths, force=False):
    """check_target on each of a study's products; the first refused: one line on stderr, exit 2."""
    with refusal_exits(prog):
        for path in paths:
            check_target(path, force=force)


@contextlib.contextmanager
def refusal_exits(prog):
    """An OutputRefused raised in the block (e.g. a product that appeared while the study ran):
    one line on stderr, exit 2, not a traceback."""
    try:
        yield
    except OutputRefused as e:
        print("%s: refused: %s" % (prog, e), file=sys.stderr)
        sys.exit(2)


def save_figure(fig, path, force=False, **kwargs):
    """fig.savefig(path, **kwargs) through replacing (the format is path's extension)."""
    with replacing(path, force=force) as tmp:
        fig.savefig(tmp, format=os.path.splitext(str(path))[1][1:] or None, **kwargs)


if __name__ == "__main__":
    print("contact2d.outfile is a module, not a script (docs/postproc.md): it is used by "
          "postproc/compare.py, getfem_reference.py, plot.py and the study scripts", file=sys.stderr)
    sys.exit(2)
