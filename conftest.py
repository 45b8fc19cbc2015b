"""Test-wide settings: Qt draws offscreen so the suite runs on machines with no display, and
OpenBLAS keeps to one thread as the command line does (timeline.cli.main.one_blas_thread)."""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # before anything loads numpy
os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
os.environ.setdefault("MPLBACKEND", "Agg")
