#!/usr/bin/env python3
"""Lines of the code `semo-verify emit` generated, per robot, in the categories of the SeMo paper's
Table I (README, "Generated code"): the robot's control task (its plan tables: control points and
rows), its communication (the rules of what it receives, heartbeats, gossip, crashes), its data
structures (its task graph: tasks, channels with their proven capacities, the static schedule of
each scenario), its main, the mission's shared tables (every robot's program compiles them), and
semo_runtime ("scheduler, etc.": the interpreter, transports, dataflow runner), shared by all.

  tools/generated_lines.py DIR [SEMO_SOURCE_DIR]
"""
import pathlib
import re
import sys

CONTROL = {"plans"}
DATA = {"dataflow"}
IDENTITY = {"name", "type", "team", "indexInTeam", "geometry"}


def member_lines(path):
    """Lines of each top-level member of the robot's table initializer."""
    counts = {}
    current = None
    inside = False
    for line in path.read_text().splitlines():
        if line.startswith("  static const RobotTable table{"):
            inside = True
            continue
        if not inside:
            continue
        if line.startswith("  };"):
            break
        m = re.match(r"^      \.(\w+) = ", line)
        if m:
            current = m.group(1)
        if current:
            counts[current] = counts.get(current, 0) + 1
    return counts


def lines(path):
    return len(path.read_text().splitlines())


def main():
    out = pathlib.Path(sys.argv[1])
    source = pathlib.Path(sys.argv[2]) if len(sys.argv) > 2 else pathlib.Path(__file__).resolve().parent.parent
    runtime = sum(lines(p) for p in (source / "runtime").rglob("*") if p.suffix in (".cpp", ".hpp"))
    shared = sum(lines(out / "mission" / f) for f in ("mission_tables.cpp", "assemble.cpp", "mission.hpp"))
    print("| robot | control task | communication | data structures | main | shared tables | semo_runtime | robot code |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for robot in sorted((out / "robots").iterdir()):
        counts = member_lines(robot / "tables.cpp")
        control = sum(v for k, v in counts.items() if k in CONTROL)
        data = sum(v for k, v in counts.items() if k in DATA)
        comms = sum(v for k, v in counts.items() if k not in CONTROL | DATA | IDENTITY)
        main_lines = lines(robot / "main.cpp")
        total = lines(robot / "tables.cpp") + main_lines + shared + runtime
        print(f"| {robot.name} | {control} | {comms} | {data} | {main_lines} | {shared} | {runtime:,} | {total:,} |")


if __name__ == "__main__":
    main()
