#!/usr/bin/env bash
# The Parquet batch against the JSON Lines path, alternated in one run: for each repeat,
# `interpolate groups.parquet -o curves.parquet` and `eval curves.parquet --samples 100 -o
# s.parquet` (wall time of the whole commands, summed), the fused `interpolate groups.parquet
# --samples 100 -o s.parquet` (one pass, no curve file), then `eval curves.jsonl --samples 100
# -o s.jsonl` on the same curves; prints each repeat's times and both ratios, then the medians.
# The data are bench/io/run.sh's (target/io-data/groups.parquet: 20,000 groups x 100 points).
#
# Usage: bench/io/batch_ratio.sh [REPEATS] [LEKALO]   (default 5, target/release/lekalo)
set -euo pipefail
cd "$(dirname "$0")/../.."
repeats=${1:-5}
lekalo=${2:-target/release/lekalo}
data=target/io-data/groups.parquet
[ -f "$data" ] || { echo "no $data: run bench/io/run.sh once" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
secs() { local t0 t1; t0=$(date +%s.%N); "$@" >/dev/null; t1=$(date +%s.%N); echo "$t1 - $t0" | bc; }
"$lekalo" interpolate "$data" -o "$out/curves.parquet"
"$lekalo" convert "$out/curves.parquet" -o "$out/curves.jsonl"
ratios=()
fused=()
for i in $(seq "$repeats"); do
  a=$(secs "$lekalo" interpolate "$data" -o "$out/curves.parquet" --force)
  b=$(secs "$lekalo" eval "$out/curves.parquet" --samples 100 -o "$out/s.parquet" --force)
  f=$(secs "$lekalo" interpolate "$data" --samples 100 -o "$out/fused.parquet" --force)
  j=$(secs "$lekalo" eval "$out/curves.jsonl" --samples 100 -o "$out/s.jsonl" --force)
  r=$(echo "scale=2; $j / ($a + $b)" | bc)
  rf=$(echo "scale=2; $j / $f" | bc)
  ratios+=("$r")
  fused+=("$rf")
  printf 'repeat %d: interpolate %.3f s + eval %.3f s (Parquet), fused %.3f s, against eval %.3f s (JSON Lines): %.1fx, fused %.1fx\n' \
    "$i" "$a" "$b" "$f" "$j" "$r" "$rf"
done
median() { sort -n | awk -v what="$1" '{v[NR]=$1} END {printf "median ratio %s %.1fx (min %.1fx, max %.1fx)\n", what, v[int((NR+1)/2)], v[1], v[NR]}'; }
printf '%s\n' "${ratios[@]}" | median "interpolate + eval"
printf '%s\n' "${fused[@]}" | median "fused"
