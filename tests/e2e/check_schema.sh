#!/bin/sh
# specs/check.schema.json against real outputs of check --json: a safety violation (explicit and
# smt), a lasso, vacuous checks, a selection, an IR model; and a broken copy must fail.
# Arguments: SEMO_VERIFY SOURCE_DIR WORK_DIR
set -eu
semo="$1"; src="$2"; work="$3"
rm -rf "$work"; mkdir -p "$work"; cd "$src"
run() { name="$1"; shift; "$semo" check "$@" --json > "$work/$name.json" 2>/dev/null || true; }
run deadlock specs/defects/double_receive.semo -s specs/defects/strategy.xml
run deadlock_smt specs/defects/double_receive.semo -s specs/defects/strategy.xml --engine smt --max-depth 12
run formation_smt specs/defects/lone_lidar.semo -s specs/defects/strategy.xml --engine smt --max-depth 3
run lasso tests/e2e/ir/retry_delivery_weak.ir
run vacuous tests/e2e/inputs/vacuous_checks.semo -s tests/diagnostics/common/strategy.xml
run selection specs/examples/swarm/swarm3.semo -s specs/examples/swarm/strategy.xml --prop mode_agreement --loss events --crash 1:Swarm
mkdir -p "$work/lint"
"$semo" lint specs/examples/scouting/scouting.semo -s specs/examples/scouting/strategy.xml --json > "$work/lint/clean.json" || true
"$semo" lint tests/e2e/inputs/undefined_mode.semo -s specs/examples/scouting/strategy.xml --json > "$work/lint/errors.json" || true
"$semo" lint tests/diagnostics/common/mission.semo -s tests/diagnostics/strategy/urdf_file_missing.xml --json > "$work/lint/notes.json" || true
python3 - "$src/specs/lint.schema.json" "$work/lint" <<'PY'
import json, pathlib, sys
import jsonschema
schema = json.load(open(sys.argv[1]))
jsonschema.Draft202012Validator.check_schema(schema)
validator = jsonschema.Draft202012Validator(schema)
files = sorted(pathlib.Path(sys.argv[2]).glob("*.json"))
assert len(files) == 3, files
noted = 0
for f in files:
    doc = json.load(open(f))
    errors = list(validator.iter_errors(doc))
    assert not errors, f"{f.name}: {errors[0].message} at {list(errors[0].path)}"
    noted += sum(1 for d in doc["diagnostics"] if d.get("notes"))
assert noted >= 1, "a diagnostic with a note was read"
PY
mkdir -p "$work/sdf" "$work/analyze"
"$semo" sdf specs/examples/scouting/scouting.semo -s specs/examples/scouting/strategy.xml --json > "$work/sdf/scouting.json" || true
"$semo" sdf --graph tests/e2e/sdf/taskgraph_deadlock.json --json > "$work/sdf/deadlock.json" || true
"$semo" analyze specs/examples/quantitative/gamble.ir --json --rounds 3 > "$work/analyze/gamble.json" || true
"$semo" analyze specs/examples/quantitative/leader_sync_4_4.ir --json --reward pick --max-states 100 --runs 500 > "$work/analyze/estimated.json" 2>/dev/null || true
"$semo" analyze specs/examples/scouting/scouting.semo -s specs/examples/scouting/strategy.xml --loss-prob 0.2 --rounds 2 --json > "$work/analyze/mission.json" || true
"$semo" analyze specs/examples/swarm/swarm10.semo -s specs/examples/swarm/strategy.xml --loss-prob 0.6 --rounds 2 --max-states 1000 --runs 200 --json > "$work/analyze/swarm.json" 2>/dev/null || true
for kind in sdf analyze; do
python3 - "$src/specs/$kind.schema.json" "$work/$kind" <<'PY'
import json, pathlib, sys
import jsonschema
schema = json.load(open(sys.argv[1]))
jsonschema.Draft202012Validator.check_schema(schema)
validator = jsonschema.Draft202012Validator(schema)
files = sorted(pathlib.Path(sys.argv[2]).glob("*.json"))
assert len(files) >= 2, files
for f in files:
    doc = json.load(open(f))
    errors = list(validator.iter_errors(doc))
    assert not errors, f"{sys.argv[1]} {f.name}: {errors[0].message} at {list(errors[0].path)}"
PY
done
python3 - "$src/specs/check.schema.json" "$work" <<'PY'
import json, pathlib, sys
import jsonschema
schema = json.load(open(sys.argv[1]))
jsonschema.Draft202012Validator.check_schema(schema)
validator = jsonschema.Draft202012Validator(schema)
files = sorted(pathlib.Path(sys.argv[2]).glob("*.json"))
assert len(files) == 6, files
for f in files:
    doc = json.load(open(f))
    errors = list(validator.iter_errors(doc))
    assert not errors, f"{f.name}: {errors[0].message} at {list(errors[0].path)}"
broken = json.load(open(files[0]))
del broken["properties"][0]["verdict"]
assert list(validator.iter_errors(broken)), "a property without its verdict must fail"
print(f"SCHEMA-VALIDATES: {len(files)} outputs (and 3 of lint, 2 of sdf, 4 of analyze)")
PY
