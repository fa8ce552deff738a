// `analyze`: how likely and how soon each `eventually {p}` property of a model is met, on the IR
// read as a Markov decision process (checker/markov.hpp, specs/quantitative.md).
#include <fnmatch.h>

#include <cmath>

#include <iostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "analyze_internal.hpp"
#include "probability_chart.hpp"
#include "progress_line.hpp"
#include "semo/checker/markov.hpp"
#include "semo/checker/statistical.hpp"
#include "semo/semantics/ir_text.hpp"

namespace semo::cli {
namespace {

using checker::Optimum;

struct Answer {
  std::string name, target;
  checker::QuantitativeResult eventually[2], expected[2];  // [min, max]
  std::vector<double> within[2];
};

std::string range(const checker::QuantitativeResult (&r)[2], bool chain) {
  if (chain || r[0].value == r[1].value) return number(r[0].value);
  return "min " + number(r[0].value) + ", max " + number(r[1].value);
}

// The methods of the minimum and the maximum, once when they are the same.
std::string methods(const checker::QuantitativeResult (&r)[2], bool chain) {
  if (chain || r[0].method == r[1].method) return r[0].method;
  return "min: " + r[0].method + "; max: " + r[1].method;
}

nlohmann::json resultJson(const checker::QuantitativeResult (&r)[2]) {
  auto one = [](double v) { return std::isinf(v) ? nlohmann::json("infinite") : nlohmann::json(v); };
  // The bounds the true value is known to lie within (equal to the value when it is exact).
  return {{"min", one(r[0].value)},
          {"max", one(r[1].value)},
          {"bounds", {{"min", {one(r[0].lower), one(r[0].upper)}}, {"max", {one(r[1].lower), one(r[1].upper)}}}},
          {"method", r[0].method},
          {"methods", {{"min", r[0].method}, {"max", r[1].method}}}};
}

// The model's reachable states outgrew --max-states: each property estimated from simulated runs of
// the IR (statistical.hpp), printed as an estimate with its bands, never as the exact figures.
int analyzeBySampling(const AnalyzeOptions& options, const ir::Model& model, const std::vector<std::size_t>& asked,
                      const std::vector<double>& reward, const std::string& counting) {
  const std::string& input = options.model.input;
  std::cerr << fmt::format("analyze: more than {} reachable states; estimating from {} simulated runs\n", options.maxStates, options.runs);
  std::vector<char> unit(model.rules.size());
  for (std::size_t r = 0; r < model.rules.size(); ++r) unit[r] = reward[r] > 0 ? 1 : 0;
  nlohmann::json out{{"schemaVersion", 1}, {"tool", std::string("semo-verify ") + kToolVersion}, {"model", input}, {"reward", counting},
                     {"statistical", {{"runs", options.runs}, {"seed", options.seed}, {"confidence", 0.95}}}, {"properties", nlohmann::json::array()}};
  if (!options.json) {
    std::cout << "model:       " << input << " (" << model.variables.size() << " variables, " << model.rules.size() << " rules)\n";
    std::cout << "markov:      more than " << options.maxStates << " reachable states: ESTIMATED from " << options.runs << " simulated runs\n";
    std::cout << "counting:    " << counting << "\n";
  }
  std::vector<ChartSeries> series;
  for (std::size_t p : asked) {
    const ir::Property& property = model.properties[p];
    checker::SamplingOptions sampling{.runs = options.runs, .seed = options.seed, .horizon = options.rounds, .withinSteps = true};
    sampling.progress = [&](std::size_t done) { std::cerr << fmt::format("analyze: {}: {} of {} runs\n", property.name, done, options.runs); };
    const checker::SampledAnswer a = checker::sampleRuns(model, property.formula.args[0].atom, unit, sampling);
    const std::string target = ir::toText(model, property.formula.args[0].atom);
    const nlohmann::json mean = a.unfinished == 0 ? nlohmann::json(a.meanUnits) : nlohmann::json("not estimated");
    out["properties"].push_back({{"name", property.name}, {"target", target}, {"within", a.within}, {"withinBand", a.band},
                                 {"expected", mean}, {"expectedHalfWidth", a.meanHalfWidth}, {"unfinishedRuns", a.unfinished},
                                 {"schedulerDrawn", a.scheduled}, {"method", a.method}});
    series.push_back({property.name + fmt::format(" (estimated +-{:.3f})", a.band), a.within, false});
    if (options.json) continue;
    std::cout << "property " << property.name << ": eventually {" << target << "}\n";
    std::cout << "  estimate:       " << a.method << "\n";
    std::cout << "  expected:       "
              << (a.unfinished == 0 ? fmt::format("{:.6g} +-{:.3g}", a.meanUnits, a.meanHalfWidth)
                                    : fmt::format("not estimated ({} runs short of the target)", a.unfinished))
              << "\n";
    const std::string header = fmt::format("  P(within t steps), each +-{:.4f}:", a.band);
    std::cout << header;
    for (std::size_t t = 1; t <= options.rounds; ++t) {
      if (t > 1 && (t - 1) % 5 == 0) std::cout << "\n" << std::string(header.size(), ' ');
      std::cout << fmt::format("  {:>3}: {:.6f}", t, a.within[t]);
    }
    std::cout << "\n";
  }
  if (options.json) std::cout << out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  if (options.svg && !writeAtomically(*options.svg, probabilityChartSvg(series, "P(reached within t steps), estimated - " + input,
                                                                       "t (steps of the model)"))) {
    std::cerr << errorPrefix() << "cannot write '" << *options.svg << "'\n";
    return kBadInput;
  }
  return kOk;
}

}  // namespace

int runAnalyze(const AnalyzeOptions& options) {
  std::unique_ptr<BuiltModel> built;
  {
    ProgressLine line(true);  // a large mission's translation; the analyses say their own progress
    built = buildModel(options.model, &line);
  }
  if (!built) return kBadInput;
  if (built->mission) {
    std::vector<Output> outputs;
    if (options.svg) outputs.push_back({"--svg", *options.svg});
    std::vector<std::string> inputs = filesRead(built->sources);
    inputs.insert(inputs.end(), {options.model.input, options.model.strategy.value_or(""), options.model.robotsDir.value_or("")});
    if (!outputsSpareInputs(outputs, inputs)) return kBadInput;
    return analyzeMission(options, *built);
  }
  if (options.lossProb) {
    std::cerr << errorPrefix() << "--loss-prob applies to a mission; an IR model states its probabilities in its rules\n";
    return kBadInput;
  }
  const ir::Model& model = *built->model;
  const std::string& input = options.model.input;
  std::vector<std::size_t> asked;
  for (std::size_t p = 0; p < model.properties.size(); ++p) {
    const ir::Ltl& f = model.properties[p].formula;
    if (f.kind == ir::Ltl::Kind::Eventually && f.args.size() == 1 && f.args[0].kind == ir::Ltl::Kind::Atom) asked.push_back(p);
  }
  if (asked.empty()) {
    std::cerr << errorPrefix() << input << " has no property of the form `eventually {p}`: nothing to measure\n";
    return kBadInput;
  }
  std::vector<double> reward(model.rules.size(), 1.0);
  std::string counting = "steps of every rule";
  if (options.reward) {
    std::size_t matched = 0;
    for (std::size_t r = 0; r < model.rules.size(); ++r) {
      reward[r] = fnmatch(options.reward->c_str(), model.rules[r].name.c_str(), 0) == 0 ? 1.0 : 0.0;
      matched += reward[r] > 0 ? 1 : 0;
    }
    if (matched == 0) {
      std::cerr << errorPrefix() << "--reward '" << *options.reward << "' names no rule of " << input << "\n";
      return kBadInput;
    }
    counting = fmt::format("steps of the {} rule{} matching '{}'", matched, matched == 1 ? "" : "s", *options.reward);
  }
  std::vector<Output> outputs;
  if (options.svg) outputs.push_back({"--svg", *options.svg});
  std::vector<std::string> inputs = filesRead(built->sources);
  inputs.insert(inputs.end(), {input, options.model.strategy.value_or(""), options.model.robotsDir.value_or("")});
  if (!outputsSpareInputs(outputs, inputs)) return kBadInput;

  checker::MarkovModel chain;
  try {
    chain = checker::buildMarkovModel(model, {.maxStates = options.maxStates});
  } catch (const checker::MarkovError& e) {
    if (e.tooManyStates && options.runs > 0) {
      try {
        return analyzeBySampling(options, model, asked, reward, counting);
      } catch (const checker::MarkovError& inner) {
        std::cerr << errorPrefix() << inner.what() << "\n";
        return kBadInput;
      }
    }
    std::cerr << programName() << ": " << (e.limitReached ? "limit" : "error") << ": " << e.what() << "\n";
    return e.limitReached ? kLimit : kBadInput;
  }
  const bool deterministic = chain.deterministic();
  std::vector<Answer> answers;
  try {
    for (std::size_t p : asked) {
      Answer a;
      a.name = model.properties[p].name;
      a.target = ir::toText(model, model.properties[p].formula.args[0].atom);
      const std::vector<char> target = checker::statesWhere(chain, model.properties[p].formula.args[0].atom);
      for (int k = 0; k < 2; ++k) {
        const Optimum o = k == 0 ? Optimum::Min : Optimum::Max;
        a.eventually[k] = checker::reachability(chain, target, o);
        a.expected[k] = checker::expectedReward(chain, target, reward, o);
        a.within[k] = checker::boundedReachability(chain, target, options.rounds, o);
      }
      answers.push_back(std::move(a));
    }
  } catch (const checker::MarkovError& e) {
    std::cerr << programName() << ": " << (e.limitReached ? "limit" : "error") << ": " << e.what() << "\n";
    return e.limitReached ? kLimit : kBadInput;
  }

  const std::string kind = deterministic ? "a Markov chain (one rule enabled at most)" : "a Markov decision process: min and max over schedules";
  if (options.json) {
    nlohmann::json out{{"schemaVersion", 1},          {"tool", std::string("semo-verify ") + kToolVersion},
                       {"model", input},              {"states", chain.size()},
                       {"actions", chain.actions()}, {"deterministic", deterministic},
                       {"reward", counting},          {"properties", nlohmann::json::array()}};
    for (const Answer& a : answers) {
      out["properties"].push_back({{"name", a.name},
                                   {"target", a.target},
                                   {"eventually", resultJson(a.eventually)},
                                   {"expected", resultJson(a.expected)},
                                   {"within", {{"min", a.within[0]}, {"max", a.within[1]}}}});
    }
    std::cout << out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  } else {
    std::cout << "model:       " << input << " (" << model.variables.size() << " variables, " << model.rules.size() << " rules)\n";
    std::cout << "markov:      " << chain.size() << " states, " << chain.actions() << (chain.actions() == 1 ? " action: " : " actions: ") << kind << "\n";
    std::cout << "counting:    " << counting << "\n";
    for (const Answer& a : answers) {
      std::cout << "property " << a.name << ": eventually {" << a.target << "}\n";
      std::cout << "  P(eventually):  " << range(a.eventually, deterministic) << "  (" << methods(a.eventually, deterministic) << ")\n";
      std::cout << "  expected:       " << range(a.expected, deterministic) << "  (" << methods(a.expected, deterministic) << ")\n";
      std::cout << "  P(within t steps):";
      for (std::size_t t = 1; t <= options.rounds; ++t) {
        if (t > 1 && (t - 1) % 5 == 0) std::cout << "\n                    ";
        const std::string lo = probabilityText(a.within[0][t]), hi = probabilityText(a.within[1][t]);
        std::cout << fmt::format("  {:>3}: {}", t, deterministic || lo == hi ? hi : lo + (lo.find(' ') != std::string::npos || hi.find(' ') != std::string::npos ? " .. " : "..") + hi);
      }
      std::cout << "\n";
    }
  }
  if (options.svg) {
    std::vector<ChartSeries> series;
    for (const Answer& a : answers) {
      if (!deterministic) series.push_back({a.name + " (min)", a.within[0], true});
      series.push_back({a.name + (deterministic ? "" : " (max)"), a.within[1], false});
    }
    const std::string svg = probabilityChartSvg(series, "P(reached within t steps) - " + input, "t (steps of the model)");
    if (!writeAtomically(*options.svg, svg)) {
      std::cerr << errorPrefix() << "cannot write '" << *options.svg << "'\n";
      return kBadInput;
    }
  }
  return kOk;
}

}  // namespace semo::cli
