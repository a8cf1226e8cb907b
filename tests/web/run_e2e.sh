#!/usr/bin/env bash
# The web viewer end to end: starts `penumbra serve`, drives the viewer in
# headless Chromium and checks that it reacts (e2e.mjs). Skips (exit 77, which
# CTest reports as skipped) with a message when Chromium, node, the npm
# packages (scripts/install-deps.sh --web-tests installs them) or the engine CT
# are missing, so that a run by hand on a bare machine does not fail.
# Usage: run_e2e.sh PENUMBRA_BINARY DATA_DIR OUTPUT_DIR
set -u
here=$(cd "$(dirname "$0")" && pwd)
skip() { echo "SKIPPED: $*"; exit 77; }
[ -x /usr/bin/chromium ] || skip "/usr/bin/chromium is not installed (make test or scripts/install-deps.sh --web-tests installs it)"
command -v node > /dev/null || skip "node is not installed"
[ -f "$here/node_modules/playwright-core/package.json" ] || skip "tests/web/node_modules is missing (run npm ci in tests/web)"
[ -f "$2/engine_256x256x128_uint8.nhdr" ] || skip "the engine CT is not in $2"
mkdir -p "$3"
exec node "$here/e2e.mjs" "$1" "$2" "$3"
