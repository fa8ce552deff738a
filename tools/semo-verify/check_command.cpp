// `check` and `export`: build (or read) the IR, then verify it (checker/verify.hpp) and print the
// Report, or write the model out.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include <fmt/format.h>

#include "commands.hpp"
#include "progress_line.hpp"
#include "sequence_chart.hpp"
#include "semo/checker/fingerprint.hpp"
#include "semo/checker/markov.hpp"
#include "semo/checker/prism_export.hpp"
#include "semo/checker/promela_export.hpp"
#include "semo/semantics/ir_text.hpp"
#include "semo/semantics/load.hpp"
#include "semo/semantics/translate.hpp"

namespace semo::cli {

namespace {

bool isIrFile(const std::string& path) { return std::filesystem::path(path).extension() == ".ir"; }

}  // namespace

std::unique_ptr<BuiltModel> buildModel(const ModelInput& in, ProgressLine* line, bool warnings) {
  auto out = std::make_unique<BuiltModel>();
  const auto started = std::chrono::steady_clock::now();
  DiagnosticEngine diags(out->sources);
  if (isIrFile(in.input)) {
    std::string why;
    FileId file = out->sources.load(in.input, why);
    if (file == kNoFile) {
      diags.error({}, why);
    } else {
      if (line != nullptr) line->phase(fmt::format("reading the IR model ({} bytes)", out->sources.text(file).size()));
      out->model = ir::parseText(out->sources, file, diags);
    }
    if (in.crash || !in.crashPerTeam.empty() || in.loss || in.fairLoss) {
      diags.error({}, "--crash, --loss and --fair-loss/--unfair-loss apply to missions; an IR file states its own assumptions");
    }
  } else if (!in.strategy) {
    diags.error({}, "a mission needs its strategy: add " + strategyExample(in.input) + "; an .ir file needs none");
  } else if ((out->mission = loadMission({in.input, *in.strategy, in.robotsDir}, out->sources, diags))) {
    TranslationOptions options;
    options.crashOverride = in.crash;
    options.crashPerTeam = in.crashPerTeam;
    options.lossOverride = in.loss;
    options.fairLossOverride = in.fairLoss;
    if (line != nullptr) {
      const std::size_t teams = out->mission->teams.size();
      line->phase(fmt::format("translating the mission: {} robots in {} team{}", out->mission->robots.size(), teams, teams == 1 ? "" : "s"));
    }
    out->translation = translateMission(*out->mission, options, out->sources, diags);
    if (out->translation) out->model = out->translation->model;
  }
  if (line != nullptr) line->pause();
  diags.sortByPosition();
  if (warnings || diags.hasErrors()) diags.print(std::cerr);
  if (diags.hasErrors() || !out->model) return nullptr;
  out->buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

namespace {

// --props FILE: per line a property name or glob, or `check a, b` as in the verify block; `#`
// starts a comment. A `property` line would need the mission's formula syntax: refused, with its
// position, pointing at the verify block.
bool readPropsFile(const std::string& path, std::vector<std::string>& out, SourceManager& sources, DiagnosticEngine& diags) {
  std::string why;
  const FileId file = sources.load(path, why);
  if (file == kNoFile) {
    diags.error({}, why);
    return false;
  }
  for (std::uint32_t line = 1; line <= sources.lineCount(file); ++line) {
    std::string text(sources.lineText(file, line));
    text = text.substr(0, text.find('#'));
    const std::size_t first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos) continue;
    auto at = [&](std::size_t column, std::size_t length) {
      return SourceRange{{file, line, static_cast<std::uint32_t>(column + 1)}, static_cast<std::uint32_t>(std::max<std::size_t>(1, length))};
    };
    const std::string head = text.substr(first, text.find_first_of(" \t", first) - first);
    if (head == "property" || head == "assume") {
      diags.error(at(first, head.size()), "a `" + head + "` line belongs in the mission's verify block; --props names properties to decide, "
                                          "a name or glob per line, or `check a, b`");
      continue;
    }
    std::size_t start = first;
    bool list = head == "check";
    if (list) start = first + head.size();
    // `check` lists are separated by commas; a single name may contain them (group names do).
    while (start < text.size()) {
      const std::size_t end = list ? std::min(text.find(',', start), text.size()) : text.size();
      const std::string item = text.substr(start, end - start);
      const std::size_t b = item.find_first_not_of(" \t\r"), e = item.find_last_not_of(" \t\r");
      if (b == std::string::npos) {
        if (list) diags.error(at(start, 1), "an empty name in a `check` list");
      } else {
        out.push_back(item.substr(b, e - b + 1));
      }
      start = end + 1;
    }
  }
  return !diags.hasErrors();
}

}  // namespace

// The model's size, and what the search will try. Said at once for a large model (a team of
// hundreds of robots, thousands of rules), else only once the run has lasted long enough to print
// its phases.
void announceSearch(const BuiltModel& built, const CheckOptions& o, ProgressLine& line) {
  const ir::Model& m = *built.model;
  auto count = [](std::uint64_t n, const char* one, const char* many) { return withThousands(n) + " " + (n == 1 ? one : many); };
  std::string text = fmt::format("model: {}, {}, {}; {}{}, {}", count(m.robots.size(), "robot", "robots"),
                                 count(m.variables.size(), "variable", "variables"), count(m.rules.size(), "rule", "rules"),
                                 count(m.invariants.size(), "invariant", "invariants"), m.validEnd ? " and deadlock freedom" : "",
                                 count(o.safetyOnly ? 0 : m.properties.size(), "LTL property", "LTL properties"));
  if (built.buildSeconds >= 1.0) text += fmt::format(" (built in {:.1f} s)", built.buildSeconds);
  text += "\n  trying: ";
  const std::string symmetry = o.symmetry ? ", one state per ordering of interchangeable robots" : "";
  const std::string explicitSearch = "a breadth-first search of the states (at most " + withThousands(o.maxStates) +
                                    (o.maxDepth != UINT32_MAX ? ", to depth " + std::to_string(o.maxDepth) : std::string()) + symmetry + ")";
  const std::string cone = o.coneSeconds > 0 ? fmt::format(", then on its exact cone (up to {} s of processor time: --cone-seconds)", o.coneSeconds) : "";
  const std::string ltl = o.safetyOnly || m.properties.empty() ? std::string()
                          : o.slicing ? "; then each LTL property on its product, searched whole if the state space is small, else on slices of the model refined by counterexamples" + cone
                                      : "; then each LTL property on its product with the whole model";
  if (o.engine == "counting") {
    text += "the counter abstraction: the robots of the team counted per local state";
  } else if (o.engine == "smt") {
    text += "Z3: bounded model checking" + (o.maxDepth != UINT32_MAX ? " to depth " + std::to_string(o.maxDepth) : std::string(" to depth 5")) +
            (o.bmcOnly ? "" : ", then k-induction and IC3") + " (safety properties only)";
  } else if (o.engine == "auto") {
    if (built.translation && !built.translation->lowering.countDefinitions.empty()) {
      text += "the counter abstraction (the team's robots counted per local state); where it leaves a property undecided, ";
    }
    text += explicitSearch + " within 2,000,000 states, else Z3 (bounded model checking, k-induction, IC3)" + ltl;
  } else {
    text += explicitSearch + ltl;
    if (built.translation && !built.translation->lowering.countDefinitions.empty()) {
      text += "\n  (the team has counts of its robots: --engine auto, or counting, searches them per local state, "
              "at a cost that does not grow with the team)";
    }
  }
  const bool large = m.robots.size() >= 50 || m.variables.size() >= 1000 || m.rules.size() >= 5000 || built.buildSeconds >= 2.0;
  if (large) line.say(text);
  else line.sayIfLong(text);
}

checker::VerifyOptions verifyOptions(const CheckOptions& options, ProgressLine* line) {
  checker::VerifyOptions v;
  v.engine = options.engine == "smt"        ? checker::Engine::Smt
             : options.engine == "auto"     ? checker::Engine::Auto
             : options.engine == "counting" ? checker::Engine::Counting
                                            : checker::Engine::Explicit;
  v.limits.maxStates = options.maxStates;
  v.limits.maxMemoryBytes = options.maxMemoryMiB << 20;
  v.limits.maxDepth = options.maxDepth;
  v.limits.symmetry = options.symmetry;
  v.liveness.slicing = options.slicing;
  v.liveness.slicesFirst = options.slicesFirst;
  v.liveness.symbolic = options.symbolic;
  v.liveness.walks = options.walks;
  v.liveness.walkSeed = options.walkSeed;
  v.liveness.sliceStates = options.sliceStates;
  v.liveness.symbolicSeconds = options.symbolicSeconds;
  v.liveness.coneSeconds = options.coneSeconds;
  v.limits.threads = options.threads != 0 ? options.threads : checker::defaultThreads();
  v.safetyOnly = options.safetyOnly;
  v.smt.induction = v.smt.ic3 = !options.bmcOnly;
  v.smt.timeoutMs = options.smtTimeoutS * 1000u;
  v.crashOverride = options.model.crash;
  v.crashPerTeam = options.model.crashPerTeam;
  if (line != nullptr) {
    v.limits.onPhase = [line](const std::string& what) { line->phase(what); };
    v.smt.onPhase = v.limits.onPhase;
    v.bounds.onPhase = v.limits.onPhase;  // emit: the task graphs' proofs come after the searches
    v.limits.onProgress = [line](const checker::Progress& p) { line->searched(p); };
  }
  return v;
}

int runCheck(const CheckOptions& options) {
  ProgressLine line(!options.json);
  std::unique_ptr<BuiltModel> built = buildModel(options.model, &line);
  if (!built) return kBadInput;
  DiagnosticEngine diags(built->sources);
  checker::VerifyOptions verify = verifyOptions(options, &line);
  std::vector<std::string> globs = options.props, selected;
  if (options.propsFile && !readPropsFile(*options.propsFile, globs, built->sources, diags)) {
    diags.print(std::cerr);
    return kBadInput;
  }
  if (options.propsFile && globs.empty()) {
    std::cerr << errorPrefix() << *options.propsFile << " names no property\n";
    return kBadInput;
  }
  std::vector<Output> outputs;
  if (options.traceOut) outputs.push_back({"--trace-out", *options.traceOut});
  if (options.junit) outputs.push_back({"--junit", *options.junit});
  if (options.sarif) outputs.push_back({"--sarif", *options.sarif});
  if (options.msc) outputs.push_back({"--msc", *options.msc});
  if (!outputs.empty()) {
    std::vector<std::string> inputs = filesRead(built->sources);
    inputs.insert(inputs.end(), {options.model.input, options.model.strategy.value_or(""), options.model.robotsDir.value_or(""),
                                 options.propsFile.value_or("")});
    if (!outputsSpareInputs(outputs, inputs)) return kBadInput;
  }
  // The fingerprint names the model, whichever of its properties are decided: a counterexample found
  // with --prop is read back (show, replay) on the whole model.
  // (Only a selection changes the model verify sees; without one, verify's own fingerprint is it.)
  const std::string fingerprint = globs.empty() ? std::string() : checker::modelFingerprint(*built->model);
  if (!globs.empty()) {
    try {
      selected = checker::selectProperties(*built->model, globs);
    } catch (const std::invalid_argument& e) {
      std::cerr << errorPrefix() << e.what() << "\n";
      return kBadInput;
    }
    verify.propertyGlobs = globs;
  }
  if (built->translation) {
    verify.smt.lemmas = built->translation->lowering.countDefinitions;  // the SMT engine proves them first; counting reads them
    verify.countedTeamsFrom = TranslationOptions{}.countTeamsAbove + 1;
  }
  announceSearch(*built, options, line);
  std::optional<checker::Report> report =
      checker::verify(*built->model, built->mission ? &*built->mission : nullptr, verify, diags);
  line.stop();
  diags.sortByPosition();
  diags.print(std::cerr);
  if (!report) return kBadInput;
  if (!fingerprint.empty()) report->modelFingerprint = fingerprint;
  nlohmann::json json = reportJson(*report, *built->model, options.model);
  if (!globs.empty()) json["selection"] = {{"globs", globs}, {"properties", selected}};
  // --trace-out keeps what --json prints (verdicts and counterexamples, specs/trace.md) in a file,
  // for `show` and `replay`, whatever the text on the terminal.
  for (const auto& [path, text] : {std::pair{options.traceOut, options.traceOut ? json.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n" : std::string()},
                                   std::pair{options.junit, options.junit ? junitXml(*report, *built->model, options.model.input) : std::string()},
                                   std::pair{options.sarif, options.sarif ? checkSarif(*report, *built->model) : std::string()}}) {
    if (path && !writeAtomically(*path, text)) {
      std::cerr << errorPrefix() << "cannot write '" << *path << "'\n";
      return kBadInput;
    }
  }
  if (options.msc) {
    const checker::PropertyVerdict* first = nullptr;
    for (const checker::PropertyVerdict& p : report->properties) {
      if (p.counterexample && first == nullptr) first = &p;
    }
    if (first == nullptr) {
      std::cerr << notePrefix() << "no counterexample to draw: " << *options.msc << " not written\n";
    } else if (!writeAtomically(*options.msc, sequenceChartSvg(*built->model, *first->counterexample,
                                                               "counterexample for " + first->name + " - " + options.model.input))) {
      std::cerr << errorPrefix() << "cannot write '" << *options.msc << "'\n";
      return kBadInput;
    }
  }
  if (options.json) {
    std::cout << json.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  } else {
    // The selection overrides the verify block's list: said before the verdicts.
    if (!globs.empty()) {
      std::string names;
      for (const std::string& n : selected) names += (names.empty() ? "" : ", ") + n;
      std::cout << "selected:    " << selected.size() << " propert" << (selected.size() == 1 ? "y" : "ies")
                << " (--prop/--props, instead of the verify block's list): " << names << "\n";
    }
    std::cout << reportText(*report, *built->model, options.model.input, options.bmcOnly) << "\n" << resultLine(*report);
  }
  return report->exitCode;
}

namespace {
// At most one rule enabled in every reachable state, as far as `limit` states show (a larger model
// is written as an mdp, whose minimum and maximum then agree where it is deterministic after all).
bool deterministicWithin(const ir::Model& model, std::size_t limit) {
  try {
    return checker::buildMarkovModel(model, {.maxStates = limit}).deterministic();
  } catch (const checker::MarkovError&) {
    return false;
  }
}
}  // namespace

int runExport(const ExportOptions& options) {
  ProgressLine line(true);
  std::unique_ptr<BuiltModel> built = buildModel(options.model, &line);
  if (!built) return kBadInput;
  line.phase("writing the model as " + (options.format == "ir" ? std::string("IR") : options.format == "prism" ? std::string("PRISM") : std::string("Promela")));
  const ir::Model& model = *built->model;
  if ((options.spinBreadthFirst || options.spinLiveness) && options.format != "promela") {
    std::cerr << errorPrefix() << "--spin-bfs and --spin-ltl apply to --promela only\n";
    return kBadInput;
  }
  if (options.properties && options.format != "prism") {
    std::cerr << errorPrefix() << "--props applies to --prism only\n";
    return kBadInput;
  }
  std::string text, properties;
  if (options.format == "prism") {
    const checker::PrismModel prism = checker::toPrism(model, deterministicWithin(model, 200'000));
    text = prism.model;
    properties = prism.properties;
  } else {
    text = options.format == "promela" ? checker::toPromela(model, {.breadthFirst = options.spinBreadthFirst, .liveness = options.spinLiveness})
                                       : ir::toText(model);
  }
  const ModelInput& in = options.model;
  std::vector<Output> outputs;
  if (options.output) outputs.push_back({"--output", *options.output});
  if (options.properties) outputs.push_back({"--props", *options.properties});
  std::vector<std::string> inputs = filesRead(built->sources);  // the URDF files the strategy names too
  inputs.insert(inputs.end(), {in.input, in.strategy.value_or(""), in.robotsDir.value_or("")});
  if (!outputsSpareInputs(outputs, inputs)) return kBadInput;
  line.stop();
  if (!options.output) std::cout << text;
  for (const auto& [path, content] : {std::pair{options.output, &text}, std::pair{options.properties, &properties}}) {
    if (path && !writeAtomically(*path, *content)) {
      std::cerr << errorPrefix() << "cannot write '" << *path << "'\n";
      return kBadInput;
    }
  }
  return kOk;
}

}  // namespace semo::cli
