"""The static summary's contact line: total forces per unit thickness in N/mm (plane strain), and
three-digit exponents printed with their letter.

patch_compression_p1 with --static: a block of height H = 0.5 mm pressed by delta on a rigid plane,
frictionless; the contact pressure is p = E delta / (H (1 - nu^2)) everywhere, so the total normal
force per unit thickness is F_n = p L (L = 1 mm). The summary prints it with 4 significant digits:
- delta = 1e-3 mm (the deck): F_n = 153.8 N/mm, '1.538E+02 N/mm';
- delta = 1e-125 mm (a linear problem: the same solution scaled): F_n = 1.538e-120 N/mm, printed
  '1.538E-120' (an Ew.d format without Ee printed '1.538-120', which reads back as 1.538).
The HDF5 units of the forces (contact forces, reaction, their history totals) are 'N/mm'.
"""
import re

import c2dtest

E, NU, H, L = 7.0e4, 0.3, 0.5, 1.0


def body(t):
    for name, delta in (("deck", 1.0e-3), ("tiny", 1.0e-125)):
        run = t.run(t.deck("patch_compression_p1.nml"), "--static", "--set", "dirichlet#1:values=%r" % -delta,
                    name=name)
        t.expect_exit(run, 0)
        m = re.search(r"total F_n = (\S+) (\S+), F_t = (\S+) (\S+)", run.stdout)
        t.check(run, "summary has 'total F_n = <number> <unit>, F_t = ...'", m is not None, "a match",
                [l for l in run.stdout.splitlines() if "F_n" in l])
        if not m:
            continue
        fn_text, fn_unit, _, ft_unit = m.groups()
        t.check(run, "F_n printed with its exponent letter", re.fullmatch(r"-?\d\.\d{3}E[+-]\d{2,3}", fn_text)
                is not None, "d.dddE+-dd(d)", fn_text)
        t.check_close(run, "F_n = p L = E delta L / (H (1 - nu^2)) (4 digits)", E * delta * L / (H * (1 - NU ** 2)),
                      float(fn_text), rtol=5e-4)
        t.check_equal(run, "unit of F_n", "N/mm", fn_unit)
        t.check_equal(run, "unit of F_t", "N/mm", ft_unit)
        with run.open() as f:
            for path in ("final/contact/normal_force", "final/contact/tangential_force", "final/reaction",
                         "history/normal_force_total", "history/tangential_force_total"):
                units = f[path].attrs["units"]
                units = units.decode() if isinstance(units, bytes) else str(units)
                t.check_equal(run, "units of /" + path, "N/mm", units)


if __name__ == "__main__":
    c2dtest.Test(__doc__.splitlines()[0]).main(body)
