// Runs every annotated input under tests/diagnostics/ and compares the diagnostics semo reports with
// the expectations written in the file itself:
//
//   # expected-error@+1:7 {{undefined mode 'SEARCH'}}      (mission files, in a comment)
//   <!-- expected-warning@+1:3 {{timeout}} -->             (strategy and URDF files)
//
//   "_expect": ["expected-error@4:35 {{a point is [x, y]}}"]  (world files: a comment member)
//
// `@+N` / `@-N` are relative to the annotation's line, `@N` is absolute; `:COL` is the exact column.
// The text in {{ }} must occur in the message. Every error and warning reported in the annotated file
// must be expected, and every expectation must be met. Directives choose the companion files:
//   # strategy: ../common/strategy.xml      (mission cases; this is the default)
//   <!-- mission: ../common/mission.semo --> (strategy cases; this is the default)
// Trace cases (trace/*.json, read back with checker/trace_reader.hpp) name the model to replay on
// with members the reader ignores: "_model" (a mission or an .ir file, relative to the case),
// "_strategy" (default: strategy.xml beside the mission) and "_property" (which counterexample of a
// check output; default the first). Their expectations are in an "_expect" string, as for task graphs.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "semo/checker/trace_reader.hpp"
#include "semo/frontend/robot_catalog.hpp"
#include "semo/runtime/world.hpp"
#include "semo/sdf/sdf3_xml.hpp"
#include "semo/sdf/task_graph_io.hpp"
#include "semo/semantics/ir_text.hpp"
#include "semo/semantics/load.hpp"
#include "semo/semantics/translate.hpp"

namespace fs = std::filesystem;

namespace {

struct Expectation {
  semo::Severity severity;
  std::uint32_t line;
  std::uint32_t column;
  std::string text;
  bool met = false;
};

std::string readFile(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

std::vector<Expectation> readExpectations(const std::string& text) {
  static const std::regex pattern(R"(expected-(error|warning|note)@([+-]?)(\d+):(\d+)\s*\{\{(.*?)\}\})");
  std::vector<Expectation> out;
  std::istringstream lines(text);
  std::string line;
  for (std::uint32_t number = 1; std::getline(lines, line); ++number) {
    for (std::sregex_iterator it(line.begin(), line.end(), pattern), end; it != end; ++it) {
      const std::smatch& m = *it;
      auto severity = m[1] == "error" ? semo::Severity::Error : m[1] == "warning" ? semo::Severity::Warning : semo::Severity::Note;
      auto amount = static_cast<std::uint32_t>(std::stoul(m[3]));
      std::uint32_t target = m[2] == "+" ? number + amount : m[2] == "-" ? number - amount : amount;
      out.push_back({severity, target, static_cast<std::uint32_t>(std::stoul(m[4])), m[5], false});
    }
  }
  return out;
}

std::string directive(const std::string& text, const std::string& key, const std::string& fallback) {
  std::smatch m;
  std::regex pattern(key + R"(:\s*([^\s>]+))");
  return std::regex_search(text, m, pattern) ? m[1].str() : fallback;
}

// A trace case's "_key": "value" member.
std::string jsonDirective(const std::string& text, const std::string& key, const std::string& fallback) {
  std::smatch m;
  std::regex pattern("\"_" + key + R"re("\s*:\s*"([^"]*)")re");
  return std::regex_search(text, m, pattern) ? m[1].str() : fallback;
}

// The model a trace case is replayed on: an IR file, or a mission translated with its strategy.
std::optional<semo::ir::Model> traceModel(const fs::path& file, const std::string& text, semo::SourceManager& sources,
                                          semo::DiagnosticEngine& diags) {
  fs::path model = (file.parent_path() / jsonDirective(text, "model", "")).lexically_normal();
  if (model.extension() == ".ir") {
    std::string error;
    semo::FileId id = sources.load(model.string(), error);
    if (id == semo::kNoFile) {
      ADD_FAILURE() << error;
      return std::nullopt;
    }
    return semo::ir::parseText(sources, id, diags);
  }
  fs::path strategy = jsonDirective(text, "strategy", "").empty() ? model.parent_path() / "strategy.xml"
                                                                  : file.parent_path() / jsonDirective(text, "strategy", "");
  auto mission = semo::loadMission({model.string(), strategy.lexically_normal().string(), std::nullopt}, sources, diags);
  if (!mission) return std::nullopt;
  return semo::translate(*mission, {}, sources, diags);
}

const char* name(semo::Severity s) {
  return s == semo::Severity::Error ? "error" : s == semo::Severity::Warning ? "warning" : "note";
}

std::vector<fs::path> cases() {
  std::vector<fs::path> out;
  for (const char* folder : {"mission", "strategy", "urdf", "sdf3", "taskgraph", "world", "trace"}) {
    fs::path dir = fs::path(SEMO_DIAGNOSTICS_DIR) / folder;
    if (!fs::exists(dir)) continue;
    for (const auto& entry : fs::directory_iterator(dir)) out.push_back(entry.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

class DiagnosticCase : public ::testing::TestWithParam<fs::path> {};

TEST_P(DiagnosticCase, ReportsExactlyTheExpectedDiagnostics) {
  const fs::path& file = GetParam();
  std::string text = readFile(file);
  std::vector<Expectation> expected = readExpectations(text);
  ASSERT_FALSE(expected.empty()) << file << " has no expected-error/expected-warning annotation";

  std::string kind = file.parent_path().filename().string();
  if (kind == "world") {
    // The runtime's world reader reports WorldErrors (the runtime links nothing of semo's diagnostics).
    std::vector<semo::runtime::WorldError> errors;
    EXPECT_FALSE(semo::runtime::readWorld(file.string(), errors).has_value()) << "a malformed world must not be returned";
    for (const semo::runtime::WorldError& d : errors) {
      bool matched = false;
      for (Expectation& e : expected) {
        if (e.met || e.severity != semo::Severity::Error || e.line != d.line || e.column != d.column) continue;
        if (d.message.find(e.text) == std::string::npos) continue;
        e.met = matched = true;
        break;
      }
      if (!matched) ADD_FAILURE() << "unexpected diagnostic:\n" << semo::runtime::formatWorldError(d);
    }
    for (const Expectation& e : expected) {
      EXPECT_TRUE(e.met) << file.filename().string() << ": expected error at " << e.line << ":" << e.column << " containing '" << e.text
                         << "' was not reported";
    }
    return;
  }

  semo::SourceManager sources;
  semo::DiagnosticEngine diags(sources);
  fs::path dir = file.parent_path();
  if (kind == "mission") {
    fs::path strategy = dir / directive(text, "strategy", "../common/strategy.xml");
    semo::loadMission({file.string(), strategy.lexically_normal().string(), std::nullopt}, sources, diags);
  } else if (kind == "strategy") {
    fs::path mission = dir / directive(text, "mission", "../common/mission.semo");
    semo::loadMission({mission.lexically_normal().string(), file.string(), std::nullopt}, sources, diags);
  } else if (kind == "sdf3") {
    std::string error;
    semo::FileId id = sources.load(file.string(), error);
    ASSERT_TRUE(error.empty()) << error;
    EXPECT_FALSE(semo::sdf::readSdf3(sources, id, diags).has_value()) << "a malformed graph must not be returned";
  } else if (kind == "taskgraph") {
    std::string error;
    semo::FileId id = sources.load(file.string(), error);
    ASSERT_TRUE(error.empty()) << error;
    EXPECT_FALSE(semo::sdf::readTaskGraphJson(sources, id, diags).has_value()) << "a malformed task graph must not be returned";
  } else if (kind == "trace") {
    std::optional<semo::ir::Model> model = traceModel(file, text, sources, diags);
    ASSERT_TRUE(model.has_value()) << file << ": its \"_model\" does not load";
    std::string error;
    semo::FileId id = sources.load(file.string(), error);
    ASSERT_TRUE(error.empty()) << error;
    semo::checker::TraceReadOptions options;
    options.property = jsonDirective(text, "property", "");
    EXPECT_FALSE(semo::checker::readTrace(sources, id, *model, diags, options).has_value()) << "a trace with errors must not be returned";
  } else {
    semo::loadRobotType(sources, file.string(), {}, diags);
  }

  std::vector<const semo::Diagnostic*> all;
  for (const semo::Diagnostic& d : diags.diagnostics()) {
    all.push_back(&d);
    for (const semo::Diagnostic& n : d.notes) all.push_back(&n);
  }
  for (const semo::Diagnostic* d : all) {
    const semo::SourceLocation& at = d->range.begin;
    bool inFile = at.valid() && fs::path(sources.path(at.file)).lexically_normal() == file.lexically_normal();
    bool matched = false;
    for (Expectation& e : expected) {
      if (e.met || !inFile || e.severity != d->severity || e.line != at.line || e.column != at.column) continue;
      if (d->message.find(e.text) == std::string::npos) continue;
      e.met = matched = true;
      break;
    }
    // Warnings about the shared companion files (such as an unused leader selection) are not the case's concern.
    bool companionWarning = !inFile && d->severity == semo::Severity::Warning;
    if (!matched && d->severity != semo::Severity::Note && !companionWarning) {
      ADD_FAILURE() << "unexpected diagnostic:\n" << diags.format(*d);
    }
  }
  for (const Expectation& e : expected) {
    EXPECT_TRUE(e.met) << file.filename().string() << ": expected " << name(e.severity) << " at " << e.line << ":" << e.column
                       << " containing '" << e.text << "' was not reported";
  }
}

std::string caseName(const ::testing::TestParamInfo<fs::path>& info) {
  std::string n = info.param.parent_path().filename().string() + "_" + info.param.stem().string();
  std::replace_if(n.begin(), n.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
  return n;
}

INSTANTIATE_TEST_SUITE_P(Files, DiagnosticCase, ::testing::ValuesIn(cases()), caseName);

}  // namespace
