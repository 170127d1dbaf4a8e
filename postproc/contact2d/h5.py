"""Read contact2d output files (docs/output.md, SPEC section 8) with h5py and numpy.

    from contact2d import open_run
    with open_run("baillet_sassi_2002_p1.h5") as run:       # RunFileError: one-line reason
        run.attr("status"), run.attr("dt"), run.attr_units("dt")      # 'converged', 3.1e-09, 's'
        run.deck["mesh"]["nx"]                                        # the effective deck, parsed
        x, conn = run.coordinates, run.connectivity                   # /mesh [mm], 1-based ids
        t = run.history("time"); e = run.histories()                  # /history/<name>, all of them
        u = run.displacement; s = run.final("stress")                 # /final/<name>
        p = run.contact("pressure"); xi = run.abscissa                # /final/contact, /contact
        run.units("final/contact/pressure")                           # 'MPa' (every dataset has one)

`open_run` checks the file (exists, HDF5, the SPEC 8 datasets /mesh/coordinates and
/final/displacement) and raises RunFileError (an OSError) with one line; `Run(path)` opens any
HDF5 file in this layout without checks (GetFEM references, files cut short). Every dataset
carries its unit in a `units` attribute (`units(path)`); root attributes carry none, so
`attr_units(name)` gives the unit docs/output.md states for them.

Only the standard library, numpy and h5py are needed (Debian: python3-numpy python3-h5py).
"""
import os
import re

import h5py
import numpy as np

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

    Groups that may repeat (dirichlet, traction, body) map to lists of dicts, the others to dicts.
    &contact may repeat too (one group per contact pair): 'contact' is the first group's dict (as
    for a deck with one pair), 'contacts' the list of all of them.
    List-valued variables ('values', 'times', ...) always come back as lists.
    """
    deck = {"dirichlet": [], "traction": [], "body": [], "contacts": []}
    current = None
    for line in text.splitlines():
        m = _GROUP.match(line)
        if m:
            current = {}
            name = m.group(1).lower()
            if name in ("dirichlet", "traction", "body"):
                deck[name].append(current)
            elif name == "contact":
                deck["contacts"].append(current)
                deck.setdefault("contact", current)
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


#: Units of the root attributes [docs/output.md, "Root attributes"]; the datasets carry their own.
ROOT_UNITS = {
    "dt": "s", "dt_critical": "s", "dt_initial": "s", "dt_stable_estimate": "s",
    "omega_max_element": "1/s", "omega_max_power": "1/s",
    "added_mass": "t", "body_mass": "t", "initial_kinetic_energy": "mJ",
    "final_time": "s", "snapshot_times_not_reached": "s",
    "wall_seconds": "s", "time_setup_seconds": "s", "time_steps_seconds": "s",
    "time_contact_seconds": "s", "time_output_seconds": "s", "time_factor_seconds": "s",
    "time_condense_seconds": "s", "time_solve_seconds": "s",
    "kkt_normal_feasibility": "1", "kkt_complementarity": "1", "kkt_friction_feasibility": "1",
    "kkt_equilibrium": "1", "static_distance_energy": "1",
}


class RunFileError(OSError):
    """A file open_run cannot read as a contact2d run (one-line message naming the file)."""


def _plain(value):
    """An attribute as Python: bytes -> str, numpy scalars -> int/float, arrays kept."""
    if isinstance(value, bytes):
        return value.decode("utf-8", "replace")
    if isinstance(value, np.ndarray):
        if value.dtype.kind in "SO":
            return [_plain(v) for v in value.tolist()]
        return value
    if isinstance(value, np.generic):
        return value.item()
    return value


class Run:
    """One contact2d output file, opened read-only (the layout of docs/output.md)."""

    def __init__(self, path):
        self.path = str(path)
        self.file = h5py.File(self.path, "r")
        self.attrs = dict(self.file.attrs)
        self.deck = parse_effective_deck(_plain(self.attrs.get("effective_deck", "")))

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.file.close()

    def close(self):
        self.file.close()

    # -- root attributes ----------------------------------------------------------------------
    def attr(self, name, default=None):
        """Root attribute `name` as Python (str, int, float or array), default when absent."""
        return _plain(self.attrs[name]) if name in self.attrs else default

    @staticmethod
    def attr_units(name):
        """Unit of root attribute `name` as docs/output.md states it, None for counts and text."""
        return ROOT_UNITS.get(name)

    @property
    def status(self):
        """Final status ('converged', 'dynamic', 'blow-up', ...; 'running' while it runs)."""
        return self.attr("status", "")

    # -- any dataset --------------------------------------------------------------------------
    def has(self, path):
        """Whether the file holds the dataset or group `path` (e.g. 'final/contact/pressure')."""
        return path.strip("/") in self.file

    def read(self, path):
        """The dataset `path` as a numpy array."""
        return self.file[path.strip("/")][()]

    def units(self, path):
        """The `units` attribute of dataset `path` (e.g. 'MPa'), '' when it has none."""
        return _plain(self.file[path.strip("/")].attrs.get("units", ""))

    # -- /mesh --------------------------------------------------------------------------------
    @property
    def coordinates(self):
        """(nnode, 2) node coordinates [mm]."""
        return self.file["mesh/coordinates"][()]

    @property
    def connectivity(self):
        """(nel, 4) 1-based, counter-clockwise from the bottom-left node."""
        return self.file["mesh/connectivity"][()]

    @property
    def mass(self):
        """(nnode,) lumped nodal mass [t]."""
        return self.file["mesh/mass"][()]

    @property
    def body(self):
        """(nel,) body of each element, 1-based (all 1 in a file written before bodies existed)."""
        if "mesh/body" in self.file:
            return self.file["mesh/body"][()]
        return np.ones(len(self.connectivity), dtype=np.int32)

    @property
    def node_body(self):
        """(nnode,) body of each node, 1-based: the lowest body of its elements."""
        if "mesh/node_body" in self.file:
            return self.file["mesh/node_body"][()]
        return np.ones(len(self.coordinates), dtype=np.int32)

    @property
    def body_names(self):
        """The body names, body k at index k - 1 (['body'] in a file written before bodies existed)."""
        a = self.file["mesh"].attrs
        if "body_count" not in a:
            return ["body"]
        return [_plain(a["body_name_%d" % k]) for k in range(1, int(a["body_count"]) + 1)]

    @property
    def nx(self):
        return int(self.attrs["nx"])

    @property
    def ny(self):
        return int(self.attrs["ny"])

    # -- /history -----------------------------------------------------------------------------
    @property
    def history_names(self):
        """Names of the /history series, sorted."""
        return sorted(self.file["history"].keys()) if "history" in self.file else []

    def history(self, name, pair=None):
        """/history/<name>: one value per sample [units(f'history/{name}')]. With several contact
        pairs and `pair` (a name or 1-based index) given, that pair's series '<pair name>_<name>'
        (docs/output.md "Several contact pairs"); a file with one pair: its series."""
        if pair is not None and self._pair_group(pair):
            return self.file["history/%s_%s" % (self.pair_names[self._pair_index(pair)], name)][()]
        return self.file["history/" + name][()]

    def histories(self):
        """Every /history series as {name: 1D array} (all of one length)."""
        return {name: self.history(name) for name in self.history_names}

    # -- /final -------------------------------------------------------------------------------
    def final(self, name):
        """/final/<name>: displacement, velocity [mm/s], stress [MPa], reaction [N], ..."""
        return self.file["final/" + name][()]

    @property
    def displacement(self):
        """(nnode, 2) final displacement [mm]."""
        return self.file["final/displacement"][()]

    # -- contact: /contact (set-up) and /final/contact (end state) ----------------------------
    # Each contact reader takes `pair`: a pair's name or 1-based index, None for the first (the
    # only one of a file with one pair, whose data sit directly in /contact and /final/contact;
    # with several they sit in /contact/<name> and /final/contact/<name>, docs/output.md).
    @property
    def has_contact(self):
        return "contact" in self.file

    @property
    def pair_names(self):
        """The contact pairs' names in the deck's order ([] without contact; one pair: its
        contact:name, 'contact' unless the deck names it)."""
        if "contact" not in self.file:
            return []
        a = self.file["contact"].attrs
        if "pair_count" in a:
            return [_plain(a["pair_name_%d" % k]) for k in range(1, int(a["pair_count"]) + 1)]
        return [str(self.deck.get("contact", {}).get("name", "contact"))]

    def _pair_index(self, pair):
        """0-based index of `pair` (None: the first; a name; a 1-based index); KeyError naming it."""
        names = self.pair_names
        if not names:
            raise KeyError("%s: no contact pair (no /contact)" % self.path)
        if pair is None:
            return 0
        if isinstance(pair, (int, np.integer)) and not isinstance(pair, bool):
            if 1 <= pair <= len(names):
                return int(pair) - 1
        elif pair in names:
            return names.index(pair)
        raise KeyError("%s: no contact pair %r; its pairs: %s" % (self.path, pair, ", ".join(names)))

    def _pair_group(self, pair):
        """'' for a file with one pair, '/<name>' of `pair` for a file with several."""
        k = self._pair_index(pair)
        if "pair_count" in self.file["contact"].attrs:
            return "/" + self.pair_names[k]
        return ""

    def contact(self, name, pair=None):
        """/final/contact[/<pair>]/<name> (normal_force, tangential_force, pressure, shear, status)."""
        return self.file["final/contact%s/%s" % (self._pair_group(pair), name)][()]

    def contact_setup(self, name, pair=None):
        """/contact[/<pair>]/<name>: nodes (1-based), abscissa, weight, gap, normal, threshold."""
        return self.file["contact%s/%s" % (self._pair_group(pair), name)][()]

    def pair_nodes(self, pair=None):
        """0-based node indices along the pair's Gamma_c (the file stores 1-based ids)."""
        return self.contact_setup("nodes", pair) - 1

    @property
    def contact_nodes(self):
        """0-based node indices along Gamma_c of the first pair (pair_nodes for the others)."""
        return self.pair_nodes()

    @property
    def abscissa(self):
        """(ncontact,) curvilinear abscissa along Gamma_c of the first pair [mm]
        (contact_setup('abscissa', pair) for the others)."""
        return self.contact_setup("abscissa")

    def contact_gap(self, pair=None):
        """(ncontact,) gap at the end, g_i - u_i.n_i [mm] (SPEC section 3: d_i = u_i.n - g_i is the
        penetration, so the gap is -d_i; > 0 open, 0 closed)."""
        u = self.displacement[self.pair_nodes(pair)]
        n = self.contact_setup("normal", pair).reshape(-1, 2)
        return self.contact_setup("gap", pair) - np.einsum("ij,ij->i", u, n)

    # -- /fields/<step> snapshots -------------------------------------------------------------
    def snapshots(self):
        """The /fields/<step> groups (h5py groups; attribute `time` [s]), by increasing time."""
        if "fields" not in self.file:
            return []
        return sorted(self.file["fields"].values(), key=lambda g: float(g.attrs["time"]))

    @property
    def material(self):
        m = self.deck["material"]
        return float(m["young"]), float(m["poisson"]), float(m["density"])


def open_run(path):
    """A Run of `path` after checking it is a readable contact2d output file, else RunFileError
    with one line naming the file and the reason."""
    path = str(path)
    if not os.path.exists(path):
        raise RunFileError("%s: no such file" % path)
    if os.path.isdir(path):
        raise RunFileError("%s: is a directory" % path)
    try:
        run = Run(path)
    except OSError as exc:
        raise RunFileError("%s: not a readable HDF5 file (%s)" % (path, str(exc).splitlines()[0]))
    for name in ("mesh/coordinates", "mesh/connectivity", "final/displacement"):
        if name not in run.file:
            run.close()
            raise RunFileError("%s: no /%s (not a contact2d output file)" % (path, name))
    return run


if __name__ == "__main__":
    import sys

    print("contact2d.h5 is a module, not a script (docs/postproc.md): it is used by "
          "postproc/compare.py, the study scripts and tests/regression/c2dtest.py", file=sys.stderr)
    sys.exit(2)
