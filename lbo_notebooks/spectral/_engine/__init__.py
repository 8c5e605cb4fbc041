"""The private eigensolver engine: sparse matrices in, eigenpairs and factorisations out.

Nothing here takes a mesh, and nothing here is public: the analyses reach it through
:mod:`lbo_notebooks.spectral._solvers`, and :mod:`lbo_notebooks.spectral._spectrum` drives the eigensolver.

* ``policy`` -- dense or sparse, the default shift of shift-invert, the largest shift worth
  taking, the fixed Lanczos start vector;
* ``factor`` -- the one symmetric sparse factorisation (fill-reducing order, diagonal pivots)
  and the Sylvester count of eigenvalues below a value;
* ``krylov`` -- block shift-invert Lanczos for the eigenpairs nearest a shift;
* ``slicing`` -- where the windows of the spectrum go and how many eigenpairs each holds;
* ``eigensolver`` -- spectrum slicing: the windows in parallel, counted, completed and stitched;
* ``threads`` -- the thread policy: worker threads, one BLAS thread meanwhile, an idle machine.
"""
