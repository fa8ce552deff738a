#pragma once
// Task graphs as JSON (semo's own interchange form, specs/taskgraph.md) and as Graphviz dot.
#include <optional>
#include <string>

#include "semo/frontend/diagnostics.hpp"
#include "semo/frontend/source.hpp"
#include "semo/sdf/task_graph.hpp"

namespace semo::sdf {

std::string taskGraphToJson(const TaskGraph& tg);

// Reads what taskGraphToJson writes (and hand-written graphs of the same form). Every error is a
// positioned diagnostic; the result is nullopt if there was any.
std::optional<TaskGraph> readTaskGraphJson(const SourceManager& sources, FileId file, DiagnosticEngine& diags);

// One cluster per task kind is not needed at this size: tasks are boxes (the control task a
// double octagon, communication tasks ellipses), channels edges labelled "p:c" with initial tokens
// as "•n"; remote ports dashed edges to a node per multicast group or link. Rates are those of
// the first scenario that uses the channel.
std::string taskGraphToGraphviz(const TaskGraph& tg);

}  // namespace semo::sdf
