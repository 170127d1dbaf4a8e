"""Read contact2d output files (docs/output.md, SPEC section 8) with h5py and numpy.

    from c2dh5 import Run
    run = Run("baillet_sassi_2002_p1.h5")
    run.deck["mesh"]["nx"], run.coordinates, run.displacement, run.history("residual")

Only the standard library, numpy and h5py are needed (Debian: python3-numpy python3-h5py).
"""
import re

import h5py

_GROUP = re.compile(r"^\s*&(\w+)\s*$")
_ITEM = re.compile(r"^\s*(\w+)\s*=\s*(.*?)\s*$")


def _value(text):
    """One namelist value of the effective deck: quoted string, logical, number or list."""
    text = text.strip()
    if text.startswith("'") or text.startswith('"'):
        return text[1:-1]
    if text.lower() in (".true.", "t"):
        return True
    if text.lower() in (".false.", "f"):
        return False
    parts = [p.strip() for p in text.split(",")]
    nums = []
    for p in parts:
        try:
            nums.append(int(p))
        except ValueError:
            nums.append(float(p.replace("d", "e").replace("D", "e")))
    return nums[0] if len(nums) == 1 else nums


def parse_effective_deck(text):
    """The 'effective_deck' attribute (one 'key = value' per line) as a dict of groups.

    Groups that may repeat (dirichlet, traction) map to lists of dicts, the others to dicts.
    List-valued variables ('values', 'times', ...) always come back as lists.
    """
    deck = {"dirichlet": [], "traction": []}
    current = None
    for line in text.splitlines():
        m = _GROUP.match(line)
        if m:
            current = {}
            name = m.group(1).lower()
            if name in ("dirichlet", "traction"):
                deck[name].append(current)
            else:
                deck[name] = current
            continue
        if line.strip() == "/":
            current = None
            continue
        m = _ITEM.match(line)
        if m and current is not None:
            key, val = m.group(1).lower(), _value(m.group(2))
            if key in ("values", "times", "threshold_abscissa", "threshold_values", "snapshot_times",
                       "obstacle_point", "obstacle_normal", "origin", "velocity") and not isinstance(val, list):
                val = [val]
            current[key] = val
    return deck


class Run:
    """One contact2d output file, opened read-only."""

    def __init__(self, path):
        self.path = str(path)
        self.file = h5py.File(self.path, "r")
        self.attrs = dict(self.file.attrs)
        self.deck = parse_effective_deck(self.attrs.get("effective_deck", ""))

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.file.close()

    def close(self):
        self.file.close()

    @property
    def coordinates(self):
        """(nnode, 2) node coordinates [mm]."""
        return self.file["mesh/coordinates"][()]

    @property
    def connectivity(self):
        """(nel, 4) 1-based, counter-clockwise from the bottom-left node."""
        return self.file["mesh/connectivity"][()]

    @property
    def nx(self):
        return int(self.attrs["nx"])

    @property
    def ny(self):
        return int(self.attrs["ny"])

    @property
    def displacement(self):
        """(nnode, 2) final displacement [mm]."""
        return self.file["final/displacement"][()]

    @property
    def has_contact(self):
        return "contact" in self.file

    def contact(self, name):
        """/final/contact/<name> (normal_force, tangential_force, pressure, shear, status)."""
        return self.file["final/contact/" + name][()]

    @property
    def contact_nodes(self):
        """0-based node indices along Gamma_c (the file stores 1-based ids)."""
        return self.file["contact/nodes"][()] - 1

    @property
    def abscissa(self):
        return self.file["contact/abscissa"][()]

    def history(self, name):
        return self.file["history/" + name][()]

    @property
    def material(self):
        m = self.deck["material"]
        return float(m["young"]), float(m["poisson"]), float(m["density"])


if __name__ == "__main__":
    import sys

    print("c2dh5.py is a module, not a script: it is used by "
          "postproc/compare.py, paper_study.py, getfem_reference.py, the other study scripts "
          "and tests/regression/c2dtest.py", file=sys.stderr)
    sys.exit(2)
