// `check` and `export`: build (or read) the IR, then search it or write it out.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "semo/checker/explicit_search.hpp"
#include "semo/checker/fingerprint.hpp"
#include "semo/checker/liveness_search.hpp"
#include "semo/checker/promela_export.hpp"
#include "semo/semantics/ir_text.hpp"
#include "semo/semantics/load.hpp"
#include "semo/semantics/translate.hpp"

namespace semo::cli {

namespace {

bool isIrFile(const std::string& path) { return std::filesystem::path(path).extension() == ".ir"; }

// Reads an IR file, or loads a mission and translates it. Diagnostics are printed; nullopt on error.
std::optional<ir::Model> buildModel(const ModelInput& in) {
  SourceManager sources;
  DiagnosticEngine diags(sources);
  std::optional<ir::Model> model;
  if (isIrFile(in.input)) {
    std::string why;
    FileId file = sources.load(in.input, why);
    if (file == kNoFile) {
      diags.error({}, why);
    } else {
      model = ir::parseText(sources, file, diags);
    }
    if (in.crash || in.loss || in.fairLoss) {
      diags.error({}, "--crash, --loss and --fair-loss/--unfair-loss apply to missions; an IR file states its own assumptions");
    }
  } else if (!in.strategy) {
    diags.error({}, "checking a mission needs --strategy (or give an .ir file)");
  } else if (auto mission = loadMission({in.input, *in.strategy, in.robotsDir}, sources, diags)) {
    TranslationOptions options;
    options.crashOverride = in.crash;
    options.lossOverride = in.loss;
    options.fairLossOverride = in.fairLoss;
    model = translate(*mission, options, sources, diags);
  }
  diags.sortByPosition();
  diags.print(std::cerr);
  if (diags.hasErrors()) return std::nullopt;
  return model;
}

std::string assumptionsLine(const ir::Model& m) {
  std::string out;
  for (const std::string& a : m.assumptions) out += (out.empty() ? "" : "; ") + a;
  return out.empty() ? "none stated" : out;
}

std::string fairnessLine(const ir::Model& m) {
  std::size_t weak = 0, strong = 0;
  for (const ir::Rule& r : m.rules) {
    if (r.stronglyFair) ++strong;
    else if (r.weaklyFair) ++weak;
  }
  std::string out = std::to_string(weak) + " rules weakly fair (robot steps, deliveries: enabled for ever, taken eventually)";
  if (strong > 0) out += ", " + std::to_string(strong) + " strongly fair (deliveries under fair loss)";
  return out;
}

}  // namespace

// --engine auto: the explicit engine decides everything (liveness too) when the state space fits a
// budget; past it, the smt engine's symbolic proofs do not depend on the number of states.
constexpr std::uint64_t kAutoStateBudget = 2'000'000;

int runCheck(const CheckOptions& options) {
  std::optional<ir::Model> model = buildModel(options.model);
  if (!model) return kBadInput;
  if (options.engine == "smt") return runCheckSmt(options, *model);
  const bool automatic = options.engine == "auto";
  checker::SearchLimits limits;
  limits.maxStates = options.maxStates;
  limits.maxMemoryBytes = options.maxMemoryMiB << 20;
  limits.maxDepth = options.maxDepth;
  limits.symmetry = options.symmetry;
  limits.threads = options.threads != 0 ? options.threads : std::max(1u, std::thread::hardware_concurrency());
  if (!options.json) {
    // On a terminal the line is rewritten in place; in a log, one line every ten seconds.
    bool terminal = isatty(STDERR_FILENO) != 0;
    limits.onProgress = [terminal, last = -10.0](const checker::Progress& p) mutable {
      if (!terminal && p.seconds - last < 10.0) return;
      last = p.seconds;
      std::cerr << (terminal ? "\r" : "") << "searching: " << p.states << " states, "
                << static_cast<std::uint64_t>(p.states / p.seconds) << " states/s, depth " << p.depth << ", "
                << (p.bytes >> 20) << " MiB, " << static_cast<int>(p.seconds) << " s" << (terminal ? "   " : "\n") << std::flush;
    };
  }
  std::string engineReason;
  if (automatic) {
    // The probe is never depth-bounded: --max-depth is for BMC, should smt be chosen.
    limits.maxStates = std::min(options.maxStates, kAutoStateBudget);
    limits.maxDepth = UINT32_MAX;
  }
  checker::SearchResult r = checker::checkSafety(*model, limits);
  if (r.seconds >= 1.0 && !options.json && isatty(STDERR_FILENO) != 0) std::cerr << "\n";
  if (automatic) {
    bool found = r.rangeError.has_value();
    for (const checker::PropertyResult& p : r.properties) found = found || p.verdict == checker::Verdict::Violated;
    if (!r.complete && !found && !r.depthBounded) {
      CheckOptions symbolic = options;
      symbolic.engineReason = "the explicit search did not cover the state space within its budget of " +
                              std::to_string(limits.maxStates) + " states (stopped after " + std::to_string(r.states) + "), so smt";
      return runCheckSmt(symbolic, *model);
    }
    engineReason = found ? "explicit search found a violation within its budget of " + std::to_string(kAutoStateBudget) + " states"
                         : "the state space fits the explicit engine's budget of " + std::to_string(kAutoStateBudget) + " states";
    limits.maxStates = options.maxStates;  // the liveness products get the usual limit
  }

  // Liveness needs the whole product: not after a modelling error, and never depth-bounded.
  checker::LivenessResult live;
  std::string liveSkipped;
  if (!model->properties.empty()) {
    if (options.safetyOnly) liveSkipped = "not checked: --safety-only";
    else if (r.rangeError) liveSkipped = "not checked: the model has an error";
    else if (limits.maxDepth != UINT32_MAX) liveSkipped = "not checked: --max-depth bounds safety only";
    if (liveSkipped.empty()) {
      live = checker::checkLiveness(*model, limits);
      if (live.seconds >= 1.0 && !options.json && isatty(STDERR_FILENO) != 0) std::cerr << "\n";
    } else {
      live.complete = false;
      live.limitReached = liveSkipped;
      for (const ir::Property& p : model->properties) live.properties.push_back({p.name, p.origin, checker::Verdict::Unknown, {}});
    }
  }

  bool violated = r.rangeError.has_value();
  for (const checker::PropertyResult& p : r.properties) violated = violated || p.verdict == checker::Verdict::Violated;
  for (const checker::PropertyResult& p : live.properties) violated = violated || p.verdict == checker::Verdict::Violated;
  int code = violated ? kViolated : r.complete && live.complete ? kOk : kLimit;

  if (options.json) {
    // Every counterexample names the model it belongs to, so that it can be read back on its own.
    const std::string fingerprint = checker::modelFingerprint(*model);
    auto traceJson = [&](const checker::Trace& t) {
      nlohmann::json j = nlohmann::json::parse(checker::traceToJson(*model, t));
      j["modelFingerprint"] = fingerprint;
      return j;
    };
    nlohmann::json props = nlohmann::json::array();
    for (const checker::PropertyResult& p : r.properties) {
      nlohmann::json jp = {{"name", p.name}, {"verdict", checker::verdictName(p.verdict)}, {"origin", p.origin}};
      if (p.counterexample) jp["counterexample"] = traceJson(*p.counterexample);
      jp["type"] = "safety";
      props.push_back(jp);
    }
    for (std::size_t k = 0; k < live.properties.size(); ++k) {
      const checker::PropertyResult& p = live.properties[k];
      nlohmann::json jp = {{"name", p.name}, {"verdict", checker::verdictName(p.verdict)}, {"origin", p.origin}, {"type", "liveness"}};
      if (k < live.notes.size() && !live.notes[k].empty()) jp["note"] = live.notes[k];
      if (p.counterexample) jp["counterexample"] = traceJson(*p.counterexample);
      props.push_back(jp);
    }
    nlohmann::json root = {{"input", options.model.input},   {"assumptions", model->assumptions},
                           {"states", r.states},             {"transitions", r.transitions},
                           {"depth", r.depth},               {"complete", r.complete},
                           {"seconds", r.seconds},           {"bytesPerState", r.bytesPerState},
                           {"properties", props},            {"exitCode", code},
                           {"symmetry", r.symmetry},         {"engine", "explicit"}};
    root["modelFingerprint"] = fingerprint;
    addModelInput(root, options.model);  // what `replay` needs to build the same model again
    if (!engineReason.empty()) root["engineChoice"] = engineReason;
    if (!r.limitReached.empty()) root["limit"] = r.limitReached;
    if (r.depthBounded) root["boundedDepth"] = r.depth;
    if (r.rangeError) root["modelError"] = traceJson(*r.rangeError);
    if (!model->properties.empty()) {
      root["liveness"] = {{"productStates", live.states}, {"productTransitions", live.transitions},
                          {"complete", live.complete}, {"seconds", live.seconds},
                          {"propertiesUpToSymmetry", live.reducedProperties}};
      if (!live.limitReached.empty()) root["liveness"]["limit"] = live.limitReached;
    }
    std::cout << root.dump(2) << "\n";
    return code;
  }

  std::cout << "model:       " << options.model.input << " (" << model->variables.size() << " variables, "
            << model->rules.size() << " rules)\n";
  std::cout << "assumptions: " << assumptionsLine(*model) << "\n";
  if (!engineReason.empty()) std::cout << "engine:      explicit (--engine auto: " << engineReason << ")\n";
  for (const std::string& c : r.symmetry) std::cout << "symmetry:    interchangeable " << c << "\n";
  std::cout << "explored:    " << r.states << " states, " << r.transitions << " transitions, depth " << r.depth << " ("
            << (r.complete ? "complete" : "PARTIAL: " + r.limitReached) << "), " << r.seconds << " s\n";
  for (const checker::PropertyResult& p : r.properties) {
    std::cout << "  " << checker::verdictName(p.verdict) << "  " << p.name;
    if (p.verdict == checker::Verdict::Proven) {
      std::cout << "  (all " << r.states << " reachable states" << (r.symmetry.empty() ? "" : " up to symmetry")
                << ", under the assumptions above)";
    } else if (p.verdict == checker::Verdict::Unknown && r.depthBounded) {
      std::cout << "  (holds on every path of up to " << r.depth << (r.depth == 1 ? " step, " : " steps, ") << r.states
                << " states; longer paths not explored)";
    } else if (p.verdict == checker::Verdict::Unknown) {
      std::cout << "  (not violated in the " << r.states << " states explored; the search was not complete)";
    } else if (p.counterexample) {
      std::size_t n = p.counterexample->steps.size();
      std::cout << "  (counterexample of " << n << (n == 1 ? " step" : " steps") << " below)";
    }
    std::cout << "\n";
  }
  if (!model->properties.empty()) {
    std::cout << "liveness:    ";
    if (!liveSkipped.empty()) {
      std::cout << liveSkipped << "\n";
    } else {
      std::cout << live.states << " product states, " << live.transitions << " transitions";
      if (live.reducedProperties > 0) {
        std::cout << " (up to symmetry for " << live.reducedProperties << " of " << live.properties.size() << " properties)";
      }
      std::cout << " (" << (live.complete ? "complete" : "PARTIAL: " + live.limitReached) << "), " << live.seconds << " s\n";
      std::cout << "fairness:    " << fairnessLine(*model) << "\n";
    }
    for (std::size_t k = 0; k < live.properties.size(); ++k) {
      const checker::PropertyResult& p = live.properties[k];
      std::cout << "  " << checker::verdictName(p.verdict) << "  " << p.name;
      if (p.verdict == checker::Verdict::Proven) {
        std::cout << "  (every fair run, under the assumptions above)";
      } else if (p.verdict == checker::Verdict::Unknown && liveSkipped.empty()) {
        std::cout << "  (no violation found in the part explored; the search was not complete)";
      } else if (k < live.notes.size() && !live.notes[k].empty()) {
        std::cout << "  (" << live.notes[k] << ")";
      } else if (p.counterexample) {
        const checker::Trace& t = *p.counterexample;
        std::cout << "  (lasso of " << t.steps.size() << (t.steps.size() == 1 ? " step" : " steps") << " below, ";
        if (t.loopStart >= t.steps.size()) std::cout << "then it stays for ever)";
        else std::cout << "loop from step " << (t.loopStart + 1) << ")";
      }
      std::cout << "\n";
    }
  }
  for (const checker::PropertyResult& p : r.properties) {
    if (p.counterexample) std::cout << "\n" << checker::traceToText(*model, *p.counterexample);
  }
  for (const checker::PropertyResult& p : live.properties) {
    if (p.counterexample) std::cout << "\n" << checker::traceToText(*model, *p.counterexample);
  }
  if (r.rangeError) {
    std::cout << "\nmodel error: " << r.limitReached << "\n" << checker::traceToText(*model, *r.rangeError);
  }
  return code;
}

int runExport(const ExportOptions& options) {
  std::optional<ir::Model> model = buildModel(options.model);
  if (!model) return kBadInput;
  if (options.spinBreadthFirst && options.format != "promela") {
    std::cerr << "semo-verify: error: --spin-bfs applies to --promela only\n";
    return kBadInput;
  }
  std::string text = options.format == "promela" ? checker::toPromela(*model, {.breadthFirst = options.spinBreadthFirst})
                                                 : ir::toText(*model);
  if (!options.output) {
    std::cout << text;
    return kOk;
  }
  const ModelInput& in = options.model;
  if (!outputsSpareInputs({{"--output", *options.output}}, {in.input, in.strategy.value_or(""), in.robotsDir.value_or("")})) return kBadInput;
  if (!writeAtomically(*options.output, text)) {
    std::cerr << "semo-verify: error: cannot write '" << *options.output << "'\n";
    return kBadInput;
  }
  return kOk;
}

}  // namespace semo::cli
