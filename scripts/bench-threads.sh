#!/usr/bin/env bash
# Thread scaling of whole runs (docs/performance.md, "Threads"): for each thread count T
# (RAYON_NUM_THREADS), `paper --n 512` and `solve scenarios/hertz3d.toml` (wall time, solve
# and writing times), the numeric factorization of the paper square at n = 512
# (`bench --n 512` on T threads: as two substructures side by side, and as one matrix with
# faer's parallelism inside its dense blocks, `--threads T`), and `scenarios/paper.toml` at n = 512 with
# `factorization_threads` 1 and 0 (its solver timings from summary.json).
#
# Usage: scripts/bench-threads.sh [BIN] [T ...]   (default target/release/hemicontact, 1 2 4 8 16)
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-target/release/hemicontact}
shift || true
THREADS=${*:-1 2 4 8 16}
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
dt() { awk "BEGIN{printf \"%.2f\", $2 - $1}"; }
timings() { tr -d '\n ' < "$1" | grep -o '"timings":{[^}]*}'; }
nproc
for t in $THREADS; do
  s=$EPOCHREALTIME
  RAYON_NUM_THREADS=$t "$B" paper --n 512 --out "$W/p" > /dev/null 2> "$W/e"
  e=$EPOCHREALTIME
  echo "paper --n 512, $t threads: wall $(dt "$s" "$e") s;" \
    $(grep -o 'Newton steps in [0-9.]* s\|written in [0-9.]* s' "$W/e" | tr '\n' ' ')
  rm -rf "$W/p"
done
for t in $THREADS; do
  s=$EPOCHREALTIME
  RAYON_NUM_THREADS=$t "$B" solve scenarios/hertz3d.toml --out "$W/h" > /dev/null 2> "$W/e"
  e=$EPOCHREALTIME
  echo "hertz3d, $t threads: wall $(dt "$s" "$e") s; $(timings "$W/h/summary.json")"
  rm -rf "$W/h"
done
for t in $THREADS; do
  echo "bench --n 512, $t threads (RAYON_NUM_THREADS), dense blocks on 1 thread (--threads 1):"
  RAYON_NUM_THREADS=$t "$B" bench --n 512 --repeat 3 --threads 1 2> /dev/null | grep -E '^ +(n|512) '
  echo "bench --n 512, $t threads, dense blocks on $t threads (--threads $t):"
  RAYON_NUM_THREADS=$t "$B" bench --n 512 --repeat 3 --threads "$t" 2> /dev/null | grep -E '^ +(n|512) '
done
for ft in 1 0; do
  sed 's/^n = \[128, 128\]/n = [512, 512]/' scenarios/paper.toml > "$W/p.toml"
  printf '\n[solver]\nfactorization_threads = %s\n' "$ft" >> "$W/p.toml"
  for t in $THREADS; do
    RAYON_NUM_THREADS=$t "$B" solve "$W/p.toml" --out "$W/r" > /dev/null 2>&1
    echo "paper.toml n = 512, factorization_threads = $ft, $t threads: $(timings "$W/r/summary.json")"
    rm -rf "$W/r"
  done
done
