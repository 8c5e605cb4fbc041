"""Why SuperLU's solves do not run side by side in two threads (the 10k-vertex eigensolver's limit).

``eigenbasis(mesh, 100)`` at 10k vertices runs two Lanczos sets in two threads, each mostly
4-column solves with its own factorisation plus BLAS-3 projections. Side by side the sets take
nearly as long as one after the other. This measures why, with the scan proxy's factorisation
(10.9k unknowns, ``benchmarks/eigen.py``), all with one BLAS thread:

1. 100 solves in one thread against 50 + 50 in two threads (two factorisations);
2. 100 solves beside a thread streaming numpy's BLAS (GIL released, memory-bound): memory
   bandwidth is not what stops them;
3. 100 solves beside a thread running pure Python (holding the GIL): SciPy releases the GIL
   around SuperLU's solve (``_superluobject.c``), so that thread does not slow, but each solve
   takes it back a few times (SciPy's SuperLU allocator), so the solves do;
4. with a C compiler present: SuperLU's supernodal solve is many small ``dtrsm`` + ``dgemm``
   calls into SciPy's OpenBLAS. A C program (no Python) makes such calls from one thread and
   from two: the small ones do not run side by side at all.

Run: ``python benchmarks/superlu_threads.py``.

One recorded run and what it showed: ``benchmarks/results/superlu-threads-history.md``.
"""

from __future__ import annotations

import glob
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import numpy as np
import scipy

sys.path.insert(0, str(Path(__file__).resolve().parent))
import eigen  # noqa: E402

from lbo_notebooks import mass_matrix, stiffness_matrix  # noqa: E402
from lbo_notebooks.spectral._engine.threads import one_blas_thread  # noqa: E402
from lbo_notebooks.spectral._engine.factor import symmetric_lu  # noqa: E402

C_PROGRAM = r"""
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
extern void scipy_dtrsm_(char*, char*, char*, char*, int*, int*, double*, double*, int*, double*, int*);
extern void scipy_dgemm_(char*, char*, int*, int*, int*, double*, double*, int*, double*, int*, double*, double*, int*);
extern void scipy_openblas_set_num_threads(int);
static int NS, NR = 4, RO;
static double now(void) { struct timespec t; clock_gettime(CLOCK_MONOTONIC, &t); return t.tv_sec + 1e-9 * t.tv_nsec; }
static void *work(void *arg) {
    long n = (long)arg;
    double *L = calloc(NS * NS, 8), *B = calloc(NS * NR, 8), *A = calloc(RO * NS, 8), *C = calloc(RO * NR, 8);
    double one = 1, minus = -1;
    for (int i = 0; i < NS; i++) L[i * NS + i] = 1;
    for (long k = 0; k < n; k++) {
        scipy_dtrsm_("L", "L", "N", "U", &NS, &NR, &one, L, &NS, B, &NS);
        scipy_dgemm_("N", "N", &RO, &NR, &NS, &minus, A, &RO, B, &NS, &one, C, &RO);
    }
    free(L); free(B); free(A); free(C);
    return 0;
}
int main(int argc, char **argv) {
    NS = atoi(argv[1]); RO = atoi(argv[2]);
    long n = 200000;
    scipy_openblas_set_num_threads(1);
    double t = now(); work((void *)n); double one_thread = now() - t;
    pthread_t th[2];
    t = now();
    for (int i = 0; i < 2; i++) pthread_create(&th[i], 0, work, (void *)(n / 2));
    for (int i = 0; i < 2; i++) pthread_join(th[i], 0);
    printf("%.4f %.4f\n", one_thread, now() - t);
    return 0;
}
"""


def _timed(fn, *args) -> float:
    start = time.perf_counter()
    fn(*args)
    return time.perf_counter() - start


def _beside(background, foreground) -> tuple[float, float]:
    """Wall times of ``foreground()`` and ``background()`` started together in two threads."""
    out = {}
    thread = threading.Thread(target=lambda: out.setdefault("background", _timed(background)))
    thread.start()
    front = _timed(foreground)
    thread.join()
    return front, out["background"]


def python_measurements() -> None:
    mesh = eigen.scan_proxy()
    W, A = stiffness_matrix(mesh), mass_matrix(mesh)
    factors = [symmetric_lu(W - shift * A) for shift in (30.0, 60.0)]
    rhs = np.asfortranarray(np.random.default_rng(0).standard_normal((mesh.n_vertices, 4)))
    block = np.random.default_rng(1).standard_normal((mesh.n_vertices, 200))

    def solves(factor, count):
        for _ in range(count):
            factor.solve(rhs)

    def stream():
        for _ in range(60):
            block.T @ rhs

    def python_loop():
        total = 0
        for i in range(3_000_000):
            total += i

    solves(factors[0], 5)
    one = _timed(solves, factors[0], 100)
    pair = [threading.Thread(target=solves, args=(factor, 50)) for factor in factors]
    start = time.perf_counter()
    for thread in pair:
        thread.start()
    for thread in pair:
        thread.join()
    two = time.perf_counter() - start
    print(f"1. solves: one thread {one:.3f} s, two threads {two:.3f} s ({one / two:.2f}x)")
    stream_alone = _timed(stream)
    front, back = _beside(stream, lambda: solves(factors[0], 100))
    print(f"2. beside numpy's BLAS: {front:.3f} s (alone {one:.3f} s); the stream {back:.3f} s (alone {stream_alone:.3f} s)")
    loop_alone = _timed(python_loop)
    front, back = _beside(python_loop, lambda: solves(factors[0], 100))
    print(f"3. beside pure Python: {front:.3f} s; the Python loop {back:.3f} s (alone {loop_alone:.3f} s)")


def c_measurements() -> None:
    compiler = shutil.which("cc") or shutil.which("gcc")
    libraries = glob.glob(str(Path(scipy.__file__).parent.parent / "scipy.libs" / "libscipy_openblas*.so"))
    if compiler is None or not libraries:
        print("4. skipped: needs a C compiler and SciPy's bundled OpenBLAS (a Linux wheel)")
        return
    with tempfile.TemporaryDirectory() as work:
        source, program = Path(work) / "blas_threads.c", Path(work) / "blas_threads"
        source.write_text(C_PROGRAM)
        library = Path(libraries[0])
        build = [compiler, "-O2", str(source), "-o", str(program), str(library), "-lpthread", f"-Wl,-rpath,{library.parent}"]
        if subprocess.run(build, capture_output=True, check=False).returncode:
            print("4. skipped: the C program did not build against SciPy's OpenBLAS")
            return
        cells = []
        for supernode, rows in ((4, 10), (8, 20), (32, 100)):
            out = subprocess.run([str(program), str(supernode), str(rows)], capture_output=True, text=True, check=True)
            one, two = (float(x) for x in out.stdout.split())
            cells.append(f"{supernode}x4 / {rows}x{supernode}x4: {one / two:.2f}x")
        print("4. dtrsm + dgemm in two threads (speed-up over one):", "; ".join(cells))


def main() -> None:
    with one_blas_thread():
        python_measurements()
    c_measurements()


if __name__ == "__main__":
    main()
