#!/usr/bin/env python3
"""Regenerates the seed traces of fuzz_trace_reader (tests/fuzz/corpus/trace/): what
`semo-verify check --json` writes for the fuzz target's own model (kModel in fuzz_trace_reader.cpp),
whole and one counterexample at a time, so that the fuzzer starts from traces the reader accepts.

    tests/fuzz/corpus/make_trace_seeds.py build/tools/semo-verify

The model's `jump` rule takes c out of its range, which stops the search before deadlocks and
lassos: those two come from a variant without `jump` (the same variables and other rules, so the
same steps replay on the fuzz model), with its fingerprint left out (a fingerprint is optional).
Every seed but check_smt.json reads back on the fuzz model (that one names a property the smt
engine left unknown: a refusal to start from).
"""
import json
import pathlib
import re
import subprocess
import sys
import tempfile

here = pathlib.Path(__file__).resolve().parent
verify = sys.argv[1] if len(sys.argv) > 1 else str(here.parents[2] / "build/tools/semo-verify")
source = (here.parent / "fuzz_trace_reader.cpp").read_text()
model = re.search(r'kModel = R"\((.*?)\)";', source, re.S).group(1)
out = here / "trace"
out.mkdir(exist_ok=True)


def check(text, *options):
    with tempfile.TemporaryDirectory() as tmp:
        ir = pathlib.Path(tmp) / "fuzz.ir"
        ir.write_text(text)
        r = subprocess.run([str(pathlib.Path(verify).resolve()), "check", "fuzz.ir", "--json", *options], capture_output=True, text=True, cwd=tmp)
        if r.returncode not in (0, 1, 3):
            sys.exit(f"semo-verify check failed ({r.returncode}): {r.stderr}")
        return r.stdout


def write(name, text):
    (out / name).write_text(text if text.endswith("\n") else text + "\n")


full = check(model)
write("check.json", full)
write("check_smt.json", check(model, "--engine", "smt", "--max-depth", "4"))
report = json.loads(full)
for p in report["properties"]:
    if "counterexample" in p:
        write(f"counterexample_{p['name']}.json", json.dumps(p["counterexample"], indent=2))
if report.get("modelError"):
    write("model_error.json", json.dumps(report["modelError"], indent=2))

# Without `jump`, and with the deadlocks where d holds counted valid: the deadlock found then is one
# the fuzz model has too (with d false, `jump` stays disabled).
variant = "\n".join(line for line in model.splitlines() if not line.startswith("rule jump"))
variant = variant.replace("valid_end : mode == 2 && c == 0;", "valid_end : (mode == 2 && c == 0) || d;")
for p in json.loads(check(variant))["properties"]:
    cx = p.get("counterexample")
    if cx and cx["kind"] in ("deadlock", "lasso"):
        cx.pop("modelFingerprint", None)
        write(f"counterexample_{cx['kind']}.json", json.dumps(cx, indent=2))
print("\n".join(sorted(str(f.relative_to(here.parents[2])) for f in out.iterdir())))
