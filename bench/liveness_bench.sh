#!/usr/bin/env bash
# Benchmark (not a test): the LTL properties of scouting and patrol, property by property, with
# each reduction on and off: slicing (cone of influence refined by counterexamples) and symmetry,
# and the random walks that hunt violations when no slice decides.
# Prints, per configuration, the wall time and peak memory of the whole check, and per property
# its verdict, where it was searched (slice of k variables, enumerated or symbolic, or whole model),
# its product states (counted, for a symbolic slice) and seconds; swarm10's liveness with the
# symbolic search of large slices on and off. Then SPIN's partial-order reduction on the exported safety model of each example:
# states stored by pan with and without it (-DNOREDUCE), the reduction factor, for comparison
# (the export is one process whose every step reads and writes shared globals, which leaves SPIN's
# reduction nothing to prune: see bench/README.md).
#
#   bench/liveness_bench.sh [BUILD_DIR]        (default: build)
# Needs a release build (tools/setup.sh run), python3, spin and gcc. Every run is bounded by
# MAX_STATES product states per slice or product (default 5000000) and TIME_LIMIT seconds
# (default 900); a run over the limit is reported as such. ONLY_MISSIONS=1 stops after scouting
# and patrol (the swarm's symbolic comparison and SPIN's reduction, which take longest, left out);
# CONE=1 adds scouting with --cone-seconds 3000 (about half an hour, its own limit of 3600 s).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build}"
exe="$build/tools/semo-verify"
max_states="${MAX_STATES:-5000000}"
limit="${TIME_LIMIT:-900}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# One line per LTL property of a `check --json` output.
properties() {
  python3 -c '
import json, sys
d = json.load(sys.stdin)
for p in d["properties"]:
    if p["type"] != "liveness":
        continue
    s = p.get("search", {})
    where = "-"
    states = s.get("productStates", "-")
    if s.get("on") == "slice":
        where = "slice %d/%d, %d refinements" % (s["variables"], s["ofVariables"], s["refinements"])
    elif s.get("on") == "slice, symbolically":
        where = "symbolic slice %d/%d, %d refinements" % (s["variables"], s["ofVariables"], s["refinements"])
        states = "%.3g" % s["symbolicProductStates"]
    elif s.get("on") == "exact cone, symbolically":
        where = "exact cone %d/%d" % (s["variables"], s["ofVariables"])
        states = "%.3g" % s["symbolicProductStates"]
    elif s.get("on") == "round-robin":
        where = "robots taking turns"
    elif s.get("on") == "random walks":
        where = "random walks, walk %d" % s["walks"]
    elif s:
        where = "whole model"
    print("    %-44s %-8s %-36s %12s %9.2f" % (p["name"], p["verdict"], where, states, s.get("seconds", 0.0)))
'
}

# bench_check LABEL ARGS...: one configuration, timed, its properties listed.
bench_check() {
  local label="$1"
  shift
  local start end kib
  start=$(date +%s.%N)
  if ! /usr/bin/time -f "%M" -o "$work/rss" timeout "$limit" "$exe" check "$@" --json --max-states "$max_states" >"$work/out.json" 2>/dev/null; then
    [ -s "$work/out.json" ] || { printf '  %-40s over %s s\n' "$label" "$limit"; return; }
  fi
  end=$(date +%s.%N)
  kib="$(tail -1 "$work/rss")"
  printf '  %-40s %8.1f s %8d MiB peak\n' "$label" "$(python3 -c "print($end - $start)")" "$((kib / 1024))"
  properties <"$work/out.json"
}

# spin_por NAME ARGS...: pan's states with and without partial-order reduction on the safety model.
spin_por() {
  local name="$1"
  shift
  "$exe" export "$@" --promela -o "$work/model.pml" 2>/dev/null
  (cd "$work" && spin -a model.pml >/dev/null)
  local reduced full
  for variant in reduced full; do
    local flags="-DSAFETY -DMEMLIM=12000"
    [ "$variant" = full ] && flags="$flags -DNOREDUCE"
    (cd "$work" && gcc -O2 -w $flags -o pan pan.c)
    local out
    out="$(cd "$work" && timeout "$limit" ./pan -m100000000 -w26 2>&1 || true)"
    local states
    states="$(echo "$out" | sed -n 's/^ *\([0-9e.+]*\) states, stored.*/\1/p' | head -1)"
    if echo "$out" | grep -q "errors: 0" && ! echo "$out" | grep -qE "out of memory|MEMLIM|depth too small|Search not completed"; then
      printf -v "$variant" '%s' "$states"
    else
      printf -v "$variant" '%s' "not finished (${states:-?} stored)"
    fi
  done
  local factor="-"
  if [[ "$reduced" =~ ^[0-9]+$ && "$full" =~ ^[0-9]+$ ]]; then factor="$(python3 -c "print('%.2f' % ($full / $reduced))")"; fi
  printf '  %-12s without reduction %-28s with reduction %-28s factor %s\n' "$name" "$full" "$reduced" "$factor"
}

for example in scouting patrol; do
  model=("$here/specs/examples/$example/$example.semo" --strategy "$here/specs/examples/$example/strategy.xml")
  echo "== $example (MAX_STATES=$max_states, TIME_LIMIT=$limit s)"
  bench_check "auto (slicing + symmetry)" "${model[@]}" --engine auto
  if [ "$example" = scouting ] && [ "${CONE:-0}" = 1 ]; then
    # The exact cone for what the slices leave undecided (mode_agreement): half an hour, so only
    # with CONE=1, and with a time limit of its own.
    limit_before="$limit"
    limit=3600
    bench_check "auto, --cone-seconds 3000" "${model[@]}" --engine auto --cone-seconds 3000
    limit="$limit_before"
  fi
  bench_check "auto, no random walks" "${model[@]}" --engine auto --no-walks
  if [ "$example" = scouting ]; then
    # The explicit safety search does not finish on scouting; smt decides safety, which leaves
    # the LTL properties to the configurations measured.
    engine=(--engine smt)
  else
    engine=()
  fi
  bench_check "slicing, no symmetry" "${model[@]}" "${engine[@]}" --no-symmetry
  bench_check "symmetry, no slicing" "${model[@]}" "${engine[@]}" --no-slicing
  bench_check "no slicing, no symmetry" "${model[@]}" "${engine[@]}" --no-slicing --no-symmetry
done

if [ "${ONLY_MISSIONS:-0}" = 1 ]; then exit 0; fi

# A slice that outgrows --slice-states is searched symbolically (decision diagrams) unless
# --no-symbolic: swarm10 without symmetry, its slices limited to 2,000,000 states.
echo "== swarm10 without symmetry, --slice-states 2000000: the symbolic search of larger slices on and off"
model=("$here/specs/examples/swarm/swarm10.semo" --strategy "$here/specs/examples/swarm/strategy.xml")
bench_check "symbolic search on" "${model[@]}" --no-symmetry --slice-states 2000000
bench_check "symbolic search off" "${model[@]}" --no-symmetry --slice-states 2000000 --no-symbolic

echo "== SPIN's partial-order reduction on the exported safety model (pan -DSAFETY, states stored)"
for example in patrol deployment chase scouting; do
  spin_por "$example" "$here/specs/examples/$example/$example.semo" --strategy "$here/specs/examples/$example/strategy.xml"
done
spin_por swarm10 "$here/specs/examples/swarm/swarm10.semo" --strategy "$here/specs/examples/swarm/strategy.xml"
