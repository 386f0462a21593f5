#!/usr/bin/env bash
# Wall-clock comparison of PHCpack's blackbox solver and `singdist solve` on katsura-7
# (128 paths), each on 1 and 2 threads, best of 3 runs of the whole process.
# Skips cleanly (exit 0) when `phc` is not installed
# (`apt-get update && apt-get install -y phcpack` provides it).
# Usage: benches/phc_compare.sh [path/to/singdist]   (default: target/release/singdist)
set -euo pipefail

here="$(cd "$(dirname "$0")/.." && pwd)"
singdist="${1:-$here/target/release/singdist}"
if ! command -v phc >/dev/null 2>&1; then
    echo "phc_compare: phc (PHCpack) not found; skipping"
    exit 0
fi
if [ ! -x "$singdist" ]; then
    echo "phc_compare: $singdist not built; run 'cargo build --release' first" >&2
    exit 1
fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# katsura-7 in Bertini format: x_0 + 2 Σ x_i = 1, Σ_l x_|l| x_|m−l| = x_m (m = 0..6).
n=7
{
    echo "INPUT"
    printf "variable_group"; for i in $(seq 0 $n); do printf " x%d" "$i"; [ "$i" -lt $n ] && printf ","; done; echo ";"
    printf "function"; for i in $(seq 0 $n); do printf " f%d" "$i"; [ "$i" -lt $n ] && printf ","; done; echo ";"
    printf "f0 = -1"; for l in $(seq -$n $n); do printf " + x%d" "${l#-}"; done; echo ";"
    for m in $(seq 0 $((n - 1))); do
        printf "f%d = -x%d" $((m + 1)) "$m"
        for l in $(seq -$n $n); do
            a=${l#-}; b=$((m - l)); b=${b#-}
            [ "$b" -le $n ] && printf " + x%d*x%d" "$a" "$b"
        done
        echo ";"
    done
    echo "END;"
} > "$work/katsura7.input"
"$singdist" system export "$work/katsura7.input" --to phc --out "$work/katsura7.phc"

best_of_3() { # command... → best wall time in seconds
    local best=""
    for _ in 1 2 3; do
        local start end t
        start=$(date +%s.%N)
        "$@" >/dev/null 2>&1
        end=$(date +%s.%N)
        t=$(awk -v a="$start" -v b="$end" 'BEGIN { print b - a }')
        if [ -z "$best" ] || awk -v t="$t" -v b="$best" 'BEGIN { exit !(t < b) }'; then best=$t; fi
    done
    printf "%.3f" "$best"
}

summary="$("$singdist" solve "$work/katsura7.input" --threads 2)"
echo "$summary" | grep -E "paths|nonsingular|failed"
for threads in 1 2; do
    if [ "$threads" = 1 ]; then phc_args=(-b); else phc_args=(-b -t2); fi
    phc_time=$(best_of_3 phc "${phc_args[@]}" "$work/katsura7.phc" "$work/phc_out_$threads")
    ours=$(best_of_3 "$singdist" solve "$work/katsura7.input" --threads "$threads")
    ratio=$(awk -v p="$phc_time" -v s="$ours" 'BEGIN { print p / s }')
    printf "katsura-7, %d thread(s): phc %s s, singdist %s s, phc/singdist = %.1f\n" \
        "$threads" "$phc_time" "$ours" "$ratio"
done
