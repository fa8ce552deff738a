// `analyze MISSION --strategy S --loss-prob P`: for each knowledge item a group service spreads by
// broadcast, how many of the runtime's gossip rounds pass until every robot working in the service
// knows a fact one of them found; for each leader block that detects failures, how likely its
// heartbeats are lost in longer runs than the model assumes, or long enough for a false takeover
// (checker/round_models.hpp, specs/quantitative.md).
#include <algorithm>
#include <chrono>
#include <iostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "analyze_internal.hpp"
#include "probability_chart.hpp"
#include "semo/checker/round_models.hpp"

namespace semo::cli {

std::string number(double v) { return std::isinf(v) ? std::string("infinite") : fmt::format("{:.9g}", v); }

namespace {
// 3.2e-7: two significant digits, the exponent without its padding.
std::string small(double v) {
  const int exponent = static_cast<int>(std::floor(std::log10(v)));
  double mantissa = v / std::pow(10.0, exponent);
  std::string digits = fmt::format("{:.1f}", mantissa);
  if (digits == "10.0") return fmt::format("1.0e{}", exponent + 1);
  return digits + "e" + std::to_string(exponent);
}
}  // namespace

std::string probabilityText(double p) {
  constexpr double kExact = 1e-12;  // below the half-unit of the sixth decimal and above rounding
  if (p >= 1 - kExact) return "1";
  if (p <= kExact) return "0";
  if (p > 0.9995) return "1 - " + small(1 - p);
  if (p < 0.0005) return small(p);
  return fmt::format("{:.6f}", p);
}

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
  // Estimated from simulated runs (the round model outgrew --max-states): every P(within t) within
  // `band`, each finder's mean within `meanHalfWidth`, at 95 %.
  bool sampled = false;
  double band = 0, meanHalfWidth = 0;
};

// The spread of one knowledge item among `members` (in the team's order), from each of them as the
// robot that finds the fact, and the least and greatest of those.
// The round model keeps a bit per robot (the runtime's round depends on the robots' order), so its
// states grow as 2^n: a large swarm can take seconds per finder, which the progress lines say.
Item measure(std::string name, const std::vector<std::string>& members, const strategy::Dissemination& d, const AnalyzeOptions& options) {
  Item item{std::move(name), members.size(), {}, d.periodMillis, d.retransmissions, {}, {}, {}, 0};
  const auto started = std::chrono::steady_clock::now();
  for (std::size_t first = 0; first < members.size(); ++first) {
    if (std::chrono::steady_clock::now() - started > std::chrono::seconds(1)) {
      std::cerr << fmt::format("analyze: {}: from {} ({} of {})\n", item.name, members[first], first + 1, members.size());
    }
    const checker::SpreadParameters parameters{members.size(), first, *options.lossProb, d.retransmissions};
    checker::SpreadAnswer a;
    try {
      if (!item.sampled) a = checker::analyzeSpread(parameters, options.rounds, {.maxStates = options.maxStates});
    } catch (const checker::MarkovError& e) {
      if (!e.tooManyStates || options.runs == 0) {
        throw checker::MarkovError(fmt::format("knowledge {} ({} robots): {}{}", item.name, members.size(), e.what(),
                                               e.tooManyStates ? "; --max-states raises the limit" : ""),
                                   e.limitReached);
      }
      item.sampled = true;  // and for the other finders too: one method per item
      std::cerr << fmt::format("analyze: {}: the round model has more than {} states; estimating from {} simulated runs per finder\n",
                               item.name, options.maxStates, options.runs);
    }
    if (item.sampled) {
      const checker::SampledAnswer s = checker::sampleSpread(parameters, {.runs = options.runs, .seed = options.seed, .horizon = options.rounds});
      a.withinRounds = s.within;
      a.expectedRounds.value = s.unfinished == 0 ? s.meanUnits : std::numeric_limits<double>::infinity();
      a.expectedRounds.infinite = s.unfinished != 0;
      a.expectedRounds.method = s.method;
      item.band = s.band;
      item.meanHalfWidth = std::max(item.meanHalfWidth, s.meanHalfWidth);
    }
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

// A leader block's heartbeats on one link to a waiting candidate.
struct Heartbeats {
  std::string block;
  std::int64_t heartbeatMillis = 0;
  std::size_t takeoverAfter = 0, burst = 0, horizon = 0;  // periods
  checker::LossRunAnswer outside, takeover;
};

void printHeartbeats(const Heartbeats& h, double loss) {
  std::cout << fmt::format("leader block {}: heartbeat every {} ms, takeover after {} silent period{}, assumed burst <= {}\n", h.block,
                           h.heartbeatMillis, h.takeoverAfter, h.takeoverAfter == 1 ? "" : "s", h.burst);
  std::cout << fmt::format("  one waiting candidate's link, heartbeats lost with probability {:g}, within {} periods ({:g} s):\n", loss,
                           h.horizon, static_cast<double>(h.horizon * static_cast<std::size_t>(h.heartbeatMillis)) / 1000.0);
  auto line = [&](const char* what, std::size_t run, const checker::LossRunAnswer& a) {
    const double e = a.expectedPeriods.infinite ? std::numeric_limits<double>::infinity() : a.expectedPeriods.value;
    std::cout << fmt::format("  {:<44} P = {}; expected after {} periods ({} s)\n", fmt::format(fmt::runtime(what), run), probabilityText(a.withinPeriods.back()),
                             number(e), number(e * static_cast<double>(h.heartbeatMillis) / 1000.0));
  };
  line("{} lost in a row (outside the assumption):", h.burst + 1, h.outside);
  line("{} lost in a row (a takeover, the leader alive):", h.takeoverAfter, h.takeover);
  // Re-election after a crash involves no chance: a crashed leader sends nothing to lose, so every
  // waiting candidate's silence grows each period, and leaders hear each other without loss.
  std::cout << fmt::format("  the leader crashed: a candidate waiting in the block all along takes over within {} periods ({} ms),\n"
                           "    with probability 1 whatever the loss (a crashed leader sends nothing to lose); one whose `others`\n"
                           "    arm has ended takes over when the block forms again (`simulate --crash` measures that)\n",
                           h.takeoverAfter, h.takeoverAfter * static_cast<std::size_t>(h.heartbeatMillis));
}

}  // namespace

int analyzeMission(const AnalyzeOptions& given, const BuiltModel& built) {
  const model::MissionModel& mission = *built.mission;
  // --loss-prob, else the verify block's `assume loss probability P`.
  AnalyzeOptions options = given;
  if (!options.lossProb) options.lossProb = mission.assumptions.lossProbability;
  if (!options.lossProb) {
    std::cerr << errorPrefix() << "give --loss-prob P or `assume loss probability P` in the verify block (the probability that "
                 "one copy of a message is lost): a mission's knowledge spread and its heartbeats are measured under that loss\n";
    return kBadInput;
  }
  const char* source = given.lossProb ? "--loss-prob" : "assume loss probability";
  std::vector<Item> items;
  std::vector<Heartbeats> heartbeats;
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
    for (const model::GroupBlock& b : mission.groupBlocks) {
      if (!b.isLeaderBlock || !b.leader.detectsFailures) continue;
      Heartbeats h;
      h.block = mission.services.at(b.service).name;
      h.heartbeatMillis = std::max<std::int64_t>(1, b.leader.heartbeatMillis);
      h.takeoverAfter = static_cast<std::size_t>(std::max<std::int64_t>(1, b.leader.timeoutMillis / h.heartbeatMillis));  // as the translation
      h.burst = static_cast<std::size_t>(std::max<std::int64_t>(0, mission.assumptions.lossBurst));
      h.horizon = static_cast<std::size_t>(options.seconds * 1000.0 / static_cast<double>(h.heartbeatMillis));
      h.outside = checker::analyzeLossRun(h.burst + 1, *options.lossProb, h.horizon);
      h.takeover = checker::analyzeLossRun(h.takeoverAfter, *options.lossProb, h.horizon);
      heartbeats.push_back(std::move(h));
    }
  } catch (const checker::MarkovError& e) {
    std::cerr << programName() << ": " << (e.limitReached ? "limit" : "error") << ": " << e.what() << "\n";
    return e.limitReached ? kLimit : kBadInput;
  }
  if (items.empty() && heartbeats.empty()) {
    std::cerr << errorPrefix() << options.model.input
              << " has neither a group service that spreads knowledge by broadcast among two or more robots nor a leader block that "
                 "detects failures: nothing to measure\n";
    return kBadInput;
  }
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
      if (i.sampled) {
        out["knowledge"].back()["statistical"] = {{"runsPerFinder", options.runs}, {"seed", options.seed}, {"confidence", 0.95},
                                                  {"withinBand", i.band}, {"expectedHalfWidth", i.meanHalfWidth}};
      }
      for (const Finder& f : i.finders) {
        out["knowledge"].back()["byFinder"].push_back({{"robot", f.robot}, {"expectedRounds", value(f.expected)}, {"withinRounds", f.within}});
      }
    }
    out["leaderBlocks"] = nlohmann::json::array();
    for (const Heartbeats& h : heartbeats) {
      auto run = [](std::size_t length, const checker::LossRunAnswer& a) {
        return nlohmann::json{{"inARow", length},
                              {"withinHorizon", a.withinPeriods.back()},
                              {"expectedPeriods", a.expectedPeriods.infinite ? nlohmann::json("infinite") : nlohmann::json(a.expectedPeriods.value)}};
      };
      out["leaderBlocks"].push_back({{"block", h.block},
                                     {"heartbeatMillis", h.heartbeatMillis},
                                     {"horizonPeriods", h.horizon},
                                     {"outsideAssumption", run(h.burst + 1, h.outside)},
                                     {"falseTakeover", run(h.takeoverAfter, h.takeover)},
                                     {"reelectionAfterCrash", {{"withinPeriods", h.takeoverAfter},
                                                               {"withinMillis", h.takeoverAfter * static_cast<std::size_t>(h.heartbeatMillis)},
                                                               {"probability", 1.0}}}});
    }
    std::cout << out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  } else {
    std::cout << "model:       " << options.model.input << "\n";
    std::cout << fmt::format("assumes:     each copy of a message lost with probability {:g} ({}), independently; no crash\n"
                             "             (the figures are for the robots that work: `check` proves that the knowledge converges\n"
                             "             under the verify block's crashes too, without saying how soon)\n",
                             *options.lossProb, source);
    for (const Item& i : items) {
      std::cout << fmt::format("knowledge {}: {} robots, a gossip round every {} ms, {} extra cop{} per message ({})\n", i.name, i.robots,
                               i.periodMillis, i.retransmissions, i.retransmissions == 1 ? "y" : "ies",
                               i.sampled ? fmt::format("ESTIMATED from {} simulated runs per finder", options.runs)
                                         : fmt::format("{} states", i.states));
      std::cout << "  rounds until every robot in the service knows a fact one of them found (min .. max over the finder):\n";
      std::cout << "  expected:       " << span(i.expected[0], i.expected[1]) << " rounds"
                << (i.sampled ? fmt::format(" +-{:.3g}", i.meanHalfWidth) : std::string()) << " (" << i.method << ")\n";
      const std::string header = i.sampled ? fmt::format("  P(within t rounds), each +-{:.4f}:", i.band) : std::string("  P(within t rounds):");
      std::cout << header;
      for (std::size_t t = 1; t < i.within[0].size(); ++t) {
        if (t > 1 && (t - 1) % 4 == 0) std::cout << "\n" << std::string(header.size(), ' ');
        const std::string lo = i.sampled ? fmt::format("{:.6f}", i.within[0][t]) : probabilityText(i.within[0][t]);
        const std::string hi = i.sampled ? fmt::format("{:.6f}", i.within[1][t]) : probabilityText(i.within[1][t]);
        std::cout << fmt::format("  {:>3}: {}", t, lo == hi ? hi : lo + (lo.find(' ') != std::string::npos || hi.find(' ') != std::string::npos ? " .. " : "..") + hi);
      }
      std::cout << "\n";
    }
    for (const Heartbeats& h : heartbeats) printHeartbeats(h, *options.lossProb);
  }
  if (options.svg && !items.empty()) {
    std::vector<ChartSeries> series;
    for (const Item& i : items) {
      const std::string estimated = i.sampled ? fmt::format(", estimated +-{:.3f}", i.band) : "";
      series.push_back({i.name + " (min" + estimated + ")", i.within[0], true});
      series.push_back({i.name + " (max" + estimated + ")", i.within[1], false});
    }
    const std::string title = fmt::format("P(every robot knows within t rounds), loss {:g} - {}", *options.lossProb, options.model.input);
    if (!writeAtomically(*options.svg, probabilityChartSvg(series, title, "t (gossip rounds)"))) {
      std::cerr << errorPrefix() << "cannot write '" << *options.svg << "'\n";
      return kBadInput;
    }
  }
  return kOk;
}

}  // namespace semo::cli
