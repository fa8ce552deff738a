#!/usr/bin/env bash
# Benchmark (not a test): the SDF analyses on SDF3's benchmark graphs (specs/benchmarks/sdf3), with
# the figures SDF3 reports beside ours, then the throughput-buffer fronts of the generated mp3-family
# graphs (specs/benchmarks/generated). Usage: bench/sdf_bench.sh [BUILD_DIR] [MAX_DISTRIBUTIONS]
# (a release build; default build, 200000).
set -euo pipefail
build="${1:-build}"
limit="${2:-200000}"
exe="$build/tools/semo-verify"
benchmarks="$(dirname "$0")/../specs/benchmarks"
printf '%-32s %12s %10s %14s %7s %12s %10s\n' graph period analysis front points distributions seconds
for g in sdf3/h263decoder sdf3/modem sdf3/samplerate sdf3/satellite sdf3/mp3decoder_granule_parallelism \
         generated/mp3family_b4_g16 generated/mp3family_b8_g16 generated/mp3family_b8_g8_skew10 generated/mp3family_b16_g32 \
         generated/mp3family_b16_g32_skew5 generated/mp3family_b32_g8 generated/mp3family_b32_g32_skew2 generated/mp3family_b64_g2 \
         generated/mp3family_b64_g2_skew1; do
  start=$(date +%s.%N)
  json=$("$exe" sdf --sdf3 "$benchmarks/$g.xml" --json || true)
  mid=$(date +%s.%N)
  front=$("$exe" sdf --sdf3 "$benchmarks/$g.xml" --json --buffers --max-distributions "$limit" || true)
  end=$(date +%s.%N)
  period=$(python3 -c "import json,sys; p=json.loads(sys.argv[1])['period']; print(p['num'] if p['den']==1 else f\"{p['num']}/{p['den']}\")" "$json")
  summary=$(printf '%s' "$front" | python3 -c "
import json,sys
f=json.load(sys.stdin)['paretoFront']
pts=[p for p in f['points'] if not p['deadlock']]
print(f\"{pts[0]['total']}..{pts[-1]['total']}{'' if f['complete'] else '+'} {len(f['points'])} {f['distributions']}\")")
  read -r range points distributions <<< "$summary"
  printf '%-32s %12s %9.3fs %14s %7s %12s %9.2fs\n' "${g#*/}" "$period" "$(python3 -c "print($mid - $start)")" "$range" "$points" "$distributions" "$(python3 -c "print($end - $mid)")"
done
echo "(front: smallest total with throughput .. total at the best throughput found; '+' = not finished)"
echo "SDF3 (specs/benchmarks/sdf3/README.md): periods 332046, 16, 960, 1056, 278650;"
echo "fronts 1189..1224, 38..40, 32..34, 1542..1544, 20..76 (mp3: SDF3 did not finish in 300 s; K-Iter 0.03 s)"
echo "generated graphs (specs/benchmarks/generated/README.md): no reference figures"
