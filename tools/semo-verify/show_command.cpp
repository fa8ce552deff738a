// `show TRACE.json`: a counterexample of `check --json` / `check --trace-out` printed again, read
// back against the model it was found on (checker/trace_reader.hpp: every step replayed and checked,
// the fingerprint compared), as check prints it, or one robot's steps, or with every variable.
#include <iostream>
#include <regex>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "sequence_chart.hpp"
#include "semo/checker/stepper.hpp"
#include "semo/checker/trace_reader.hpp"
#include "semo/frontend/json_text.hpp"

namespace semo::cli {

namespace {

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    out.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

// The text check prints, narrowed to one robot's steps and/or given the whole state after each
// step. Step blocks are a header "  N. [robot] ..." and the lines indented under it.
std::string narrowed(const std::string& text, const checker::ReplayedTrace& trace, const checker::Stepper& stepper,
                     const ShowOptions& options) {
  static const std::regex header(R"(^ +([0-9]+)\. \[([^\]]*)\])");
  std::string out;
  std::size_t hidden = 0;
  auto flushHidden = [&] {
    if (hidden > 0) out += "  ... " + std::to_string(hidden) + (hidden == 1 ? " step" : " steps") + " of other robots or the network\n";
    hidden = 0;
  };
  bool keeping = true;
  std::size_t step = 0;  // the step whose block is being read (1-based; 0: none)
  auto stateLine = [&] {
    if (options.fullState && keeping && step > 0 && step < trace.states.size()) {
      out += wrapText("       state: " + stepper.describe(trace.states[step]), 14);
    }
  };
  const std::vector<std::string> all = lines(text);
  for (std::size_t i = 0; i < all.size(); ++i) {
    const std::string& line = all[i];
    std::smatch m;
    if (std::regex_search(line, m, header)) {
      stateLine();
      step = static_cast<std::size_t>(std::stoul(m[1].str()));
      keeping = !options.robot || m[2].str() == *options.robot;
      if (!keeping) {
        ++hidden;
        continue;
      }
      flushHidden();
      out += line + "\n";
      continue;
    }
    const bool detail = step > 0 && line.rfind("       ", 0) == 0;
    if (detail) {
      if (keeping) out += line + "\n";
      continue;
    }
    stateLine();
    step = 0, keeping = true;
    flushHidden();
    out += line + "\n";
    if (i == 0 && options.fullState && !trace.states.empty()) out += wrapText("  initial state: " + stepper.describe(trace.states[0]), 14);
  }
  stateLine();
  flushHidden();
  return out;
}

}  // namespace

int runShow(const ShowOptions& options) {
  SourceManager traceSources;
  DiagnosticEngine traceDiags(traceSources);
  std::string why;
  const FileId file = traceSources.load(options.trace, why);
  if (file == kNoFile) {
    std::cerr << errorPrefix() << why << "\n";
    return kBadInput;
  }
  std::optional<nlohmann::json> root = parseJsonFile(traceSources, file, traceDiags);
  if (!root) {
    traceDiags.print(std::cerr);
    return kBadInput;
  }
  ModelInput in = options.model;
  if (std::string e = modelInputFromTrace(*root, in); !e.empty()) {
    std::cerr << options.trace << ": error: " << e << "\n";
    return kBadInput;
  }
  if (in.input.empty()) {
    std::cerr << errorPrefix() << options.trace << " does not say which model it was found on (a single counterexample "
              << "object): give the mission (with --strategy) or the IR file\n";
    return kBadInput;
  }
  std::unique_ptr<BuiltModel> built = buildModel(in, nullptr, /*warnings=*/false);  // check printed them
  if (!built) return kBadInput;
  const ir::Model& model = *built->model;
  if (options.robot && std::find(model.robots.begin(), model.robots.end(), *options.robot) == model.robots.end()) {
    std::string names;
    for (const std::string& r : model.robots) names += (names.empty() ? "" : ", ") + r;
    std::cerr << errorPrefix() << "--robot '" << *options.robot << "' is no robot of " << in.input << " (its robots: " << names << ")\n";
    return kBadInput;
  }
  const checker::Stepper stepper(model);
  checker::TraceReadOptions read;
  read.property = options.property.value_or("");
  read.checkFingerprint = options.checkFingerprint;
  std::optional<checker::ReplayedTrace> trace = checker::readTrace(traceSources, file, stepper, traceDiags, read);
  traceDiags.sortByPosition();
  traceDiags.print(std::cerr);
  if (!trace) return kBadInput;
  const checker::Trace asChecked = trace->toTrace();
  if (options.msc) {
    std::vector<std::string> inputs = filesRead(built->sources);
    inputs.insert(inputs.end(), {options.trace, in.input, in.strategy.value_or(""), in.robotsDir.value_or("")});
    if (!outputsSpareInputs({{"--msc", *options.msc}}, inputs)) return kBadInput;
    const std::string name = trace->property.empty() ? std::string("the model error") : trace->property;
    if (!writeAtomically(*options.msc, sequenceChartSvg(model, asChecked, "counterexample for " + name + " - " + in.input))) {
      std::cerr << errorPrefix() << "cannot write '" << *options.msc << "'\n";
      return kBadInput;
    }
  }
  const std::string text = checker::traceToText(model, asChecked);
  std::cout << (options.robot || options.fullState ? narrowed(text, *trace, stepper, options) : text);
  return kOk;
}

}  // namespace semo::cli
