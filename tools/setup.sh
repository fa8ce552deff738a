#!/usr/bin/env bash
# One command for everything on a fresh Debian 12 machine: installs the Debian packages semo needs
# (only those missing), builds, and then
#   run       runs semo-verify on the paper's scouting mission (check, then the task graphs)
#   test      also runs the whole test suite
#   sanitize  builds a second time with AddressSanitizer + UndefinedBehaviorSanitizer and runs the tests
#   fuzz      builds the libFuzzer targets with clang and fuzzes each for FUZZ_SECONDS (default 300)
set -euo pipefail
cd "$(dirname "$0")/.."
mode="${1:-run}"
jobs="$(nproc)"

packages=(build-essential cmake pkg-config libz3-dev libeigen3-dev libsundials-dev liburdfdom-dev libxml2-utils python3-jsonschema
          libbdd-dev libtinyxml2-dev libcli11-dev nlohmann-json3-dev libfmt-dev libgtest-dev libbenchmark-dev libssl-dev spin graphviz librsvg2-bin
          cyclonedds-dev cyclonedds-tools)
if [ "$mode" = fuzz ]; then packages+=(clang libclang-rt-14-dev); fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# Each step's header says when it started (seconds since this script did), so that a log shows
# where the time went.
step() { printf '\n== %s  [%d s]\n' "$*" "$SECONDS"; }

# apt's own output goes to a log file: the terminal gets one line, and the log's end if it fails.
packages_log="setup-packages.log"
step "packages"
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing ${#missing[@]}: ${missing[*]} (apt's output: $packages_log)"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  if ! { $sudo apt-get update -qq && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"; } \
      > "$packages_log" 2>&1; then
    tail -n 30 "$packages_log"
    echo "tools/setup.sh: installing the packages failed; the whole log is $packages_log" >&2
    exit 1
  fi
else
  echo "all ${#packages[@]} packages installed"
fi

# Unity builds (CMake compiles the sources of a target in batches of 8, one translation unit each):
# a clean build here parses the big headers (nlohmann/json, fmt, gtest, Z3) a few dozen times instead
# of two hundred, and takes 9 minutes of processor time instead of 15. Every source still compiles
# on its own (a developer's `cmake --build` without it rebuilds one file per change), and file-local
# names must differ between the files of a target (docs/development.md, "Builds").
build() {  # build DIR [cmake options...]
  local dir="$1"; shift
  cmake -S . -B "$dir" -DCMAKE_UNITY_BUILD=ON "$@" > "$dir.configure.log" 2>&1 || { cat "$dir.configure.log"; exit 1; }
  cmake --build "$dir" -j "$jobs"
}

scouting=(specs/examples/scouting/scouting.semo --strategy specs/examples/scouting/strategy.xml)

case "$mode" in
  run)
    step "build (release, build/)"
    build build -DCMAKE_BUILD_TYPE=Release -DSEMO_BUILD_TESTS=OFF
    step "lint: the paper's scouting mission"
    ./build/tools/semo-verify lint "${scouting[@]}"
    # The plain command: with no options, check chooses its engines (the explicit search within its
    # budget, else Z3 for the safety properties; the LTL properties on slices, then on their exact
    # cones), and decides every property of the mission.
    step "check: every property of the mission"
    checked=0
    ./build/tools/semo-verify check "${scouting[@]}" || checked=$?
    # Then each robot's dataflow task graph: every scenario consistent and deadlock free, with its
    # schedule, period and buffer bounds proven (Z3).
    step "sdf: each robot's task graph"
    graphs=0
    ./build/tools/semo-verify sdf "${scouting[@]}" || graphs=$?
    # check's exit code is passed on (a violation or a partial result is not hidden), then sdf's.
    meaning=([0]="everything proven" [1]="a property is violated" [2]="bad input" [3]="partial: some property undecided"
             [4]="the run left the model")
    step "summary"
    echo "check: exit $checked (${meaning[$checked]:-unexpected}); sdf: exit $graphs (${meaning[$graphs]:-unexpected})"
    if [ "$checked" -ne 0 ]; then exit "$checked"; fi
    exit "$graphs"
    ;;
  test)
    step "build (release, build/, with the tests)"
    build build -DCMAKE_BUILD_TYPE=Release -DSEMO_BUILD_TESTS=ON
    step "lint: the paper's scouting mission"
    ./build/tools/semo-verify lint "${scouting[@]}"
    step "tests (ctest)"
    ctest --test-dir build --output-on-failure -j "$jobs"
    ;;
  sanitize)
    # -O1 rather than -O0, the sanitizers' own advice for reasonable speed (the tests ran in 6 min
    # instead of 14.5 on 2 cores), and -g1 rather than -g: line tables are all a sanitizer report
    # needs, and full debug info made the build take half again as long. The build type stays
    # Debug so that assertions stay on.
    step "build with AddressSanitizer and UndefinedBehaviorSanitizer (build-sanitize/)"
    build build-sanitize -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -g1" -DSEMO_SANITIZE=ON -DSEMO_BUILD_TESTS=ON
    # Every test but the few long searches (label `heavy`) and the comparisons with SPIN (label
    # `spin`: their time is SPIN compiling and searching, which no sanitizer looks into; the export
    # they read is sanitized by the e2e export tests). The release run above covers both. Nor the
    # scouting mission's generated programs (EmitScouting, left out by the emit tests' filter in
    # tests/e2e/CMakeLists.txt: seven minutes here, most of it emit's proofs and the build): the
    # swarm's (EmitSwarm3) run the same generated code and runtime under the sanitizers, as programs
    # and in the simulator. The random-model comparisons go through a fifth of their models here
    # (tests/unit/random_model.hpp). Each GoogleTest program runs in a few parts rather than a
    # process per test (tests/CMakeLists.txt, semo_add_gtests). Label `release_only`: the install
    # and package test, and runs on the largest models whose code the sanitized tests run on
    # smaller ones (scouting's task graphs printed three ways, its IC3 and the two largest BMC
    # comparisons; tests/e2e/CMakeLists.txt says why for each).
    step "tests under the sanitizers (ctest -LE 'heavy|spin|release_only')"
    # The stacks kept for where each block was allocated and freed are 10 frames deep instead of 30
    # (a report's own stack stays whole), freed memory waits in a quarantine of 64 MB instead of
    # 256 before reuse (a use after free is caught while its block waits there), and none is handed
    # back to the system on a timer: fewer page faults and unwinds (a schema test of 18 runs 50 s ->
    # 34 s, the hostile inputs' first part 62 -> 57 s, measured 2026-11-29).
    ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:malloc_context_size=10:quarantine_size_mb=64:allocator_release_to_os_interval_ms=-1 \
    UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
      ctest --test-dir build-sanitize --output-on-failure -j "$jobs" -LE "heavy|spin|release_only"
    ;;
  fuzz)
    step "build the fuzz targets (clang, build-fuzz/)"
    # clang for C too: the runtime compiles the C that Cyclone DDS's idlc generates, and gcc knows no
    # -fsanitize=fuzzer-no-link.
    build build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DSEMO_FUZZ=ON
    seconds="${FUZZ_SECONDS:-300}"
    targets=(fuzz_mission_parser fuzz_strategy_reader fuzz_ir_reader fuzz_sdf3_reader fuzz_taskgraph_reader
             fuzz_trace_reader fuzz_world_reader fuzz_packet_decode fuzz_tables_reader)
    # Seed corpora: the project's own inputs, and the malformed ones of the diagnostics tests.
    for target in "${targets[@]}"; do mkdir -p "build-fuzz/corpus-$target"; done
    for f in specs/benchmarks/sdf3/*.xml tests/diagnostics/sdf3/*.xml; do
      cp "$f" "build-fuzz/corpus-fuzz_sdf3_reader/$(echo "$f" | tr / _)"
    done
    for f in tests/e2e/sdf/*.json tests/diagnostics/taskgraph/*.json; do
      cp "$f" "build-fuzz/corpus-fuzz_taskgraph_reader/$(echo "$f" | tr / _)"
    done
    for f in tests/e2e/ir/*.ir specs/examples/quantitative/*.ir; do cp "$f" "build-fuzz/corpus-fuzz_ir_reader/$(echo "$f" | tr / _)"; done
    for f in specs/*.semo specs/examples/*/*.semo tests/diagnostics/common/*.semo; do
      cp "$f" "build-fuzz/corpus-fuzz_mission_parser/$(echo "$f" | tr / _)"
    done
    for f in specs/examples/*/strategy.xml tests/diagnostics/common/*.xml; do
      cp "$f" "build-fuzz/corpus-fuzz_strategy_reader/$(echo "$f" | tr / _)"
    done
    # Traces: `check --json` of the fuzz target's own model (tests/fuzz/corpus/make_trace_seeds.py
    # writes them), and the refused ones of the diagnostics tests.
    for f in tests/fuzz/corpus/trace/*.json tests/diagnostics/trace/*.json; do
      cp "$f" "build-fuzz/corpus-fuzz_trace_reader/$(echo "$f" | tr / _)"
    done
    for f in specs/examples/*/*.world.json tests/diagnostics/world/*.json; do
      cp "$f" "build-fuzz/corpus-fuzz_world_reader/$(echo "$f" | tr / _)"
    done
    # Generated tables: emit's own output for the swarm example.
    ./build-fuzz/tools/semo-verify emit specs/examples/swarm/swarm3.semo -s specs/examples/swarm/strategy.xml \
      --out build-fuzz/emitted > /dev/null
    for f in build-fuzz/emitted/mission/mission_tables.cpp build-fuzz/emitted/robots/*/tables.cpp; do
      cp "$f" "build-fuzz/corpus-fuzz_tables_reader/$(echo "$f" | tr / _)"
    done
    # Each target with the dictionary of its language (tests/fuzz/dict, the reader's own words),
    # and inputs up to 64 KiB: long enough for the nesting limits (256 levels) and for long lines
    # and lists, which a few kilobytes never reach.
    declare -A dictionary=([fuzz_mission_parser]=mission [fuzz_strategy_reader]=strategy [fuzz_ir_reader]=ir
                           [fuzz_sdf3_reader]=sdf3 [fuzz_taskgraph_reader]=taskgraph [fuzz_trace_reader]=trace
                           [fuzz_world_reader]=world)
    for target in "${targets[@]}"; do
      corpus="build-fuzz/corpus-$target"
      dict=()
      [ -z "${dictionary[$target]:-}" ] || dict=(-dict="tests/fuzz/dict/${dictionary[$target]}.dict")
      echo "== fuzzing $target for ${seconds}s ${dict[*]:-}"
      ./build-fuzz/tests/fuzz/"$target" -max_total_time="$seconds" -max_len=65536 -timeout=10 -rss_limit_mb=4096 \
        "${dict[@]}" -artifact_prefix=build-fuzz/ "$corpus"
    done
    ;;
  *)
    echo "usage: tools/setup.sh run|test|sanitize|fuzz" >&2
    exit 2
    ;;
esac
