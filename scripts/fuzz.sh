#!/usr/bin/env bash
# Runs every lekalo fuzz target for a fixed time (see docs/robustness.md).
#
#   FUZZ_SECONDS=60 scripts/fuzz.sh            # all targets, 60 s each
#   FUZZ_SECONDS=300 scripts/fuzz.sh curves    # one target
#
# cargo-fuzz needs nightly-only compiler flags (-Z sanitizer); on a stable toolchain they are
# unlocked with RUSTC_BOOTSTRAP=1, which this script sets. Install the driver once with
# `cargo install cargo-fuzz`. Memory is bounded per run (-rss_limit_mb, -malloc_limit_mb): an
# attempt to allocate an absurd size is reported as a crash, as is a run longer than
# FUZZ_TIMEOUT seconds on one input. Crashes land in fuzz/artifacts/<target>/; each one must
# become a test in crates/lekalo/tests/all/fuzz_regressions.rs.
set -euo pipefail

cd "$(dirname "$0")/../fuzz"
export RUSTC_BOOTSTRAP=1
seconds="${FUZZ_SECONDS:-60}"
timeout_s="${FUZZ_TIMEOUT:-10}"
rss_mb="${FUZZ_RSS_MB:-2048}"
# FUZZ_JOBS > 1 runs parallel workers (their output goes to fuzz/fuzz-<n>.log)
jobs="${FUZZ_JOBS:-1}"
parallel=()
[ "$jobs" -gt 1 ] && parallel=(-jobs="$jobs" -workers="$jobs")
all_targets=(json_load knots curves surfaces ppform interpolation degree blending io_parsers cli_inputs cli_args parquet_batches step_read iges_read npy_header)
if [ "$#" -gt 0 ]; then targets=("$@"); else targets=("${all_targets[@]}"); fi

cargo fuzz build
failed=()
for t in "${targets[@]}"; do
    mkdir -p "corpus/$t"
    seeds=()
    [ -d "seeds/$t" ] && seeds=("$PWD/seeds/$t")
    echo "== fuzz target $t for ${seconds}s"
    if ! cargo fuzz run "$t" "$PWD/corpus/$t" "${seeds[@]}" -- \
        -max_total_time="$seconds" -timeout="$timeout_s" -rss_limit_mb="$rss_mb" \
        -malloc_limit_mb="$rss_mb" -max_len=4096 "${parallel[@]}" -print_final_stats=1; then
        failed+=("$t")
    fi
done
if [ "${#failed[@]}" -gt 0 ]; then
    echo "fuzz targets with findings: ${failed[*]} (see fuzz/artifacts/)" >&2
    exit 1
fi
echo "all fuzz targets ran ${seconds}s without a finding"
