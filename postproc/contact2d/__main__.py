"""`python3 -m contact2d COMMAND ...` (PYTHONPATH=postproc): the package's command-line tools.

Each command is also a script, `python3 postproc/COMMAND.py ...` (docs/postproc.md).
"""
import importlib
import sys

#: command -> (module, one line)
COMMANDS = {
    "plot": ("plot", "contact fields along Gamma_c and histories of one run as PNG"),
    "compare": ("compare", "SPEC section 9 errors between two runs on nested meshes"),
    "getfem_reference": ("getfem_reference", "the same discrete problem solved statically by GetFEM"),
    "getfem_coulomb": ("getfem_coulomb", "GetFEM's quasi-static Coulomb solution along the run's load path"),
    "mindlin": ("mindlin", "a Coulomb partial-slip run against Cattaneo-Mindlin"),
}


def usage():
    return ("usage: python3 -m contact2d COMMAND [ARGS ...]   (COMMAND --help for its options)\n\ncommands:\n"
            + "".join("  %-17s %s\n" % (c, text) for c, (_, text) in COMMANDS.items()))


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if not argv or argv[0] in ("-h", "--help"):
        sys.stdout.write(usage())
        return 0 if argv else 2
    if argv[0] not in COMMANDS:
        print("contact2d: error: unknown command '%s' (one of: %s)" % (argv[0], ", ".join(COMMANDS)),
              file=sys.stderr)
        return 2
    module = importlib.import_module("." + COMMANDS[argv[0]][0], __package__)
    sys.argv = ["contact2d " + argv[0]] + argv[1:]   # argparse names the command so in --help and errors
    return module.main(argv[1:])


if __name__ == "__main__":
    sys.exit(main())
