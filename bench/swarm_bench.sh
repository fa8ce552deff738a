#!/usr/bin/env bash
# Benchmark (not a test): the swarm example for N = 3..10 robots (crash <= 2, lossy broadcast, as
# in specs/examples/swarm), safety search with and without symmetry reduction, and SPIN on the
# exported Promela of the same instances (pan -DNOREDUCE -DSAFETY, every state stored, as semo
# without symmetry). Prints states, seconds, states/s, bytes per state and peak memory for each,
# the semo/SPIN ratios on the same model (without symmetry), and the time of the whole check
# (safety and liveness) with symmetry.
#
#   bench/swarm_bench.sh [BUILD_DIR] [N_MIN] [N_MAX]      (default: build 3 10)
# Needs a release build (tools/setup.sh run) and spin + gcc. Instances that exceed MAX_STATES
# (default 100000000) or TIME_LIMIT seconds (default 600) are reported as such.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build}"
nmin="${2:-3}"
nmax="${3:-10}"
exe="$build/tools/semo-verify"
max_states="${MAX_STATES:-100000000}"
limit="${TIME_LIMIT:-600}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cp -r "$here/specs/examples/swarm/." "$work/"
sed -i 's|\.\./\.\./robots/|'"$here"'/specs/robots/|g' "$work/strategy.xml"

json() { python3 -c 'import json,sys; d=json.load(sys.stdin); print(d["states"], d["seconds"], d["bytesPerState"], d["complete"])'; }
peak_kib() { { /usr/bin/time -f "%M" "$@" 2>&1 >/dev/null || true; } | tail -1; }

printf '%-3s | %-42s | %-42s | %-44s | %s\n' N "semo, symmetry" "semo, no symmetry" "SPIN (-DNOREDUCE -DSAFETY)" "ratios (no symmetry / SPIN)"
printf '%-3s | %10s %8s %10s %5s %6s | %10s %8s %10s %5s %6s | %10s %8s %10s %5s %8s | %s\n' "" states s states/s B/st MiB states s states/s B/st MiB states s states/s B/st MiB "speed  bytes/state"
for n in $(seq "$nmin" "$nmax"); do
  sed "s/legged\[3\]/legged[$n]/" "$work/swarm3.semo" > "$work/swarm_n.semo"
  row="$n"
  for sym in "" "--no-symmetry"; do
    args=(check "$work/swarm_n.semo" --strategy "$work/strategy.xml" --safety-only --json --max-states "$max_states" $sym)
    out="$(timeout "$limit" "$exe" "${args[@]}" 2>/dev/null || true)"
    if [ -z "$out" ]; then row+=$(printf ' | %-42s' "over ${limit} s"); continue; fi
    read -r states secs bps complete <<<"$(echo "$out" | json)"
    kib="$(peak_kib timeout "$limit" "$exe" "${args[@]}")"
    [ "$complete" = "True" ] || states="${states}+"
    row+=$(printf ' | %10s %8.2f %10.0f %5s %6d' "$states" "$secs" "$(python3 -c "print(${states%+}/max($secs,1e-6))")" "$bps" "$((kib / 1024))")
    if [ -n "$sym" ]; then
      semo_sps="$(python3 -c "print(${states%+}/max($secs,1e-6))")"; semo_bps="$bps"; plain_states="${states%+}"
    fi
  done
  "$exe" export "$work/swarm_n.semo" --strategy "$work/strategy.xml" --promela -o "$work/model.pml" 2>/dev/null
  (cd "$work" && spin -a model.pml >/dev/null && gcc -O2 -w -DNOREDUCE -DSAFETY -DMEMLIM=16000 -o pan pan.c)
  start=$(date +%s.%N)
  # pan sized as for the tests: a hash table of about twice the states, a depth limit above the
  # depth its depth-first search can reach (at most the number of states).
  bits="$(python3 -c "import math; print(max(18, math.ceil(math.log2(max(${plain_states:-1000},1)))+1))")"
  depth="$(python3 -c "print(min(${plain_states:-1000}*2+1000, 200000000))")"
  pan_out="$(cd "$work" && timeout "$limit" ./pan -m"$depth" -w"$bits" -c0 -n 2>&1 || true)"
  end=$(date +%s.%N)
  spin_states="$(echo "$pan_out" | sed -n 's/^ *\([0-9]*\) states, stored.*/\1/p')"
  vector="$(echo "$pan_out" | sed -n 's/.*State-vector \([0-9]*\) byte.*/\1/p')"
  spin_mib="$(echo "$pan_out" | sed -n 's/^ *\([0-9.]*\).*total actual memory usage.*/\1/p')"
  if [ -z "$spin_states" ]; then row+=" | SPIN did not finish"; echo "$row"; continue; fi
  spin_secs="$(python3 -c "print($end-$start)")"
  spin_sps="$(python3 -c "print($spin_states/max($spin_secs,1e-6))")"
  # pan's bytes per stored state: its total memory over the states (hash table included), as ours.
  spin_bps="$(python3 -c "print(round($spin_mib*1048576/$spin_states))")"
  row+=$(printf ' | %10s %8.2f %10.0f %5s %8.1f' "$spin_states" "$spin_secs" "$spin_sps" "$spin_bps" "$spin_mib")
  row+=$(printf ' | %5.2fx %6.2fx' "$(python3 -c "print($semo_sps/$spin_sps)")" "$(python3 -c "print($semo_bps/$spin_bps)")")
  # The whole check with symmetry: safety and the three liveness properties (mode_agreement,
  # knowledge_convergence, all_turn_back), as a user runs it.
  full_start=$(date +%s.%N)
  full_out="$(timeout "$limit" "$exe" check "$work/swarm_n.semo" --strategy "$work/strategy.xml" --json 2>/dev/null || true)"
  full_secs="$(python3 -c "print(round($(date +%s.%N)-$full_start, 2))")"
  full_verdicts="$(echo "$full_out" | python3 -c 'import json,sys; d=json.load(sys.stdin); print(",".join(sorted({p["verdict"] for p in d["properties"]})), d["exitCode"])' 2>/dev/null || echo "no result")"
  echo "$row (vector $vector B) | full check with symmetry: ${full_secs} s, verdicts ${full_verdicts}"
done
