#!/usr/bin/env bash
# End-to-end tests of `lekalo serve` in headless Chromium (web-tests/).
#
# 1. Debian's Chromium (apt-get install chromium) when /usr/bin/chromium is missing;
# 2. the npm test dependency (playwright-core, pinned by web-tests/package-lock.json) when
#    web-tests/node_modules is missing or older than the lock file;
# 3. the debug binary (cargo build -p lekalo-cli: nothing to do after cargo test --workspace);
# 4. `lekalo serve --port <free port>` in the background, stopped on every exit;
# 5. the tests; screenshots in target/browser-artifacts/.
#
# Usage: scripts/test-browser.sh            (SCREENSHOTS_FOR_DOCS=1 also refreshes docs/img/)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

if [ ! -x /usr/bin/chromium ]; then
  echo "installing chromium (apt-get)"
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq chromium >/dev/null
fi

if [ ! -d web-tests/node_modules/playwright-core ] \
  || [ web-tests/package-lock.json -nt web-tests/node_modules/.package-lock.json ]; then
  (cd web-tests && npm ci --no-audit --no-fund --loglevel=error)
fi

cargo build -q -p lekalo-cli
bin="$root/target/debug/lekalo"

port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1]); s.close()')
log=$(mktemp)
"$bin" serve --port "$port" >"$log" 2>&1 &
server=$!
cleanup() {
  kill "$server" 2>/dev/null || true
  wait "$server" 2>/dev/null || true
  rm -f "$log"
}
trap cleanup EXIT INT TERM

url="http://127.0.0.1:$port/"
for _ in $(seq 1 100); do
  if grep -q "listening on" "$log"; then break; fi
  if ! kill -0 "$server" 2>/dev/null; then
    echo "lekalo serve exited:"; cat "$log"; exit 1
  fi
  sleep 0.1
done
grep -q "listening on $url" "$log" || { echo "lekalo serve did not start:"; cat "$log"; exit 1; }

mkdir -p target/browser-artifacts
LEKALO_URL="$url" ARTIFACTS="$root/target/browser-artifacts" node web-tests/editor.test.mjs
