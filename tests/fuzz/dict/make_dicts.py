#!/usr/bin/env python3
"""Writes the libFuzzer dictionaries of tests/fuzz/dict: each reader's own string literals (its
keywords, element, attribute and key names) and its language's punctuation, so that the fuzzer
builds well-formed pieces instead of finding each keyword byte by byte. Run it again when a
reader learns new words: python3 tests/fuzz/dict/make_dicts.py"""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[3]
JSON = {"{", "}", "[", "]", ":", ",", "true", "false", "null"}


def literals(*paths):
    out = set()
    for p in paths:
        out |= set(re.findall(r'"([A-Za-z_][A-Za-z_0-9.]*)"', (ROOT / p).read_text()))
    return out


def write(name, header, words):
    words = sorted(w for w in words if w and len(w) < 40)
    lines = [f"# {header}", "# libFuzzer dictionary, written by make_dicts.py (the reader's string literals and punctuation)."]
    for i, w in enumerate(words):
        lines.append('kw{}="{}"'.format(i, w.replace("\\", "\\\\").replace('"', '\\"')))
    (ROOT / "tests/fuzz/dict" / f"{name}.dict").write_text("\n".join(lines) + "\n")


write("mission", "the mission language (fuzz_mission_parser)",
      literals("frontend/src/lexer.cpp", "frontend/src/parser_verify.cpp", "frontend/src/parser_stmts.cpp",
               "frontend/src/parser_decls.cpp", "frontend/src/parser_exprs.cpp")
      | {"SEC", "MSEC", "MIN", "instance of", "capable of", "[[", "]]", "{", "}", "(", ")", "==", "!=", "<=", ">=", "mode", ".", ":", "#"})
write("ir", "the IR text (fuzz_ir_reader)",
      literals("semantics/src/ir_reader.cpp")
      | {"semo-ir 1", "@robot(", '@values("', '@facts("', "@kind(", '@origin("', '@label("', "@fair", "@strongly_fair", '@senses("',
         "@settled", '@construct("', "->", "..", "&&", "||", "=>", "==", "!=", "<=", ">=", "'", "min(", "max(", "always", "eventually",
         "until", "release", "next", "{", "}"})
write("strategy", "strategy XML (fuzz_strategy_reader)",
      literals("frontend/src/strategy_reader.cpp", "frontend/src/xml_support.cpp")
      | {'<?xml version="1.0"?>', "<strategy", "</strategy>", "<service", "<implementation", "<task", "<port", "<channel", "<value",
         "<knowledge", "<dissemination", "<goal", "<domain", "<param", "<capability", "<!DOCTYPE", "<!ENTITY", "/>", '="'})
write("sdf3", "SDF3 XML (fuzz_sdf3_reader)",
      literals("sdf/src/sdf3_xml.cpp")
      | {'<?xml version="1.0"?>', "<sdf3", "<applicationGraph", "<sdf", "<actor", "<port", "<channel", "<sdfProperties",
         "<actorProperties", "<processor", "<executionTime", "/>", '="'})
write("taskgraph", "task-graph JSON (fuzz_taskgraph_reader)", literals("sdf/src/task_graph_json.cpp") | JSON)
write("trace", "counterexample JSON (fuzz_trace_reader)", literals("checker/src/trace_reader.cpp") | JSON)
write("world", "world JSON (fuzz_world_reader)", literals("runtime/src/world_reader.cpp") | JSON)
