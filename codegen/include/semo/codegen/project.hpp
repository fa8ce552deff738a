#pragma once
// The projection of a translated mission onto its robots (specs/runtime.md, "The projection"):
// every IR rule of a robot's program becomes one row of that robot's step tables, with the rule's
// index; every other IR rule (deliveries, losses, crashes, heartbeat periods, takeovers, learning,
// discoveries, mode defaults) is indexed where the runtime takes that step; every IR variable gets
// its place in the abstraction function. Nothing here reads the mission a second time: rows come
// from the lowering the translation made together with the IR.
#include "semo/frontend/source.hpp"
#include "semo/runtime/tables.hpp"
#include "semo/semantics/translate.hpp"

namespace semo::codegen {

// `mission` must be the model `translation` was made from (the lowering points into it).
runtime::MissionTables project(const model::MissionModel& mission, const Translation& translation, const SourceManager& sources);

}  // namespace semo::codegen
