#!/usr/bin/env bash
# Benchmark (not a test): how the cost of an expression grows with its size, from reading the IR
# to the search's hot loop. Three shapes, each for N terms: a rule guard that is a conjunction of N
# comparisons, an invariant that is a disjunction of N comparisons, and an update that adds N
# terms. Each model has a few states, so the time is the expressions' own (reading, checks,
# compilation, evaluation). Prints seconds and peak memory per N and the ratio to the N before:
# linear cost gives about 10 for ten times the terms.
#
#   bench/expression_bench.sh [BUILD_DIR] [N...]      (default: build 2000 20000 200000)
# Needs a release build (tools/setup.sh run).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build}"
shift || true
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(2000 20000 200000)
exe="$build/tools/semo-verify"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

model() {  # model SHAPE N FILE
  python3 - "$1" "$2" "$3" <<'PY'
import sys
shape, n, path = sys.argv[1], int(sys.argv[2]), sys.argv[3]
with open(path, "w") as f:
    f.write("semo-ir 1\nvar x : 0..3 = 0;\nvar y : 0..1 = 0;\nvar s : 0..3 = 0;\n")
    if shape == "guard":
        terms = " && ".join(f"x + {i % 7} >= {i % 5 - 5}" for i in range(n))
        f.write(f"rule go : {terms} -> y' = 1, x' = (x + 1) % 4;\ninvariant ok : y <= 1;\n")
    elif shape == "invariant":
        terms = " || ".join(f"x == {4 + i % 9}" for i in range(n - 1))
        f.write(f"rule go : true -> x' = (x + 1) % 4;\ninvariant ok : {terms} || x <= 3;\n")
    else:
        terms = " + ".join("x" if i % 2 == 0 else f"{i % 3}" for i in range(n))
        f.write(f"rule go : true -> x' = (x + 1) % 4, s' = ({terms}) % 4;\ninvariant ok : s <= 3;\n")
PY
}

printf '%-10s | %9s | %9s | %8s | %s\n' shape terms seconds "peak MiB" "ratio to the size before (time)"
for shape in guard invariant update; do
  previous=""
  for n in "${sizes[@]}"; do
    model "$shape" "$n" "$work/m.ir"
    start=$(date +%s.%N)
    kib=$({ /usr/bin/time -f "%M" "$exe" check "$work/m.ir" --safety-only 2>&1 >/dev/null || true; } | tail -1)
    secs=$(python3 -c "import time; print(f'{time.time() - $start:.3f}')")
    ratio=""
    [ -z "$previous" ] || ratio=$(python3 -c "print(f'{$secs / max($previous, 1e-3):.1f}')")
    printf '%-10s | %9s | %9s | %8d | %s\n' "$shape" "$n" "$secs" "$((kib / 1024))" "$ratio"
    previous="$secs"
  done
done
