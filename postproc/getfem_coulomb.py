#!/usr/bin/python3
"""The command line of contact2d.getfem_coulomb (docs/postproc.md):

    postproc/getfem_coulomb.py IN.h5 -o REF.h5 [--force] [--increments 20] [--tol 1e-12] [--side NAME=SIDE ...]

Run it from anywhere: Python searches a script's own folder (postproc/) first, so it finds
the package contact2d beside it. `python3 -m contact2d.getfem_coulomb` with PYTHONPATH=postproc is the same.
"""
import sys

from contact2d.getfem_coulomb import main

if __name__ == "__main__":
    sys.exit(main())
