"""pytest set-up shared by the unit tests, the doctests and the notebooks that nbval runs."""

import os

# One BLAS thread for every test worker and every notebook kernel (kernels inherit this
# environment), as ./make.sh sets it, also when pytest is started directly: the problems are small
# and oversubscribed OpenBLAS makes them several times slower (README, "Threads"). A value the
# caller set is kept, so `OPENBLAS_NUM_THREADS=2 pytest ...` still tests two threads.
for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_name, "1")
