#!/usr/bin/env bash
# One entry point for set-up, JupyterLab and the test suite (see README.md).
#
#   ./make.sh lab     install everything into .venv and open JupyterLab on notebooks/
#   ./make.sh test    install everything (with test extras) and run unit tests + every notebook
#   ./make.sh browser real-browser test: JupyterLab driven by Debian's chromium (Playwright)
#   ./make.sh binder  rebuild a fresh environment from binder/ only and run the notebooks in it
#   ./make.sh site    execute the notebooks and write a static HTML site into build/site
#   ./make.sh bench   print the benchmark tables (benchmarks/*.py)
#   ./make.sh install only install
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
  "$VENV/bin/python" -m pip install -q --upgrade pip
  log "installing lbo_notebooks and its dependencies ($1)"
  "$VENV/bin/python" -m pip install -q -e ".$1"
  # dash (pulled in by open3d) ships a JupyterLab extension that makes JupyterLab show a
  # "Build Recommended" pop-up; nothing needs building, so switch the check off.
  local labconfig="$VENV/etc/jupyter/labconfig"
  mkdir -p "$labconfig"
  printf '{\n  "buildCheck": false,\n  "buildAvailable": false\n}\n' > "$labconfig/page_config.json"
}

case "${1:-}" in
  install)
    system_packages; python_env "[test]" ;;
  lab)
    system_packages; python_env ""
    log "starting JupyterLab on notebooks/ (Ctrl-C to stop)"
    exec "$VENV/bin/jupyter" lab --notebook-dir=notebooks "${@:2}" ;;
  test)
    system_packages; python_env "[test]"
    log "running unit tests and every notebook (nbval)"
    # Two pytest workers on two cores: one BLAS thread each (oversubscribed OpenBLAS is ~30x
    # slower on the small dense problems the tests solve).
    export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1} OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} MKL_NUM_THREADS=${MKL_NUM_THREADS:-1}
    exec "$VENV/bin/python" -m pytest -p no:dash -n "${JOBS:-2}" --dist loadfile --nbval-lax --doctest-modules --durations=15 tests notebooks lbo_notebooks "${@:2}" ;;
  site)
    system_packages; python_env "[test]"
    exec "$VENV/bin/python" scripts/build_site.py "${@:2}" ;;
  browser)
    system_packages; python_env "[test]"
    if ! command -v chromium >/dev/null 2>&1; then
      log "installing Debian's chromium for the real-browser test (Playwright uses it; it downloads no browser)"
      { as_root apt-get update -qq && as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null; } \
        || { log "install the browser with: sudo apt-get install -y chromium"; exit 1; }
    fi
    export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1} OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
    LBO_BROWSER_TESTS=1 exec "$VENV/bin/python" -m pytest -p no:dash tests/browser -v "${@:2}" ;;
  binder)
    exec scripts/binder_parity.sh "${@:2}" ;;
  bench)
    system_packages; python_env "[test]"
    for b in benchmarks/*.py; do log "$b"; "$VENV/bin/python" "$b"; done ;;
  *)
    echo "usage: ./make.sh {lab|test|browser|binder|site|bench|install} [extra arguments]" >&2; exit 2 ;;
esac
