#!/bin/sh
# `cmake --install` into a fresh prefix, then the installed program on the installed example (from
# another folder, so that nothing of the source tree is read), a project emitted there configured
# against the installed runtime, and `cpack` making the Debian package with the program in it.
# Arguments: BUILD_DIR WORK_DIR
set -eu
build="$1"; work="$2"
rm -rf "$work"; mkdir -p "$work"; cd "$work"
cmake --install "$build" --prefix "$work/prefix" > install.log
share="$work/prefix/share/semo/specs/examples/swarm"
"$work/prefix/bin/semo-verify" check "$share/swarm3.semo" --strategy "$share/strategy.xml" > check.txt
grep -q "^result: 6 proven, 0 violated, 0 unknown" check.txt
"$work/prefix/bin/semo-verify" emit "$share/swarm3.semo" --strategy "$share/strategy.xml" --out "$work/emitted" > emit.txt
cmake -S "$work/emitted" -B "$work/emitted/build" -Dsemo_runtime_DIR="$work/prefix/lib/cmake/semo_runtime" > configure.log
(cd "$build" && cpack -G DEB -B "$work/deb" > "$work/cpack.log")
dpkg-deb -c "$work"/deb/semo_*.deb | grep -q "./usr/bin/semo-verify$"
dpkg-deb -c "$work"/deb/semo_*.deb | grep -q "./usr/share/semo/specs/examples/scouting/scouting.semo$"
dpkg-deb -I "$work"/deb/semo_*.deb | grep -q "Depends: libz3-4"
echo INSTALLED-AND-PACKAGED
