#pragma once
// Loading the benchmark graphs of specs/benchmarks for the sdf unit tests.
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "semo/sdf/sdf3_xml.hpp"

namespace semo::sdf::test {

// A graph under specs/benchmarks ("sdf3/modem.xml", "generated/..."); any read error fails the test.
inline Graph benchmarkGraph(const std::string& path) {
  SourceManager sources;
  DiagnosticEngine diags(sources);
  std::string error;
  const FileId file = sources.load(SEMO_SOURCE_DIR "/specs/benchmarks/" + path, error);
  EXPECT_TRUE(error.empty()) << error;
  if (!error.empty()) return Graph{};
  std::optional<Graph> g = readSdf3(sources, file, diags);
  for (const Diagnostic& d : diags.diagnostics()) ADD_FAILURE() << diags.format(d);
  return g ? *g : Graph{};
}

// One of SDF3's five graphs, by name ("samplerate").
inline Graph sdf3Benchmark(const std::string& name) { return benchmarkGraph("sdf3/" + name + ".xml"); }

}  // namespace semo::sdf::test
