#!/usr/bin/env bash
# Serves web/dist/ (made by scripts/build-web.sh) at http://127.0.0.1:PORT/ (default 8080),
# on this machine only. WebGPU needs a secure context, which 127.0.0.1 is.
set -euo pipefail
cd "$(dirname "$0")/../web/dist"
port="${1:-8080}"
echo "bumpview: http://127.0.0.1:$port/"
exec python3 -m http.server "$port" --bind 127.0.0.1
