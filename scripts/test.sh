#!/usr/bin/env bash
# Set up (if needed) and run the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
./scripts/browser.sh
.venv/bin/ruff check src tests benchmarks  # the rules in pyproject.toml; the layering is tests/test_architecture.py
.venv/bin/mypy  # core/ and the public API ([tool.mypy] in pyproject.toml)
exec .venv/bin/python -m pytest -q -p no:cacheprovider "$@"
