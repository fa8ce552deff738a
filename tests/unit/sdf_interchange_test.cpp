// SDF3's format written back: every benchmark graph reads back the same (actors, times, channels,
// rates, tokens), and the analyses give the same figures; the Graphviz form names every actor and
// channel.
#include <gtest/gtest.h>

#include "semo/sdf/consistency.hpp"
#include "semo/sdf/sdf3_xml.hpp"
#include "semo/sdf/throughput.hpp"

namespace semo::sdf {
namespace {

std::optional<Graph> read(SourceManager& sources, DiagnosticEngine& diags, const std::string& path, const std::string* text) {
  FileId file = 0;
  if (text != nullptr) {
    file = sources.add(path, *text);
  } else {
    std::string error;
    file = sources.load(path, error);
    EXPECT_TRUE(error.empty()) << error;
  }
  std::optional<Graph> g = readSdf3(sources, file, diags);
  for (const Diagnostic& d : diags.diagnostics()) ADD_FAILURE() << diags.format(d);
  return g;
}

TEST(SdfInterchange, Sdf3BenchmarksRoundTrip) {
  for (const char* name : {"h263decoder", "modem", "samplerate", "satellite", "mp3decoder_granule_parallelism"}) {
    SCOPED_TRACE(name);
    SourceManager sources;
    DiagnosticEngine diags(sources);
    std::optional<Graph> original = read(sources, diags, SEMO_SOURCE_DIR "/specs/benchmarks/sdf3/" + std::string(name) + ".xml", nullptr);
    ASSERT_TRUE(original.has_value());
    std::string text = writeSdf3(*original);
    std::optional<Graph> again = read(sources, diags, "written.xml", &text);
    ASSERT_TRUE(again.has_value());
    ASSERT_EQ(again->actors.size(), original->actors.size());
    ASSERT_EQ(again->channels.size(), original->channels.size());
    for (std::size_t a = 0; a < original->actors.size(); ++a) {
      EXPECT_EQ(again->actors[a].name, original->actors[a].name);
      EXPECT_EQ(again->actors[a].executionTime, original->actors[a].executionTime);
    }
    for (std::size_t c = 0; c < original->channels.size(); ++c) {
      const Channel& x = original->channels[c];
      const Channel& y = again->channels[c];
      EXPECT_EQ(std::tie(x.name, x.source, x.target, x.production, x.consumption, x.initialTokens),
                std::tie(y.name, y.source, y.target, y.production, y.consumption, y.initialTokens));
    }
    RepetitionVector q = repetitionVector(*again);
    ASSERT_TRUE(q.consistent());
    EXPECT_EQ(q.firings, repetitionVector(*original).firings);
    EXPECT_EQ(throughput(*again, q.firings).period, throughput(*original, q.firings).period);
    EXPECT_EQ(writeSdf3(*again), text) << "writing is deterministic";
  }
}

TEST(SdfInterchange, NamesThatNeedEscaping) {
  Graph g;
  g.name = "a<b>&\"c\"";
  g.actors = {{"x&y", 3, {}}, {"<z>", 4, {}}};
  g.channels = {{"c\"1", 0, 1, 2, 3, 1, {}}};
  SourceManager sources;
  DiagnosticEngine diags(sources);
  std::string text = writeSdf3(g);
  std::optional<Graph> again = read(sources, diags, "escaped.xml", &text);
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ(again->name, g.name);
  EXPECT_EQ(again->actors[0].name, "x&y");
  EXPECT_EQ(again->actors[1].name, "<z>");
  EXPECT_EQ(again->channels[0].name, "c\"1");
  EXPECT_EQ(again->channels[0].initialTokens, 1);
  std::string dot = toGraphviz(g);
  EXPECT_NE(dot.find("digraph \"a<b>&\\\"c\\\"\""), std::string::npos) << dot;
  EXPECT_NE(dot.find("a0 -> a1 [label=\"c\\\"1: 2 -> 3 (1 tokens)\"]"), std::string::npos) << dot;
}

}  // namespace
}  // namespace semo::sdf
