#!/usr/bin/env bash
# Benchmark (not a test): how the swarm example's cost grows with its team, N = 10, 20, 50, 100,
# 1,000 robots by default (specs/examples/swarm/swarm10.semo with the count on its team line
# changed; crash <= 2, events and knowledge lost, fair loss). For each N:
#   - the model: `export --ir` size (bytes, rules) and time;
#   - the safety search with symmetry (`check --safety-only`, one state per ordering of the
#     interchangeable robots): states, transitions, seconds, peak memory;
#   - the whole check with the explicit engine (safety and the three LTL properties): seconds, peak
#     memory, verdicts, product states of each property;
#   - the whole check with `--engine auto`, which counts the robots per local state (the counter
#     abstraction, specs/ir.md): seconds, peak memory, abstract states, verdicts, and the team size
#     from which its proofs hold.
# Each run is cut at TIME_LIMIT seconds (default 300) and reported as such. SPIN's figures for the
# same model are in swarm_bench.sh (N <= 10: beyond, pan does not finish without symmetry).
#
#   bench/swarm_scale_bench.sh [BUILD_DIR] [N...]      (default: build 10 20 50 100 1000)
# Needs a release build (tools/setup.sh run) and python3.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build}"
shift || true
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(10 20 50 100 1000)
exe="$build/tools/semo-verify"
limit="${TIME_LIMIT:-300}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cp -r "$here/specs/examples/swarm/." "$work/"
sed -i 's|\.\./\.\./robots/|'"$here"'/specs/robots/|g' "$work/strategy.xml"

# timed OUT ARGS...: runs semo-verify, its stdout to OUT; prints "seconds peak_KiB exit".
timed() {
  local out="$1"
  shift
  local rc=0
  /usr/bin/time -f "%e %M" -o "$work/time" timeout "$limit" "$exe" "$@" >"$out" 2>/dev/null || rc=$?
  echo "$(cat "$work/time" | tail -1) $rc"
}

# summary KIND JSON SECONDS KIB: a whole check's line (KIND explicit: the product states per LTL
# property; counting: the abstract states and the team size its proofs hold from), or the limit.
summary() {
  if [ ! -s "$2" ]; then
    echo "over ${limit} s"
    return
  fi
  python3 -c '
import json, sys
kind, d = sys.argv[1], json.load(open(sys.argv[2]))
verdicts = {}
for p in d["properties"]:
    verdicts[p["verdict"]] = verdicts.get(p["verdict"], 0) + 1
tally = " ".join("%d %s" % (v, k) for k, v in sorted(verdicts.items()))
head = "%s, %d" % (sys.argv[3], int(sys.argv[4]) // 1024)
if kind == "explicit":
    products = ["%s %s" % (p["name"].split("[")[0], p.get("search", {}).get("productStates", "-")) for p in d["properties"] if p["type"] == "liveness"]
    print("%s, %s; %s" % (head, tally, ", ".join(products)))
else:
    sizes = sorted({p["everyTeamSizeFrom"] for p in d["properties"] if "everyTeamSizeFrom" in p})
    print("%s, %s (%s), %s; %s" % (head, d.get("states", "-"), d["engine"], tally, ", ".join(map(str, sizes)) or "-"))
' "$@"
}

printf '%-5s | %-28s | %-48s | %-60s | %s\n' N "export --ir: bytes, rules, s" "safety (symmetry): states, transitions, s, MiB" "whole check, explicit: s, MiB, verdicts; product states per LTL property" "whole check, auto (counting): s, MiB, abstract states, verdicts, every N from"
for n in "${sizes[@]}"; do
  sed "s/legged\[10\]/legged[$n]/" "$work/swarm10.semo" >"$work/swarm_n.semo"
  common=("$work/swarm_n.semo" --strategy "$work/strategy.xml")
  read -r secs kib rc <<<"$(timed "$work/export.out" export --ir "${common[@]}" -o "$work/model.ir")"
  if [ "$rc" = 0 ]; then
    rules="$(grep -c '^rule ' "$work/model.ir")"
    model="$(printf '%s, %s, %s' "$(stat -c %s "$work/model.ir")" "$rules" "$secs")"
  else
    model="over ${limit} s"
  fi
  # --safety-only leaves the LTL properties undecided: exit 3 with the safety verdicts is expected.
  read -r secs kib rc <<<"$(timed "$work/safety.json" check "${common[@]}" --safety-only --json)"
  if python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); sys.exit(0 if d.get("complete") else 1)' "$work/safety.json" 2>/dev/null; then
    safety="$(python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
print("%s, %s, %s, %d" % (d["states"], d["transitions"], sys.argv[2], int(sys.argv[3]) // 1024))
' "$work/safety.json" "$secs" "$kib")"
  else
    safety="exit $rc (over ${limit} s, or a limit) after ${secs} s"
  fi
  read -r secs kib rc <<<"$(timed "$work/whole.json" check "${common[@]}" --json)"
  whole="$(summary explicit "$work/whole.json" "$secs" "$kib")"
  read -r secs kib rc <<<"$(timed "$work/counting.json" check "${common[@]}" --engine auto --json)"
  counting="$(summary counting "$work/counting.json" "$secs" "$kib")"
  printf '%-5s | %-28s | %-48s | %-60s | %s\n' "$n" "$model" "$safety" "$whole" "$counting"
done
