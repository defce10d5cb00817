#!/usr/bin/env bash
# Does load stepping help a hard problem? Solves the paper example (scenarios/paper.toml)
# with a strongly nonmonotone friction coefficient, once at the full load and along
# uniform load paths of 2, 4 and 8 steps, and prints per case the median over the runs of
# the total Newton steps, the total outer iterations and the total solve time (the sum over
# the steps of each step's `timings.total` in its summary.json), and whether every step
# converged.
#
# Usage: scripts/bench-loading.sh [--n N] [--runs R] [--mu MU_TOML] [--steps "2 4 8"]
#        scripts/bench-loading.sh --fixed [--runs R] [--steps N]
#   --n N        squares per side of the paper mesh (default 128, the scenario's own)
#   --runs R     runs per case (default 3); the medians are printed
#   --mu TOML    the friction coefficient of both contact parts (default the exponential
#                law with a = 5: '{ law = "exponential", a = 5.0, b = 0.1, beta = 100.0 }';
#                e.g. '5.0' for a constant Coulomb coefficient μ = 5)
#   --steps LIST the numbers of load steps compared with the plain solve (default "2 4 8")
#   --fixed      instead, the fixed cost of a load step: a 2 × 2 mesh (18 DOFs, a contact
#                part; each solve well under a millisecond) along a path of N steps
#                (--steps N, default 1500) and of 1 step, each run R times as a whole
#                process under /usr/bin/time; prints the medians of the wall and CPU
#                seconds and of the peak memory of both, and the cost of one more step,
#                (T_N − T_1)/(N − 1): the fixed cost of a step (writing its folder, its
#                summary, its share of the memory) next to its solve
# Needs: the release binary target/release/hemicontact (cargo build --release), or
# HEMICONTACT_BIN pointing to one; python3 (standard library only) for the medians;
# GNU time (/usr/bin/time) for --fixed.
set -euo pipefail
cd "$(dirname "$0")/.."
n=128
runs=3
mu='{ law = "exponential", a = 5.0, b = 0.1, beta = 100.0 }'
steps="2 4 8"
fixed=0
while [ $# -gt 0 ]; do
    case "$1" in
        --n) n="$2"; shift 2 ;;
        --runs) runs="$2"; shift 2 ;;
        --mu) mu="$2"; shift 2 ;;
        --steps) steps="$2"; shift 2 ;;
        --fixed) fixed=1; shift ;;
        *) echo "unknown option $1" >&2; exit 2 ;;
    esac
done
bin="${HEMICONTACT_BIN:-target/release/hemicontact}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

if [ "$fixed" -eq 1 ]; then
    [ "$steps" = "2 4 8" ] && steps=1500
    for case in 1 "$steps"; do
        cat > "$work/tiny-$case.toml" <<EOF
[mesh]
kind = "rectangle"
size = [1.0, 1.0]
n = [2, 2]
[material]
young = 1000.0
poisson = 0.3
[[dirichlet]]
part = "bottom"
[[loads.traction]]
part = "top"
value = [0.0, -30.0]
[[contact]]
part = "right"
gap = 0.01
c_nu = 1.0e4
[loading]
steps = $case
EOF
        for run in $(seq "$runs"); do
            # A fresh folder each run (removed after it, outside the timing).
            /usr/bin/time -f "%e %U %S %M" -o "$work/time-$case-$run" \
                "$bin" --quiet solve "$work/tiny-$case.toml" --out "$work/out-$case-$run"
            rm -rf "$work/out-$case-$run"
        done
    done
    python3 - "$work" "$steps" "$runs" <<'EOF'
import statistics, sys
work, n, runs = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
def medians(case):
    rows = [open(f"{work}/time-{case}-{r}").read().split()[-4:] for r in range(1, runs + 1)]
    wall = statistics.median(float(r[0]) for r in rows)
    cpu = statistics.median(float(r[1]) + float(r[2]) for r in rows)
    peak = statistics.median(int(r[3]) for r in rows) / 1024
    return wall, cpu, peak
one, many = medians(1), medians(n)
print(f"2 x 2 mesh, 18 DOFs, {runs} runs per case (medians, whole process)")
print(f"{'steps':>6} {'wall s':>8} {'cpu s':>8} {'peak MiB':>9}")
for k, (wall, cpu, peak) in ((1, one), (n, many)):
    print(f"{k:>6} {wall:>8.3f} {cpu:>8.3f} {peak:>9.1f}")
print(f"one more step: {1e3 * (many[0] - one[0]) / (n - 1):.2f} ms wall, "
      f"{1e3 * (many[1] - one[1]) / (n - 1):.2f} ms cpu, "
      f"{1024 * (many[2] - one[2]) / (n - 1):.1f} KiB of peak memory")
EOF
    exit 0
fi

# The paper scenario with n × n squares and the coefficient $mu on both contact parts.
base="$work/base.toml"
sed -e "s/^n = \[128, 128\]/n = [$n, $n]/" \
    -e "s/^mu = .*/mu = $mu/" scenarios/paper.toml > "$base"

echo "paper example, n = $n, mu = $mu, $runs runs per case (medians)"
printf '%-8s %8s %8s %10s %s\n' "steps" "Newton" "outer" "time s" "converged"
for case in 0 $steps; do
    file="$work/case-$case.toml"
    cp "$base" "$file"
    if [ "$case" -gt 0 ]; then
        printf '\n[loading]\nsteps = %s\n' "$case" >> "$file"
    fi
    for run in $(seq "$runs"); do
        out="$work/out-$case-$run"
        code=0
        "$bin" --quiet solve "$file" --out "$out" || code=$?
        if [ "$code" -ne 0 ] && [ "$code" -ne 3 ]; then
            echo "case $case: exit code $code" >&2
            exit 1
        fi
    done
    python3 - "$work" "$case" "$runs" <<'EOF'
import glob, json, os, statistics, sys
work, case, runs = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
newton, outer, seconds, converged = [], [], [], []
for run in range(1, runs + 1):
    out = os.path.join(work, f"out-{case}-{run}")
    files = sorted(glob.glob(os.path.join(out, "step-*", "summary.json"))) or [
        os.path.join(out, "summary.json")
    ]
    summaries = [json.load(open(f)) for f in files]
    newton.append(sum(len(s["report"]["newton"]) for s in summaries))
    outer.append(sum(len(s["report"]["outer"]) for s in summaries))
    seconds.append(sum(s["report"]["timings"]["total"] for s in summaries))
    converged.append(all(s["report"]["converged"] for s in summaries) and (case == 0 or len(summaries) == case))
label = "plain" if case == 0 else str(case)
print(f"{label:<8} {statistics.median(newton):>8g} {statistics.median(outer):>8g} "
      f"{statistics.median(seconds):>10.3f} {'yes' if all(converged) else 'NO'}")
EOF
done
