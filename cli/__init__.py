"""The rocketsim command line (installed as ``rocketsim_cli``).

The command's process runs OpenBLAS (numpy's and scipy's linear algebra) on one
thread unless ``OPENBLAS_NUM_THREADS`` says otherwise: a flight's arithmetic is on
3-vectors and small matrices in compiled kernels, where BLAS threads only cost their
start (measured warm, whole process, 2 cores: ``fly scenarios/iss-coast.yaml
--duration 0`` 1.27-1.45 s with OpenBLAS's default threads, 1.01-1.04 s with one;
``validate`` 0.43-0.51 s of CPU against 0.25-0.30 s). It is set before anything
imports numpy, and the worker processes of a campaign's embedded cluster inherit it.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
