// Benchmark (not a test): group formation for every crash set (checker/group_formation.hpp) on a
// team of 200 robots of 5 types, crash <= 10, one block with 5, 10 or 20 arms whose candidate
// sets overlap (arm a wants type a % 5, and from a = 5 on also type (a + 1) % 5); then the same
// blocks where each group runs a group service with min-robots = 10 (20 such groups need all 200
// robots, so there one crash breaks the block). Prints the
// budget tolerated, the size of the smallest breaking crash set and the time. Build against a
// release build (paths from the project's top folder):
//   g++ -std=c++20 -O2 -I checker/include -I semantics/include -I frontend/include \
//       bench/group_formation_bench.cpp build/checker/libsemo_checker.a \
//       build/semantics/libsemo_semantics.a build/frontend/libsemo_frontend.a -lz3 -ltinyxml2 -lpthread
#include <chrono>
#include <iostream>
#include "semo/checker/group_formation.hpp"
using namespace semo;
int main() {
  for (int minimum : {1, 10})
  for (int arms : {5, 10, 20}) {
    model::MissionModel m;
    m.teams.push_back({});
    m.teams[0].name = "T";
    m.services.push_back({});
    m.services[0].name = "S";
    m.assumptions.crashBudget = {10};
    strategy::Service work;
    work.name = "work";
    work.kind = strategy::Service::Kind::Group;
    work.minRobots = minimum;
    m.strategy.services.push_back(work);
    for (int r = 0; r < 200; ++r) {
      m.robots.push_back({"r" + std::to_string(r), 0, "type" + std::to_string(r % 5), static_cast<model::Index>(r), {}});
      m.teams[0].robots.push_back(r);
    }
    model::GroupBlock block;
    block.team = 0;
    block.service = 0;
    for (int a = 0; a < arms; ++a) {
      model::GroupArm arm;
      arm.names = {"type" + std::to_string(a % 5)};
      arm.body.emplace_back();
      arm.body.back().kind = model::Stmt::Kind::CallGroupService;
      arm.body.back().service = "work";
      // arm a wants type a%5, and (for a >= 5) also type (a+1)%5: overlapping candidate sets
      for (int r = 0; r < 200; ++r) {
        if (r % 5 == a % 5 || (a >= 5 && r % 5 == (a + 1) % 5)) arm.candidates.push_back(r);
      }
      block.arms.push_back(std::move(arm));
    }
    m.groupBlocks.push_back(std::move(block));
    auto t0 = std::chrono::steady_clock::now();
    auto v = checker::checkGroupFormation(m);
    double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::cout << arms << " groups of at least " << minimum << ": tolerated " << v[0].tolerated << " budget " << v[0].budget << " breaking " << v[0].breakingSet.size() << " in " << s << " s\n";
  }
}
