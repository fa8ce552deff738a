#!/usr/bin/env bash
# Benchmark (not a test): how fast the simulator runs the paper's experiments. Simulated seconds per
# wall second for one long run of swarm10 and of the scouting mission (with and without the
# conformance monitor replaying every step on the IR), and the wall time of 1,000 seeds of swarm3.
#
#   bench/simulate_bench.sh [BUILD_DIR]        (default: build; needs a release build)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
exe="${1:-$here/build}/tools/semo-verify"
cd "$here"
S=specs/examples

wall() {  # wall seconds of a command, stdout discarded
  local start end
  start=$(date +%s.%N)
  "$@" > /dev/null
  end=$(date +%s.%N)
  echo "$end - $start" | bc -l
}

printf '%-44s %10s %10s %14s\n' run simulated wall "sim s / wall s"
row() {  # name simulated-seconds command...
  local name="$1" simulated="$2"
  shift 2
  local w
  w=$(wall "$@")
  printf '%-44s %9ss %9.3fs %14.0f\n' "$name" "$simulated" "$w" "$(echo "$simulated / $w" | bc -l)"
}
row "swarm10, 60 s" 60 "$exe" simulate $S/swarm/swarm10.semo -s $S/swarm/strategy.xml --duration 60s --keep-running
row "swarm10, 60 s, conformance checked" 60 "$exe" simulate $S/swarm/swarm10.semo -s $S/swarm/strategy.xml --duration 60s --keep-running --check-conformance
row "scouting, leader crash, 60 s" 60 "$exe" simulate $S/scouting/scouting.semo -s $S/scouting/strategy.xml --crash leader@5s --duration 60s --keep-running
row "scouting, leader crash, 60 s, conformance" 60 "$exe" simulate $S/scouting/scouting.semo -s $S/scouting/strategy.xml --crash leader@5s --duration 60s --keep-running --check-conformance
row "swarm3, 1,000 seeds, loss 0.2, conformance" "$(( 1000 * 60 ))" "$exe" simulate $S/swarm/swarm3.semo -s $S/swarm/strategy.xml --loss 0.2 --duration 60s --keep-running --check-conformance --seeds 1..1000
