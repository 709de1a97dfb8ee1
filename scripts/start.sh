#!/usr/bin/env bash
# npm start: installs what is missing, builds in release mode and serves the app.
# PORT (default 4173) and HOST (default 127.0.0.1) choose where.
set -euo pipefail
here="$(dirname "${BASH_SOURCE[0]}")"
bash "$here/setup.sh"
bash "$here/build.sh"
. "$here/env.sh"
port="${PORT:-4173}"
host="${HOST:-127.0.0.1}"
say "serving the app at http://$host:$port/ (Ctrl+C stops)"
exec vite preview --host "$host" --port "$port" --strictPort
