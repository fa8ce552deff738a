#!/usr/bin/env bash
# Benchmark (not a test): task-graph generation and analysis of every example mission (every robot,
# every scenario: consistency, schedule, period, Pareto front, both bound choices with their Z3
# proofs). Usage: bench/taskgraph_bench.sh [BUILD_DIR] (a release build; default build).
set -euo pipefail
build="${1:-build}"
exe="$build/tools/semo-verify"
root="$(dirname "$0")/.."
out="$(mktemp)"
trap 'rm -f "$out"' EXIT
printf '%-22s %7s %10s %7s %9s %13s %9s\n' mission robots scenarios tasks channels "Z3 proofs" seconds
for mission in "$root"/specs/examples/*/*.semo; do
  folder="$(dirname "$mission")"
  start=$(date +%s.%N)
  "$exe" sdf "$mission" --strategy "$folder/strategy.xml" --json > "$out" || true
  end=$(date +%s.%N)
  python3 - "$out" "$(basename "$mission" .semo)" "$(python3 -c "print($end - $start)")" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
robots = r["robots"]
scenarios = sum(len(x["scenarios"]) for x in robots)
tasks = sum(x["tasks"] for x in robots)
channels = sum(x["channels"] for x in robots)
proofs = proven = 0
for x in robots:
    for s in x["scenarios"]:
        for key in ("deadlockFreeBounds", "maxThroughputBounds"):
            b = s.get(key)
            if b is None:
                continue
            proofs += 1 + len(b["channels"])
            proven += (b["safety"] == "proven") + sum(c["oneLess"] in ("deadlocks", "slower") for c in b["channels"])
print(f"{sys.argv[2]:<22} {len(robots):>7} {scenarios:>10} {tasks:>7} {channels:>9} {f'{proven}/{proofs}':>13} {float(sys.argv[3]):>8.2f}s")
PY
done
echo "(Z3 proofs: no-overflow proofs plus one-token-less outcomes, per scenario and bound choice; a robot"
echo " scenario graph met before is analysed once)"
