#!/usr/bin/env bash
# Binder parity: build a fresh virtual environment from binder/ ONLY, then run every notebook in it.
#
#   scripts/binder_parity.sh                 # all notebooks
#   scripts/binder_parity.sh notebooks/03_laplace_beltrami.ipynb
#   KEEP=1 scripts/binder_parity.sh          # keep the temporary environment (its path is printed)
#
# What Binder (repo2docker) does with this repository, reproduced here so the Binder configuration
# cannot rot: apt-get install binder/apt.txt (checked here with dpkg-query: this script installs no
# system packages), pip install -r binder/requirements.txt into a fresh environment, run
# binder/postBuild from the repository root with that environment's python first on PATH (it also
# writes the student edition to build/student/, checked here: every notebook, no solutions). Then
# pytest + nbval (installed into the environment for the check only, after postBuild) run the
# notebooks with the environment's kernel. Nothing from .venv or pyproject.toml's dependency list
# is used, so a package missing from binder/requirements.txt makes a notebook fail here.
#
# Needs network access to the package index (or a warm pip cache) and python3 >= 3.10 with venv.
set -euo pipefail
cd "$(dirname "$0")/.."

PYTHON=${PYTHON:-python3}
log() { printf '\033[1m[binder-parity]\033[0m %s\n' "$*" >&2; }
start=$(date +%s)
elapsed() { echo "$(( $(date +%s) - start )) s"; }

# 1. System packages from binder/apt.txt (comments and blank lines skipped).
missing=()
while read -r pkg; do
  pkg=${pkg%%#*}; pkg=$(echo "$pkg" | xargs)
  [ -z "$pkg" ] && continue
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "ok installed" || missing+=("$pkg")
done < binder/apt.txt
if [ ${#missing[@]} -gt 0 ]; then
  log "binder/apt.txt packages not installed: ${missing[*]} (apt-get install -y ${missing[*]})"
  exit 1
fi
log "binder/apt.txt: all installed"

# 2. A fresh environment from binder/requirements.txt only.
work=$(mktemp -d "${TMPDIR:-/tmp}/binder-parity.XXXXXX")
if [ "${KEEP:-0}" = 1 ]; then log "keeping $work"; else trap 'rm -rf "$work"' EXIT; fi
log "python: $("$PYTHON" --version) -> $work/venv"
"$PYTHON" -m venv "$work/venv"
VPY="$work/venv/bin/python"
"$VPY" -m pip install -q --upgrade pip
log "pip install -r binder/requirements.txt"
"$VPY" -m pip install -q -r binder/requirements.txt
log "environment built ($(elapsed))"

# 3. postBuild, from the repository root, with the environment first on PATH (as on Binder).
log "running binder/postBuild"
PATH="$work/venv/bin:$PATH" VIRTUAL_ENV="$work/venv" bash binder/postBuild
page_config="$work/venv/etc/jupyter/labconfig/page_config.json"
[ -f "$page_config" ] || { log "postBuild did not write $page_config"; exit 1; }
# The kernels' sockets encrypted, as ./make.sh lab has them: the server the environment starts reads it.
encryption=$("$VPY" -c 'from jupyter_server.serverapp import ServerApp
app = ServerApp.instance(); app.initialize([]); print(app.kernel_manager.transport_encryption)' 2>/dev/null | tail -1)
[ "$encryption" = auto ] || { log "postBuild did not set MappingKernelManager.transport_encryption = auto (got '$encryption')"; exit 1; }
"$VPY" -c 'import lbo_notebooks, sys; print("lbo_notebooks from", lbo_notebooks.__file__, file=sys.stderr)'
# The student edition the Binder link opens: built by postBuild, without solutions, and nbgrader
# (used in a throw-away environment) left nothing in the student's environment.
for nb in notebooks/[0-9][0-9]_*.ipynb; do
  [ -f "build/student/$(basename "$nb")" ] || { log "postBuild did not write build/student/$(basename "$nb")"; exit 1; }
done
! grep -l "BEGIN SOLUTION" build/student/*.ipynb >&2 || { log "solutions left in the student edition (above)"; exit 1; }
! "$VPY" -c 'import nbgrader' 2>/dev/null || { log "postBuild left nbgrader in the Binder environment"; exit 1; }
log "postBuild wrote the student edition to build/student/ (no solutions, no grader in the environment)"
"$VPY" -m pip check >&2 || log "warning: pip check reports inconsistent requirements (above)"

# 4. The notebooks, with nbval, in that environment (test tools added only now, for the check).
"$VPY" -m pip install -q pytest nbval
log "running the notebooks with nbval ($(elapsed) so far)"
status=0
# Through binder/start, as on Binder, so the kernels get the environment it sets.
PATH="$work/venv/bin:$PATH" VIRTUAL_ENV="$work/venv" \
  bash binder/start "$VPY" -m pytest -p no:dash -p no:cacheprovider --nbval-lax -q "${@:-notebooks}" || status=$?
log "done in $(elapsed) (exit $status)"
exit $status
