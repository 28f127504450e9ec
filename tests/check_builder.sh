#!/usr/bin/env bash
# End-to-end test of the browser project builder: starts `plantarch builder` on a free port
# with a scratch output folder and drives its page in headless Chromium (tests/js/builder_e2e.mjs
# says what it checks). Usage: check_builder.sh PROJECT_DIR PLANTARCH_BINARY [--screenshots DIR]
# Exits 1 on a failed check, 2 when node, Chromium or the npm packages are missing
# (scripts/test.sh installs them).
set -euo pipefail
root=${1:?usage: check_builder.sh PROJECT_DIR PLANTARCH_BINARY [--screenshots DIR]}
cli=$(realpath "${2:?usage: check_builder.sh PROJECT_DIR PLANTARCH_BINARY [--screenshots DIR]}")
shift 2
command -v node > /dev/null || { echo "check_builder: node is not installed" >&2; exit 2; }
[ -x "${CHROMIUM:-/usr/bin/chromium}" ] || { echo "check_builder: chromium is not installed (scripts/test.sh installs it)" >&2; exit 2; }
[ -d "$root/tests/js/node_modules/puppeteer-core" ] ||
    { echo "check_builder: puppeteer-core missing (run: npm ci --prefix tests/js)" >&2; exit 2; }
exec node "$root/tests/js/builder_e2e.mjs" --cli "$cli" "$@"
