#!/bin/sh
# specs/{check,lint,sdf,analyze}.schema.json against real outputs: check (a safety violation with
# both engines, a lasso, counting (proven, not applicable), a lasso naming knowledge facts, vacuous checks, a selection), lint (clean, errors, notes), sdf (a mission, a
# deadlocking graph), analyze (exact, estimated, two missions); a broken check output must fail.
# Arguments: SEMO_VERIFY SOURCE_DIR WORK_DIR
set -eu
semo="$1"; src="$2"; work="$3"
rm -rf "$work"; mkdir -p "$work/check" "$work/lint" "$work/sdf" "$work/analyze"; cd "$src"
# keep KIND NAME ARGS...: `semo-verify KIND ARGS --json` into WORK/KIND/NAME.json, whatever its exit code.
keep() { kind="$1"; name="$2"; shift 2; "$semo" "$kind" "$@" --json > "$work/$kind/$name.json" 2>/dev/null || true; }
keep check deadlock specs/defects/double_receive.semo -s specs/defects/strategy.xml
keep check deadlock_smt specs/defects/double_receive.semo -s specs/defects/strategy.xml --engine smt --max-depth 12
keep check formation_smt specs/defects/lone_lidar.semo -s specs/defects/strategy.xml --engine smt --max-depth 3
keep check lasso tests/e2e/ir/retry_delivery_weak.ir
keep check facts specs/defects/liveness/stuck_gossip.semo -s specs/defects/liveness/strategy.xml
keep check vacuous tests/e2e/inputs/vacuous_checks.semo -s tests/diagnostics/common/strategy.xml
keep check selection specs/examples/swarm/swarm3.semo -s specs/examples/swarm/strategy.xml --prop mode_agreement --loss events --crash 1:Swarm
keep check counting specs/examples/swarm/swarm1000.semo -s specs/examples/swarm/strategy.xml --engine auto
keep check counting_none specs/examples/chase/chase.semo -s specs/examples/chase/strategy.xml --engine counting
keep lint clean specs/examples/scouting/scouting.semo -s specs/examples/scouting/strategy.xml
keep lint errors tests/e2e/inputs/undefined_mode.semo -s specs/examples/scouting/strategy.xml
keep lint notes tests/diagnostics/common/mission.semo -s tests/diagnostics/strategy/urdf_file_missing.xml
keep sdf scouting specs/examples/scouting/scouting.semo -s specs/examples/scouting/strategy.xml
keep sdf deadlock --graph tests/e2e/sdf/taskgraph_deadlock.json
keep analyze gamble specs/examples/quantitative/gamble.ir --rounds 3
keep analyze estimated specs/examples/quantitative/leader_sync_4_4.ir --reward pick --max-states 100 --runs 500
keep analyze mission specs/examples/scouting/scouting.semo -s specs/examples/scouting/strategy.xml --loss-prob 0.2 --rounds 2
keep analyze swarm specs/examples/swarm/swarm10.semo -s specs/examples/swarm/strategy.xml --loss-prob 0.6 --rounds 2 --max-states 1000 --runs 200
python3 - "$src/specs" "$work" <<'PY'
import json, pathlib, sys
import jsonschema
specs, work = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
counts, validators = {}, {}
for kind, expected in (("check", 9), ("lint", 3), ("sdf", 2), ("analyze", 4)):
    schema = json.load(open(specs / f"{kind}.schema.json"))
    jsonschema.Draft202012Validator.check_schema(schema)
    validators[kind] = validator = jsonschema.Draft202012Validator(schema)
    files = sorted((work / kind).glob("*.json"))
    assert len(files) == expected, (kind, files)
    for f in files:
        errors = list(validator.iter_errors(json.load(open(f))))
        assert not errors, f"{kind}/{f.name}: {errors[0].message} at {list(errors[0].path)}"
    counts[kind] = len(files)
named = [c["facts"] for p in json.load(open(work / "check" / "facts.json"))["properties"] if "counterexample" in p
         for s in p["counterexample"]["steps"] for c in s["changes"] if "facts" in c]
assert named == [["north"], ["north", "south"]], f"knowledge facts named in the trace: {named}"
noted = sum(1 for f in (work / "lint").glob("*.json") for d in json.load(open(f))["diagnostics"] if d.get("notes"))
assert noted >= 1, "a diagnostic with a note was read"
broken = json.load(open(work / "check" / "deadlock.json"))
del broken["properties"][0]["verdict"]
assert list(validators["check"].iter_errors(broken)), "a property without its verdict must fail"
print(f"SCHEMA-VALIDATES: {counts['check']} outputs (and {counts['lint']} of lint, {counts['sdf']} of sdf, {counts['analyze']} of analyze)")
PY
