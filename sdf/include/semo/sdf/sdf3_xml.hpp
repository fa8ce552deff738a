#pragma once
// SDF3's XML graph format (<sdf3 type="sdf"><applicationGraph><sdf>actors, ports, channels</sdf>
// <sdfProperties>execution times</sdfProperties>), read with positioned diagnostics: a malformed
// graph (unknown actor or port, a port used twice, a rate that is not a positive integer, ...) is
// reported at its element or attribute, and nothing is returned.
#include <optional>

#include "semo/frontend/diagnostics.hpp"
#include "semo/sdf/graph.hpp"

namespace semo::sdf {

std::optional<Graph> readSdf3(const SourceManager& sources, FileId file, DiagnosticEngine& diags);

}  // namespace semo::sdf
