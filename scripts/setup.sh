#!/usr/bin/env bash
# Create .venv and install medialaxis with every optional dependency and the test tools.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
  "$PY" -m venv .venv
fi
.venv/bin/python -m pip install --quiet --upgrade pip
.venv/bin/python -m pip install --quiet -e ".[all,test]"
# Compile the numba kernels once, now, rather than in the first call (about 80 s of CPU; cached on disk)
.venv/bin/medialaxis warmup
