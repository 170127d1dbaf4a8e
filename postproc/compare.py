#!/usr/bin/python3
"""The command line of contact2d.compare (docs/postproc.md):

    postproc/compare.py A.h5 B.h5 [--json OUT.json [--force]] [--allow-mixed-multipliers]

Run it from anywhere: Python searches a script's own folder (postproc/) first, so it finds
the package contact2d beside it. `python3 -m contact2d.compare` with PYTHONPATH=postproc is the same.
"""
import sys

from contact2d.compare import main

if __name__ == "__main__":
    sys.exit(main())
