#!/usr/bin/python3
"""The command line of contact2d.mindlin (docs/postproc.md):

    postproc/mindlin.py RUN.h5 [RUN2.h5 ...] [--figure docs/figures/mindlin_shear.png [--pressed PRESSED.h5]]

Run it from anywhere: Python searches a script's own folder (postproc/) first, so it finds
the package contact2d beside it. `python3 -m contact2d.mindlin` with PYTHONPATH=postproc is the same.
"""
import sys

from contact2d.mindlin import main

if __name__ == "__main__":
    sys.exit(main())
