// Engines never disagree: every example, seeded defect (and twin) and hand-written IR model is
// checked by every engine that applies (explicit with and without symmetry and slicing, slices
// searched symbolically, smt, auto, counting),
// through the real CLI's JSON, and a property two engines both decide gets the same verdict from
// both. Group formation for every crash set (smt) must agree with the explicit engine's invariants
// of the same block. And every property is decided by some engine, but for the documented cases.
#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>

#include "cli_run.hpp"

namespace semo::e2e {
namespace {

struct Input {
  std::string name;
  std::string args;  // the model: a mission with its strategy, or an .ir file
  bool mission = true;
  // The explicit engines' --max-states. Patrol's safety state space is beyond a million states, so
  // its bounded searches end unknown either way: at 200,000 they decide the same properties but
  // one (a violation the other searches find too) in 35 s instead of 118 (measured 2026-11-29).
  // Deployment keeps the million: there its search without symmetry proves what the quotient does.
  // The swarm of ten takes 200,000 too: without symmetry its state space is far beyond a million
  // either way, and each bound decides the same properties (the searches without symmetry, and smt's
  // slices, 100 s at a million against 76 s, measured 2026-12-03).
  std::size_t maxStates = 1'000'000;
  // More options for the smt engine's run. The swarm of ten: BMC to depth 3 rather than 5 (depth 5
  // alone took 19 s; induction goes to k = 3 either way), and no LTL properties, whose search there
  // is the one of "slicing only" over again (slices without symmetry, 28 s), as smt's slices are
  // searched on every other input (measured 2026-12-03: the run 54 s -> 4 s, the same verdicts on
  // the safety properties and group formation).
  std::string smtOptions;
};
// GoogleTest prints a parameter without PrintTo as its bytes, pointers included: ctest's names
// (gtest_discover_tests) then changed from build to build, and its measured times were lost.
void PrintTo(const Input& in, std::ostream* os) { *os << in.name; }

std::vector<Input> inputs() {
  std::vector<Input> out;
  auto add = [&out](std::string name, std::string args, bool mission = true) {
    Input in;
    in.name = std::move(name);
    in.args = std::move(args);
    in.mission = mission;
    out.push_back(std::move(in));
  };
  for (const char* e : {"chase/chase", "deployment/deployment", "swarm/swarm3", "swarm/swarm10", "patrol/patrol"}) {
    const std::string path = e;
    const std::string folder = path.substr(0, path.find('/'));
    const std::string name = path.substr(path.find('/') + 1);
    out.push_back({"example_" + name, "specs/examples/" + path + ".semo --strategy specs/examples/" + folder + "/strategy.xml", true,
                   name == "patrol" || name == "swarm10" ? 200'000u : 1'000'000u, name == "swarm10" ? " --max-depth 3 --safety-only" : ""});
  }
  for (const auto& entry : fs::directory_iterator(SEMO_SOURCE_DIR "/specs/defects")) {
    if (entry.path().extension() != ".semo") continue;
    const std::string stem = entry.path().stem().string();
    add("defect_" + stem, "specs/defects/" + stem + ".semo --strategy specs/defects/strategy.xml");
  }
  add("defect_leader_timeout_short", "specs/defects/leader_timeout.semo --strategy specs/defects/leader_timeout_short.xml");
  add("defect_leader_timeout_ok", "specs/defects/leader_timeout.semo --strategy specs/defects/leader_timeout_ok.xml");
  for (const auto& entry : fs::directory_iterator(SEMO_SOURCE_DIR "/specs/defects/liveness")) {
    if (entry.path().extension() != ".semo") continue;
    const std::string stem = entry.path().stem().string();
    add("liveness_" + stem, "specs/defects/liveness/" + stem + ".semo --strategy specs/defects/liveness/strategy.xml");
  }
  add("liveness_jammed_recall_reliable", "specs/defects/liveness/jammed_recall.semo --strategy specs/defects/liveness/jammed_recall_reliable.xml");
  add("liveness_stuck_gossip_reliable", "specs/defects/liveness/stuck_gossip.semo --strategy specs/defects/liveness/stuck_gossip_reliable.xml");
  add("liveness_orphaned_relay_formation", "specs/defects/liveness/orphaned_relay.semo --strategy specs/defects/liveness/orphaned_relay_formation.xml");
  add("liveness_handed_watch_release", "specs/defects/liveness/handed_watch.semo --strategy specs/defects/liveness/handed_watch_release.xml");
  add("liveness_handed_watch_keep", "specs/defects/liveness/handed_watch.semo --strategy specs/defects/liveness/handed_watch_keep.xml");
  add("liveness_orphaned_relay_timeout", "specs/defects/liveness/orphaned_relay.semo --strategy specs/defects/liveness/orphaned_relay_timeout.xml");
  for (const auto& entry : fs::directory_iterator(SEMO_SOURCE_DIR "/tests/e2e/ir")) {
    if (entry.path().extension() != ".ir") continue;
    add("ir_" + entry.path().stem().string(), "tests/e2e/ir/" + entry.path().filename().string(), false);
  }
  std::sort(out.begin(), out.end(), [](const Input& a, const Input& b) { return a.name < b.name; });
  return out;
}

// The engines, as `check` options ({states}: the input's maxStates). The explicit searches are
// bounded, so that a model beyond them gives "unknown" rather than a long wait; a bound never makes
// a verdict wrong. `auto` runs as a user runs it, with its default budgets: it must decide what the
// bounded ones leave open (patrol's knowledge convergence needs a slice of 4.5 million states,
// searched symbolically).
const std::vector<std::pair<std::string, std::string>> kEngines = {
    {"explicit", "--max-states {states}"},
    {"explicit, no symmetry, no slicing", "--max-states {states} --no-symmetry --no-slicing"},
    {"explicit, symmetry only", "--max-states {states} --no-slicing"},
    {"explicit, slicing only", "--max-states {states} --no-symmetry"},
    {"smt", "--engine smt --max-states {states}"},
    {"auto", "--engine auto"},
    // Every slice too large for one state: each is searched symbolically (decision diagrams).
    {"symbolic slices", "--max-states {states} --slice-states 1"},
    // The counter abstraction: decides on a team with counts (swarm10), nothing elsewhere.
    {"counting", "--engine counting"},
};

struct Verdicts {
  std::map<std::string, std::string> properties;  // name -> "proven" | "VIOLATED" | "unknown"
  std::map<std::string, std::string> blocks;      // smt: group formation per block (service name)
};

Verdicts run(const Input& in, const std::string& options, const fs::path& dir) {
  CliRun r = verify("check " + in.args + " " + options + " --json", dir);
  Verdicts v;
  EXPECT_TRUE(r.exit == 0 || r.exit == 1 || r.exit == 3) << r.exit << r.err;
  nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
  if (j.is_discarded()) {
    ADD_FAILURE() << "not JSON: " << r.out.substr(0, 400) << r.err;
    return v;
  }
  for (const auto& p : j["properties"]) v.properties[p["name"].get<std::string>()] = p["verdict"].get<std::string>();
  if (j.contains("groupFormation")) {
    for (const auto& b : j["groupFormation"]) {
      const std::string block = b["block"].get<std::string>();
      v.blocks[block.substr(0, block.find(" ("))] = b["verdict"].get<std::string>();
    }
  }
  return v;
}

bool decided(const std::string& verdict) { return verdict == "proven" || verdict == "VIOLATED"; }

class EnginesAgree : public ::testing::TestWithParam<Input> {};

TEST_P(EnginesAgree, OnEveryVerdictBothDecide) {
  const Input& in = GetParam();
  const fs::path dir = workDir("engines_" + in.name);
  std::vector<Verdicts> all;
  for (const auto& [name, options] : kEngines) {
    std::string withStates = options;
    if (const std::size_t at = withStates.find("{states}"); at != std::string::npos) withStates.replace(at, 8, std::to_string(in.maxStates));
    if (name == "smt") withStates += in.smtOptions;
    all.push_back(run(in, withStates, dir));
  }
  std::map<std::string, std::pair<std::string, std::string>> first;  // property -> (engine, verdict)
  for (std::size_t e = 0; e < kEngines.size(); ++e) {
    for (const auto& [property, verdict] : all[e].properties) {
      if (!decided(verdict)) continue;
      auto [it, added] = first.try_emplace(property, kEngines[e].first, verdict);
      EXPECT_EQ(verdict, it->second.second) << property << ": " << kEngines[e].first << " says " << verdict << ", " << it->second.first
                                            << " says " << it->second.second;
    }
  }
  // Group formation per block (smt, every crash set) against the explicit engine's invariants of the
  // block's arms: violated exactly when one of them is.
  for (const auto& [block, verdict] : all[4].blocks) {
    bool anyViolated = false, allProven = true, anyInvariant = false;
    for (const auto& [property, v] : all[0].properties) {
      if (property.rfind("group_formation[" + block + " ", 0) != 0) continue;
      anyInvariant = true;
      anyViolated = anyViolated || v == "VIOLATED";
      allProven = allProven && v == "proven";
    }
    if (!anyInvariant || (!anyViolated && !allProven)) continue;
    EXPECT_EQ(verdict, anyViolated ? "VIOLATED" : "proven") << "block " << block;
  }
  // The seeded liveness defects (and their twins) are small: every engine, with every reduction on
  // or off, decides each of their LTL properties, so that a defect is still found with each
  // reduction (and, by the agreement above, found the same).
  if (in.name.rfind("liveness_", 0) == 0) {
    for (std::size_t e = 0; e < kEngines.size(); ++e) {
      if (kEngines[e].first == "counting") continue;  // none of them has a team with counts
      for (const auto& [property, verdict] : all[e].properties) {
        EXPECT_TRUE(decided(verdict)) << property << ": " << kEngines[e].first << " says " << verdict;
      }
    }
  }
  // Every property decided by some engine (scouting, which no engine decides whole, is not here).
  for (const auto& [property, verdict] : all[0].properties) {
    EXPECT_TRUE(first.count(property) != 0) << property << " decided by no engine";
  }
}

INSTANTIATE_TEST_SUITE_P(Models, EnginesAgree, ::testing::ValuesIn(inputs()),
                         [](const ::testing::TestParamInfo<Input>& info) { return info.param.name; });

}  // namespace
}  // namespace semo::e2e
