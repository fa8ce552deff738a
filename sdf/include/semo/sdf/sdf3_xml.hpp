#pragma once
// SDF3's XML graph format (<sdf3 type="sdf"><applicationGraph><sdf>actors, ports, channels</sdf>
// <sdfProperties>execution times</sdfProperties>), read with positioned diagnostics: a malformed
// graph (unknown actor or port, a port used twice, a rate that is not a positive integer, ...) is
// reported at its element or attribute, and nothing is returned.
#include <optional>
#include <string>

#include "semo/frontend/diagnostics.hpp"
#include "semo/sdf/graph.hpp"

namespace semo::sdf {

std::optional<Graph> readSdf3(const SourceManager& sources, FileId file, DiagnosticEngine& diags);

// The graph in SDF3's format (one port per channel end, execution times on a default processor
// "p1"); readSdf3 gives the same graph back.
std::string writeSdf3(const Graph& g);

// The graph for Graphviz: actors as boxes (name, execution time), channels as edges labelled with
// their rates and initial tokens.
std::string toGraphviz(const Graph& g);

}  // namespace semo::sdf
