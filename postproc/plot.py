#!/usr/bin/python3
"""The command line of contact2d.plot (docs/postproc.md):

    postproc/plot.py RUN.h5 [-o PREFIX] [--force]

Run it from anywhere: Python searches a script's own folder (postproc/) first, so it finds
the package contact2d beside it. `python3 -m contact2d plot` with PYTHONPATH=postproc is the same.
"""
import sys

from contact2d.plot import main

if __name__ == "__main__":
    sys.exit(main())
