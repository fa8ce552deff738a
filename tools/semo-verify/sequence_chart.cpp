#include "sequence_chart.hpp"
#include "svg_text.hpp"

#include <algorithm>
#include <map>
#include <optional>

#include <fmt/format.h>

namespace semo::cli {
namespace {

constexpr double kRow = 26, kTop = 70, kTextWidth = 470, kLane = 120, kMargin = 16;


std::string shortened(const std::string& text, std::size_t max) {
  return text.size() <= max ? text : text.substr(0, max - 3) + "...";
}

// Where a step's message came from: the step and robot that last set a variable the receiver does
// not own (another robot's event flag, message view or knowledge, or a shared channel).
struct Pending {
  std::size_t step;
  std::int32_t robot;
};

// The arrows of the chart: (from step, from robot) -> (to step, to robot), lost or not.
struct Arrow {
  std::size_t fromStep, toStep;
  std::int32_t from, to;
  bool lost;
  std::string what;
};

std::string variableShortName(const ir::Model& m, ir::VarId v) {
  const ir::Variable& var = m.variables[v];
  if (var.robot >= 0 && static_cast<std::size_t>(var.robot) < m.robots.size()) {
    const std::string& owner = m.robots[static_cast<std::size_t>(var.robot)];
    if (var.name.rfind(owner + ".", 0) == 0) return var.name.substr(owner.size() + 1);
  }
  return var.name;
}

}  // namespace

std::string sequenceChartSvg(const ir::Model& model, const checker::Trace& trace, const std::string& title) {
  const std::size_t robots = model.robots.size();
  bool worldSteps = false;  // steps of no robot (the network, timers, the world): a lane of their own
  for (const checker::Step& s : trace.steps) {
    const std::int32_t r = model.rules[s.rule].robot;
    worldSteps = worldSteps || r < 0 || static_cast<std::size_t>(r) >= robots;
  }
  const std::size_t lanes = robots + (worldSteps || robots == 0 ? 1 : 0);
  // Wide enough for the lanes and for the title (about 9 px a character at 14 px, bold).
  const double width = std::max(kMargin + kTextWidth + kLane * static_cast<double>(lanes) + kMargin, 2 * kMargin + 9.0 * static_cast<double>(title.size()));
  const std::size_t steps = trace.steps.size();
  const double height = kTop + kRow * static_cast<double>(steps + 1) + 48;
  auto laneX = [&](std::int32_t robot) {
    const std::size_t lane = robot >= 0 && static_cast<std::size_t>(robot) < robots ? static_cast<std::size_t>(robot) : robots;
    return kMargin + kTextWidth + kLane * (static_cast<double>(lane) + 0.5);
  };
  auto rowY = [&](std::size_t step) { return kTop + kRow * (static_cast<double>(step) + 0.5); };

  std::string out = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" font-family=\"sans-serif\" "
      "font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      "<defs><marker id=\"head\" viewBox=\"0 0 10 10\" refX=\"10\" refY=\"5\" markerWidth=\"7\" markerHeight=\"7\" orient=\"auto\">"
      "<path d=\"M0,0 L10,5 L0,10 z\" fill=\"#1f4e99\"/></marker>"
      "<marker id=\"lost\" viewBox=\"0 0 10 10\" refX=\"5\" refY=\"5\" markerWidth=\"9\" markerHeight=\"9\">"
      "<path d=\"M1,1 L9,9 M9,1 L1,9\" stroke=\"#c0392b\" stroke-width=\"2\"/></marker></defs>\n",
      width, height);
  out += fmt::format("<text x=\"{}\" y=\"22\" font-size=\"14\" font-weight=\"bold\">{}</text>\n", kMargin, svgEscaped(title));

  // Lifelines with their robots' names.
  for (std::size_t lane = 0; lane < lanes; ++lane) {
    const double x = laneX(lane < robots ? static_cast<std::int32_t>(lane) : -1);
    const std::string name = lane < robots ? model.robots[lane] : "network / world";
    out += fmt::format("<text class=\"robot\" x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\" font-weight=\"bold\">{}</text>\n", x, kTop - 16,
                       svgEscaped(shortened(name, 18)));
    out += fmt::format("<line class=\"lifeline\" x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{0:.1f}\" y2=\"{2:.1f}\" stroke=\"#999\"/>\n", x, kTop - 8,
                       kTop + kRow * static_cast<double>(steps) + 8);
  }

  // The loop of a lasso, behind everything else.
  if (trace.loopStart < steps) {
    const double y0 = kTop + kRow * static_cast<double>(trace.loopStart), y1 = kTop + kRow * static_cast<double>(steps);
    out += fmt::format("<rect class=\"loop\" x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"#fdf2e0\" stroke=\"#e67e22\" "
                       "stroke-dasharray=\"6,3\"/>\n",
                       kMargin / 2, y0, width - kMargin, y1 - y0);
    out += fmt::format("<text class=\"loop-label\" x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"end\" fill=\"#e67e22\" font-weight=\"bold\">"
                       "loop: steps {} to {} repeat for ever</text>\n",
                       width - kMargin - 4, y1 + 14, trace.loopStart + 1, steps);
  }

  // Arrows: from the step that set another robot's variable (or a shared one) to the step of the
  // robot that took it in (a delivery) or lost it (a loss).
  std::vector<Arrow> arrows;
  std::map<ir::VarId, Pending> pending;
  for (std::size_t k = 0; k < steps; ++k) {
    const checker::Step& s = trace.steps[k];
    const ir::Rule& rule = model.rules[s.rule];
    for (const checker::Change& c : s.changes) {
      const ir::Variable& var = model.variables[c.var];
      auto it = pending.find(c.var);
      const bool takesIn = rule.kind == ir::RuleKind::Delivery || rule.kind == ir::RuleKind::Loss;
      const bool crash = rule.kind == ir::RuleKind::Crash;  // a team's crash counter is no message
      if (it != pending.end() && it->second.robot != rule.robot && !crash && (takesIn || var.robot == rule.robot || var.robot < 0)) {
        arrows.push_back({it->second.step, k, it->second.robot, rule.robot, rule.kind == ir::RuleKind::Loss, variableShortName(model, c.var)});
        pending.erase(it);
        continue;
      }
      // Anything a robot's step writes may be what another robot then takes in or loses (its own
      // outgoing message too); what is never taken in draws nothing.
      if (rule.robot >= 0 && !takesIn && !crash) pending[c.var] = {k, rule.robot};
    }
  }

  // The steps: text on the left, a mark on the lifeline.
  const checker::KnowledgeWitness known = checker::knowledgeWitness(model, trace);
  for (std::size_t k = 0; k < steps; ++k) {
    const checker::Step& s = trace.steps[k];
    const ir::Rule& rule = model.rules[s.rule];
    const double y = rowY(k), x = laneX(rule.robot);
    const std::string robot = rule.robot >= 0 && static_cast<std::size_t>(rule.robot) < robots ? model.robots[static_cast<std::size_t>(rule.robot)] : "-";
    const std::string line = rule.origin.line > 0 ? fmt::format("  :{}", rule.origin.line) : "";
    out += fmt::format("<text class=\"step\" x=\"{:.1f}\" y=\"{:.1f}\">{}. [{}] {}{}</text>\n", kMargin, y + 4, k + 1, svgEscaped(robot),
                       svgEscaped(shortened(rule.label, 62)), line);
    out += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#eee\"/>\n", kMargin + kTextWidth - 6, y,
                       laneX(0) - 8, y);
    if (rule.kind == ir::RuleKind::Crash) {
      out += fmt::format("<path class=\"crash\" d=\"M{0:.1f},{1:.1f} L{2:.1f},{3:.1f} M{2:.1f},{1:.1f} L{0:.1f},{3:.1f}\" stroke=\"#c0392b\" "
                         "stroke-width=\"3\"/>\n",
                         x - 8, y - 8, x + 8, y + 8);
      continue;
    }
    out += fmt::format("<circle class=\"mark\" cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"4\" fill=\"{}\"/>\n", x, y,
                       rule.kind == ir::RuleKind::Loss ? "#c0392b" : "#333");
    // A mode or role that changes: a box with the new one on the robot's lifeline; so do the
    // facts a robot holds, where the trace names them.
    for (std::size_t j = 0; j < s.changes.size(); ++j) {
      const checker::Change& c = s.changes[j];
      const ir::Variable& var = model.variables[c.var];
      if (var.robot < 0) continue;
      const std::string shortName = variableShortName(model, c.var);
      std::string box;
      bool facts = false;
      if (shortName == "mode") box = checker::valueText(var, c.after);
      else if (shortName.rfind("leads.", 0) == 0 && c.after != 0) box = "leads " + shortName.substr(6, shortName.rfind('.') - 6);
      else if (shortName.rfind("leads.", 0) == 0) box = "steps down";
      else if (known.named && !var.facts.empty()) {
        for (const std::string& f : known.held[k][j]) box += (box.empty() ? "" : ", ") + f;
        if (box.empty()) box = "holds none";
        facts = true;
      }
      if (box.empty()) continue;
      const double bx = laneX(var.robot), w = std::min(kLane - 10, 7.0 * static_cast<double>(box.size()) + 10);
      // The facts held, in blue, with the whole list in the tooltip when it does not fit.
      out += fmt::format("<rect class=\"{}\" x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"16\" rx=\"3\" fill=\"{}\" "
                         "stroke=\"{}\"><title>{}</title></rect>\n<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\" font-size=\"10\">{}</text>\n",
                         facts ? "facts" : "state", bx - w / 2, y + 5, w, facts ? "#e8f0fb" : "#e8f4e8", facts ? "#2e6fb7" : "#27ae60",
                         svgEscaped(facts ? var.name + " holds " + box : box), bx, y + 17, svgEscaped(shortened(box, 16)));
    }
  }
  for (const Arrow& a : arrows) {
    const double x1 = laneX(a.from), y1 = rowY(a.fromStep), x2 = laneX(a.to), y2 = rowY(a.toStep);
    out += fmt::format("<line class=\"{}\" x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"{}\" stroke-width=\"1.3\"{} "
                       "marker-end=\"url(#{})\"><title>{}</title></line>\n",
                       a.lost ? "message lost" : "message", x1, y1, x2, y2, a.lost ? "#c0392b" : "#1f4e99",
                       a.lost ? " stroke-dasharray=\"5,3\"" : "", a.lost ? "lost" : "head", svgEscaped(a.what));
  }
  const double endY = kTop + kRow * static_cast<double>(steps) + 34;
  const std::string ending = trace.loopStart < steps ? fmt::format("then back to the state before step {}: the loop repeats for ever", trace.loopStart + 1)
                             : trace.loopStart == steps ? std::string("then the run stays in this state for ever")
                             : trace.kind == "deadlock" ? std::string("then no rule is enabled: a deadlock")
                                                        : "then " + trace.property + " does not hold";
  out += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-style=\"italic\">{}</text>\n</svg>\n", kMargin, endY, svgEscaped(ending));
  return out;
}

}  // namespace semo::cli
