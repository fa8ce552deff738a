#pragma once
// A counterexample as a message sequence chart (SVG): a lifeline per robot; each step a row, its
// number, robot, label and mission line in the left column and a mark on the robot's lifeline;
// arrows from the step that sent something (an event thrown, a message published or sent, a fact
// gossiped) to the step that received it, dashed and crossed when it was lost; a cross where a
// robot crashes, a box where its mode or role changes; a lasso's loop framed. The same trace gives
// the same bytes.
#include <string>

#include "semo/checker/trace.hpp"
#include "semo/semantics/ir.hpp"

namespace semo::cli {

std::string sequenceChartSvg(const ir::Model& model, const checker::Trace& trace, const std::string& title);

}  // namespace semo::cli
