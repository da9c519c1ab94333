#!/usr/bin/env bash
# Set up (if needed) and run the main job on the bundled sample shapes; results go to ./medialaxis-demo
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
exec .venv/bin/medialaxis demo "${1:-medialaxis-demo}"
