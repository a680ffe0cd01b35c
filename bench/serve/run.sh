#!/usr/bin/env bash
# The editor's speed, by hand (not in CI): release build, a server on a free port, then the
# round-trip latency (p99 target 5 ms, a Rust client), a bounded load with hostile requests, and the frame
# rate of dragging a point of a 200-point curve in headless Chromium.
#
# Usage: bench/serve/run.sh       (needs web-tests/node_modules: npm ci in web-tests/)
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo build -q --release -p lekalo-cli
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1]); s.close()')
target/release/lekalo serve --port "$port" >/dev/null 2>&1 &
server=$!
trap 'kill $server 2>/dev/null || true' EXIT INT TERM
for _ in $(seq 1 100); do
  curl -fs "http://127.0.0.1:$port/api/health" >/dev/null 2>&1 && break
  sleep 0.1
done
export LEKALO_URL="http://127.0.0.1:$port/"
cargo bench -q -p lekalo-serve --bench roundtrip -- 2000   # the Rust client on keep-alive sockets
node bench/serve/load.mjs 16 200
node bench/serve/fps.mjs
