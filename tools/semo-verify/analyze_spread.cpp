// `analyze MISSION --strategy S --loss-prob P`: for each knowledge item a group service spreads by
// broadcast, how many of the runtime's gossip rounds pass until every robot working in the service
// knows a fact one of them found (checker/round_models.hpp, specs/quantitative.md).
#include <algorithm>
#include <iostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "analyze_internal.hpp"
#include "probability_chart.hpp"
#include "semo/checker/round_models.hpp"

namespace semo::cli {

namespace {

struct Finder {
  std::string robot;
  std::vector<double> within;
  double expected = 0;
};
struct Item {
  std::string name;
  std::size_t robots = 0;
  std::vector<Finder> finders;
  std::int64_t periodMillis = 0, retransmissions = 0;
  std::vector<double> within[2];  // min, max over which robot finds the fact
  double expected[2] = {0, 0};
  std::string method;
  std::size_t states = 0;
};

// The spread of one knowledge item among `members` (in the team's order), from each of them as the
// robot that finds the fact, and the least and greatest of those.
Item measure(std::string name, const std::vector<std::string>& members, const strategy::Dissemination& d, const AnalyzeOptions& options) {
  Item item{std::move(name), members.size(), {}, d.periodMillis, d.retransmissions, {}, {}, {}, 0};
  for (std::size_t first = 0; first < members.size(); ++first) {
    const checker::SpreadAnswer a = checker::analyzeSpread({members.size(), first, *options.lossProb, d.retransmissions}, options.rounds);
    item.states = std::max(item.states, a.states);
    item.method = a.expectedRounds.method;
    const double e = a.expectedRounds.infinite ? std::numeric_limits<double>::infinity() : a.expectedRounds.value;
    item.finders.push_back({members[first], a.withinRounds, e});
    if (first == 0) {
      item.within[0] = item.within[1] = a.withinRounds;
      item.expected[0] = item.expected[1] = e;
      continue;
    }
    item.expected[0] = std::min(item.expected[0], e);
    item.expected[1] = std::max(item.expected[1], e);
    for (std::size_t t = 0; t < a.withinRounds.size(); ++t) {
      item.within[0][t] = std::min(item.within[0][t], a.withinRounds[t]);
      item.within[1][t] = std::max(item.within[1][t], a.withinRounds[t]);
    }
  }
  return item;
}

}  // namespace

int analyzeSpreads(const AnalyzeOptions& options, const BuiltModel& built) {
  const model::MissionModel& mission = *built.mission;
  if (!options.lossProb) {
    std::cerr << "semo-verify: error: give --loss-prob P (the probability that one copy of a message is lost): a mission's "
                 "knowledge spread is measured in gossip rounds under that loss\n";
    return kBadInput;
  }
  std::vector<Item> items;
  try {
    for (const strategy::Service& service : mission.strategy.services) {
      if (service.kind != strategy::Service::Kind::Group || !service.dissemination || service.dissemination->via != "broadcast") continue;
      for (const model::Team& team : mission.teams) {  // the runtime gossips within a team
        std::vector<std::string> members;
        for (model::Index r : team.robots) {
          if (service.implementationFor(mission.robots[r].type) != nullptr) members.push_back(mission.robots[r].name);
        }
        if (members.size() < 2) continue;
        for (const strategy::Knowledge& k : service.knowledge) {
          items.push_back(measure(team.name + ": " + service.name + "." + k.name, members, *service.dissemination, options));
        }
      }
    }
  } catch (const checker::MarkovError& e) {
    std::cerr << "semo-verify: " << (e.limitReached ? "limit" : "error") << ": " << e.what() << "\n";
    return e.limitReached ? kLimit : kBadInput;
  }
  if (items.empty()) {
    std::cerr << "semo-verify: error: " << options.model.input
              << " has no group service that spreads knowledge by broadcast among two or more robots: nothing to measure\n";
    return kBadInput;
  }
  auto number = [](double v) { return std::isinf(v) ? std::string("infinite") : fmt::format("{:.9g}", v); };
  auto span = [&](double lo, double hi) { return lo == hi ? number(lo) : number(lo) + " .. " + number(hi); };
  if (options.json) {
    nlohmann::json out{{"schemaVersion", 1}, {"tool", std::string("semo-verify ") + kToolVersion}, {"model", options.model.input},
                       {"lossPerCopy", *options.lossProb}, {"knowledge", nlohmann::json::array()}};
    for (const Item& i : items) {
      auto value = [](double v) { return std::isinf(v) ? nlohmann::json("infinite") : nlohmann::json(v); };
      out["knowledge"].push_back({{"name", i.name}, {"robots", i.robots}, {"periodMillis", i.periodMillis},
                                  {"retransmissions", i.retransmissions}, {"states", i.states},
                                  {"expectedRounds", {{"min", value(i.expected[0])}, {"max", value(i.expected[1])}}},
                                  {"withinRounds", {{"min", i.within[0]}, {"max", i.within[1]}}}, {"method", i.method},
                                  {"byFinder", nlohmann::json::array()}});
      for (const Finder& f : i.finders) {
        out["knowledge"].back()["byFinder"].push_back({{"robot", f.robot}, {"expectedRounds", value(f.expected)}, {"withinRounds", f.within}});
      }
    }
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << "model:       " << options.model.input << "\n";
    std::cout << fmt::format("assumes:     each copy of a message lost with probability {:g}; no crash; every robot in the service\n", *options.lossProb);
    for (const Item& i : items) {
      std::cout << fmt::format("knowledge {}: {} robots, a gossip round every {} ms, {} extra cop{} per message ({} states)\n", i.name,
                               i.robots, i.periodMillis, i.retransmissions, i.retransmissions == 1 ? "y" : "ies", i.states);
      std::cout << "  rounds until every robot knows a fact one of them found (min .. max over which robot finds it):\n";
      std::cout << "  expected:       " << span(i.expected[0], i.expected[1]) << " rounds (" << i.method << ")\n";
      std::cout << "  P(within t rounds):";
      for (std::size_t t = 1; t < i.within[0].size(); ++t) {
        if (t > 1 && (t - 1) % 4 == 0) std::cout << "\n                     ";
        const std::string lo = fmt::format("{:.6f}", i.within[0][t]), hi = fmt::format("{:.6f}", i.within[1][t]);
        std::cout << fmt::format("  {:>3}: {}", t, lo == hi ? hi : lo + ".." + hi);
      }
      std::cout << "\n";
    }
  }
  if (options.svg) {
    std::vector<ChartSeries> series;
    for (const Item& i : items) {
      series.push_back({i.name + " (min)", i.within[0], true});
      series.push_back({i.name + " (max)", i.within[1], false});
    }
    const std::string title = fmt::format("P(every robot knows within t rounds), loss {:g} - {}", *options.lossProb, options.model.input);
    if (!writeAtomically(*options.svg, probabilityChartSvg(series, title, "t (gossip rounds)"))) {
      std::cerr << "semo-verify: error: cannot write '" << *options.svg << "'\n";
      return kBadInput;
    }
  }
  return kOk;
}

}  // namespace semo::cli
