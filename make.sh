#!/usr/bin/env bash
# One entry point for set-up, JupyterLab and the test suite (see README.md).
#
#   ./make.sh lab     install everything into .venv and open JupyterLab on notebooks/00_start_here.ipynb
#   ./make.sh test    install everything (with test extras) and run unit tests + every notebook
#   ./make.sh browser real-browser test: JupyterLab driven by Debian's chromium (Playwright)
#   ./make.sh binder  rebuild a fresh environment from binder/ only and run the notebooks in it
#   ./make.sh site    execute the notebooks and build the site (notebooks, API reference, docs; Sphinx)
#                     into build/site: offline, open build/site/index.html
#   ./make.sh student write the student edition (solutions removed by nbgrader) into build/student;
#                     `student --check` also runs it unanswered and autogrades the instructor's answers,
#                     `student lab` opens JupyterLab on it for self-study (docs/exercises.md)
#   ./make.sh course DIR  write a ready nbgrader course to DIR, one assignment per notebook;
#                     `course --check` runs the nbgrader workflow on a simulated class (CI)
#   ./make.sh slides  lecture slides, one reveal.js deck per notebook, into build/slides (offline;
#                     npm fetches reveal.js once into build/vendor); `slides booklet` builds both
#   ./make.sh booklet the lecturers' solutions booklet (every exercise, solution, rubric) into build/booklet
#   ./make.sh bench   print the benchmark tables (benchmarks/*.py)
#   ./make.sh install only install
#   ./make.sh pull    update a clone in which notebooks have been run (see README, "Course staff")
#
# Works from a bare Debian 12 machine with Python >= 3.10: missing system libraries are
# installed with apt-get when we are root (or through sudo); otherwise the exact command is printed.
set -euo pipefail
cd "$(dirname "$0")"

VENV=${VENV:-.venv}
PYTHON=${PYTHON:-python3}
SYSTEM_PACKAGES=(libusb-1.0-0 libgl1 libegl1 libgomp1)

log() { printf '\033[1m[lbo_notebooks]\033[0m %s\n' "$*" >&2; }

as_root() {
  if [ "$(id -u)" = 0 ]; then "$@"
  elif command -v sudo >/dev/null 2>&1; then sudo "$@"
  else return 1; fi
}

system_packages() {
  local missing=()
  command -v dpkg-query >/dev/null 2>&1 || { log "not a Debian/Ubuntu system: make sure ${SYSTEM_PACKAGES[*]} (or their equivalents) are installed"; return 0; }
  for p in "${SYSTEM_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p")
  done
  if ! "$PYTHON" -c 'import venv, ensurepip' >/dev/null 2>&1; then
    missing+=("python3-venv")
  fi
  [ ${#missing[@]} -eq 0 ] && return 0
  log "installing system packages: ${missing[*]} (open3d needs libusb-1.0-0 and OpenGL libraries)"
  if ! { as_root apt-get update -qq && as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" >/dev/null; }; then
    log "could not install them; run:  sudo apt-get install -y ${missing[*]}"
    exit 1
  fi
}

python_env() {
  "$PYTHON" -c 'import sys; sys.exit(sys.version_info < (3, 10))' || { log "Python >= 3.10 is required (found $("$PYTHON" --version))"; exit 1; }
  [ -x "$VENV/bin/python" ] || { log "creating virtual environment $VENV"; "$PYTHON" -m venv "$VENV"; }
  # -q: errors and real warnings only. (The setuptools "Editable installation" box is gone at its
  # cause: pyproject.toml declares the flat layout, package-dir "" = ".".)
  "$VENV/bin/python" -m pip install -q --upgrade pip
  log "installing lbo_notebooks and its dependencies ($1)"
  "$VENV/bin/python" -m pip install -q -e ".$1"
  # JupyterLab settings shared with Binder: no "Build Recommended" pop-up (dash, pulled in by
  # open3d, ships an extension that triggers it) and no "official Jupyter news?" question.
  mkdir -p "$VENV/etc/jupyter/labconfig"
  cp binder/page_config.json "$VENV/etc/jupyter/labconfig/page_config.json"
  git_filter
}

# Notebooks run in JupyterLab get outputs written into them by autosave; this clean filter
# makes git see them as committed (scripts/strip_notebook.py, .gitattributes). Idempotent; does
# nothing outside a git checkout.
git_filter() {
  command -v git >/dev/null 2>&1 && git rev-parse --is-inside-work-tree >/dev/null 2>&1 || return 0
  git config filter.strip-notebook.clean "python3 scripts/strip_notebook.py"
}

# Options of every JupyterLab started here (lab, student lab; the browser tests read them from this
# line). Kernels talk to the server over local ZeroMQ sockets; ipykernel warns, once per kernel,
# that plain TCP is unencrypted, unless the server provisions CurveZMQ keys, which jupyter_server
# does for kernels whose kernelspec declares support (ipykernel's does) with this setting.
LAB_OPTIONS=(--MappingKernelManager.transport_encryption=auto)

# BLAS threads for every kernel and test worker started from here (README, "Threads"): one, unless
# the caller set them. The notebooks' dense problems are small, and more OpenBLAS threads than
# free cores (Binder's CPU quota, a busy laptop, two pytest workers) makes them many times slower.
one_blas_thread() {
  export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1} OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} MKL_NUM_THREADS=${MKL_NUM_THREADS:-1}
}

# A reader's JupyterLab without the grader's menus: the test extras install nbgrader (it builds the
# editions), whose "Validate" button would pass every notebook (the hidden tests are not in the
# student edition) and whose Formgrader expects a course. A config directory ahead of the
# environment's turns them off; prints its path.
no_grader_menus() {
  local config=build/lab-config
  mkdir -p "$config/labconfig"
  printf '{"disabledExtensions": {"@jupyter/nbgrader": true}}\n' > "$config/labconfig/page_config.json"
  printf '{"ServerApp": {"jpserver_extensions": {%s}}}\n' \
    '"nbgrader.server_extensions.formgrader": false, "nbgrader.server_extensions.validate_assignment": false, "nbgrader.server_extensions.assignment_list": false, "nbgrader.server_extensions.course_list": false' \
    > "$config/jupyter_server_config.json"
  echo "$config"
}

case "${1:-}" in
  install)
    system_packages; python_env "[test]" ;;
  lab)
    system_packages; python_env ""
    one_blas_thread
    root=(); [ "$(id -u)" = 0 ] && root=(--allow-root)  # containers run as root; JupyterLab refuses it otherwise
    log "starting JupyterLab on notebooks/00_start_here.ipynb (Ctrl-C to stop)"
    # Open the series' first notebook rather than the Launcher (also the link JupyterLab prints);
    # on Binder the badge's urlpath does the same. The repository is served, not notebooks/ alone:
    # the notebooks link ../docs/glossary.md, which JupyterLab cannot open outside its root.
    config=$(no_grader_menus)
    JUPYTER_CONFIG_PATH="$PWD/$config${JUPYTER_CONFIG_PATH:+:$JUPYTER_CONFIG_PATH}" \
      exec "$VENV/bin/jupyter" lab --notebook-dir=. --LabApp.default_url=/lab/tree/notebooks/00_start_here.ipynb \
      "${LAB_OPTIONS[@]}" "${root[@]}" "${@:2}" ;;
  test)
    system_packages; python_env "[test]"
    log "running unit tests and every notebook (nbval)"
    one_blas_thread
    exec "$VENV/bin/python" -m pytest -p no:dash -n "${JOBS:-2}" --dist loadfile --nbval-lax --doctest-modules --durations=15 tests notebooks lbo_notebooks "${@:2}" ;;
  site)
    system_packages; python_env "[docs]"
    one_blas_thread
    exec "$VENV/bin/python" scripts/build_site.py "${@:2}" ;;
  browser)
    system_packages; python_env "[test]"
    if ! command -v chromium >/dev/null 2>&1; then
      log "installing Debian's chromium for the real-browser test (Playwright uses it; it downloads no browser)"
      { as_root apt-get update -qq && as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null; } \
        || { log "install the browser with: sudo apt-get install -y chromium"; exit 1; }
    fi
    one_blas_thread
    LBO_BROWSER_TESTS=1 exec "$VENV/bin/python" -m pytest -p no:dash tests/browser -v "${@:2}" ;;
  student)
    system_packages; python_env "[test]"; one_blas_thread
    if [ "${2:-}" = lab ]; then
      "$VENV/bin/python" scripts/student_edition.py
      root=(); [ "$(id -u)" = 0 ] && root=(--allow-root)
      config=$(no_grader_menus)
      log "starting JupyterLab on the student edition, build/student/ (Ctrl-C to stop)"
      JUPYTER_CONFIG_PATH="$PWD/$config${JUPYTER_CONFIG_PATH:+:$JUPYTER_CONFIG_PATH}" exec "$VENV/bin/jupyter" lab \
        --notebook-dir=build/student --LabApp.default_url=/lab/tree/00_start_here.ipynb "${LAB_OPTIONS[@]}" "${root[@]}" "${@:3}"
    fi
    exec "$VENV/bin/python" scripts/student_edition.py "${@:2}" ;;
  course)
    system_packages; python_env "[test]"; one_blas_thread
    if [ "${2:-}" = --check ]; then
      log "the graded course on the standard nbgrader workflow, with a simulated class (tests/test_course.py)"
      LBO_COURSE_TESTS=1 exec "$VENV/bin/python" -m pytest -p no:dash tests/test_course.py -v "${@:3}"
    fi
    [ -n "${2:-}" ] || { echo "usage: ./make.sh course DIR [NOTEBOOK ...] [--force]   |   ./make.sh course --check" >&2; exit 2; }
    "$VENV/bin/python" scripts/course.py "${@:2}"
    log "next: source $VENV/bin/activate && cd $2 && nbgrader generate_assignment 00_start_here (docs/exercises.md)" ;;
  slides)
    system_packages; python_env "[test]"
    if [ ! -f "build/vendor/reveal.js-4.0.2/dist/reveal.js" ] && ! command -v npm >/dev/null 2>&1; then
      log "installing Debian's npm (it fetches the reveal.js package the slides are served with, once)"
      { as_root apt-get update -qq && as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq npm >/dev/null; } \
        || { log "install npm with: sudo apt-get install -y npm"; exit 1; }
    fi
    if [ "${2:-}" = booklet ]; then
      "$VENV/bin/python" scripts/slides.py
      exec "$VENV/bin/python" scripts/booklet.py
    fi
    exec "$VENV/bin/python" scripts/slides.py "${@:2}" ;;
  booklet)
    system_packages; python_env "[test]"
    exec "$VENV/bin/python" scripts/booklet.py "${@:2}" ;;
  binder)
    exec scripts/binder_parity.sh "${@:2}" ;;
  bench)
    system_packages; python_env "[test]"; one_blas_thread
    for b in benchmarks/*.py; do log "$b"; "$VENV/bin/python" "$b"; done ;;
  pull)
    # `git status` trusts file sizes, so a notebook with outputs looks changed until `git add`
    # refreshes its entry (the filter stores nothing new); then `git pull` can update it.
    git_filter
    git add -u -- notebooks
    exec git pull "${@:2}" ;;
  *)
    echo "usage: ./make.sh {lab|test|browser|binder|site|student|course|slides|booklet|bench|install|pull} [extra arguments]" >&2; exit 2 ;;
esac
