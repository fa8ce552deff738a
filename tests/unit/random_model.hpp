#pragma once
// Random IR models for the tests that compare liveness searches (slicing_test.cpp,
// symbolic_liveness_test.cpp): each seed gives one model in the IR text form.
#include <cstdint>
#include <random>
#include <sstream>
#include <string>

namespace semo::test {

// How many random models a comparison goes through, and how many cases of a kind it must meet:
// all of them in a release build; a fifth under the sanitizers, which run these searches ten times
// slower and look for faults in code paths that the first models already take (the release run
// goes through every model). The counts a test expects are then a tenth: the first fifth of the
// seeds is not exactly a fifth of every kind.
#ifndef SEMO_TESTS_SANITIZED
#define SEMO_TESTS_SANITIZED 0
#endif
inline std::uint32_t randomModels(std::uint32_t all) { return SEMO_TESTS_SANITIZED ? all / 5 : all; }
inline int atLeast(int all) { return SEMO_TESTS_SANITIZED ? all / 10 : all; }

// Robots with a program counter, a mode and a flag, talking through a shared slot; steps grouped per
// program counter, some deciding sensed conditions; losses and environment steps; properties over a
// robot or two, some on a settling world.
class RandomModel {
 public:
  explicit RandomModel(std::uint32_t seed) : rng_(seed) {}

  std::string text() {
    const int robots = pick(2, 3);
    std::ostringstream out;
    out << "semo-ir 1;\nrobots";
    for (int i = 0; i < robots; ++i) out << " r" << i;
    out << ";\nvar slot : 0..2 = 0;\n";
    for (int i = 0; i < robots; ++i) {
      out << "var r" << i << ".pc : 0..2 = 0 @robot(r" << i << ");\nvar r" << i << ".mode : 0..1 = 0 @robot(r" << i
          << ");\nvar r" << i << ".flag : bool = false @robot(r" << i << ");\n";
    }
    int rule = 0;
    for (int i = 0; i < robots; ++i) {
      const std::string r = "r" + std::to_string(i);
      const int steps = pick(3, 6);
      for (int k = 0; k < steps; ++k) {
        const int from = pick(0, 2), to = pick(0, 2);
        const int fairness = pick(0, 5);  // mostly grouped per program counter
        std::string attrs = fairness == 0 ? "" : fairness == 1 ? " @fair" : fairness == 2 ? " @strongly_fair"
                                                                                          : " @fair(" + r + ".at" + std::to_string(from) + ")";
        if (pick(0, 2) == 0) attrs += " @senses(\"" + r + ".c" + std::to_string(pick(0, 1)) + "=" + std::to_string(pick(0, 1)) + "\")";
        std::string guard = r + ".pc == " + std::to_string(from);
        switch (pick(0, 3)) {
          case 0: guard += " && slot == " + std::to_string(pick(0, 2)); break;
          case 1: guard += " && " + r + ".mode == " + std::to_string(pick(0, 1)); break;
          case 2: guard += " && r" + std::to_string((i + 1) % robots) + ".flag"; break;
          default: break;
        }
        std::string update = r + ".pc' = " + std::to_string(to);
        switch (pick(0, 4)) {
          case 0: update += ", slot' = " + std::to_string(pick(0, 2)); break;
          case 1: update += ", " + r + ".mode' = slot == 2 ? 1 : " + r + ".mode"; break;
          case 2: update += ", r" + std::to_string((i + 1) % robots) + ".flag' = true"; break;
          case 3: update += ", " + r + ".flag' = !" + r + ".flag"; break;
          default: break;
        }
        out << "rule s" << rule++ << " @robot(" << r << ")" << attrs << " : " << guard << " -> " << update << ";\n";
      }
    }
    if (pick(0, 1) == 0) out << "rule lose @kind(loss) : slot != 0 -> slot' = 0;\n";
    if (pick(0, 1) == 0) out << "rule env @kind(environment) : r0.mode == 0 -> r0.mode' = 1;\n";
    auto atom = [&] {
      const std::string r = "r" + std::to_string(pick(0, robots - 1));
      switch (pick(0, 3)) {
        case 0: return "{" + r + ".pc == " + std::to_string(pick(0, 2)) + "}";
        case 1: return "{" + r + ".mode == " + std::to_string(pick(0, 1)) + "}";
        case 2: return std::string("{r0.mode == r1.mode}");
        default: return "{slot == " + std::to_string(pick(0, 2)) + "}";
      }
    };
    const char* shapes[] = {"eventually A", "always eventually A", "always (A => eventually B)", "eventually always A", "A until B"};
    for (int p = 0; p < 3; ++p) {
      std::string f = shapes[pick(0, 4)];
      for (std::size_t at = f.find('A'); at != std::string::npos; at = f.find('A')) f.replace(at, 1, atom());
      for (std::size_t at = f.find('B'); at != std::string::npos; at = f.find('B')) f.replace(at, 1, atom());
      out << "property p" << p << (pick(0, 2) == 0 ? " @settled" : "") << " : " << f << ";\n";
    }
    return out.str();
  }

 private:
  int pick(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  std::mt19937 rng_;
};

}  // namespace semo::test
