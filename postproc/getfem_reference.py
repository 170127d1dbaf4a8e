#!/usr/bin/python3
"""The command line of contact2d.getfem_reference (docs/postproc.md):

    postproc/getfem_reference.py IN.h5 -o REF.h5 [--force] [--multiplier P1|P0]

Run it from anywhere: Python searches a script's own folder (postproc/) first, so it finds
the package contact2d beside it. `python3 -m contact2d.getfem_reference` with PYTHONPATH=postproc is the same.
"""
import sys

from contact2d.getfem_reference import main

if __name__ == "__main__":
    sys.exit(main())
