#include "commands.hpp"
#include "semo/semantics/ir_text.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "semo/frontend/ast_json.hpp"
#include "semo/frontend/parser.hpp"
#include "semo/semantics/load.hpp"

namespace semo::cli {

namespace {

std::string plural(std::size_t n, const char* word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

void printSummaryLine(const DiagnosticEngine& diags) {
  if (diags.errorCount() + diags.warningCount() == 0) return;
  std::cerr << plural(diags.errorCount(), "error") << " and " << plural(diags.warningCount(), "warning") << " generated.\n";
}

}  // namespace

void addModelInput(nlohmann::json& root, const ModelInput& in) {
  if (in.strategy) root["strategy"] = *in.strategy;
  if (in.robotsDir) root["robots"] = *in.robotsDir;
  nlohmann::json overrides = nlohmann::json::object();
  if (in.crash) overrides["crash"] = *in.crash;
  if (!in.crashPerTeam.empty()) overrides["crashPerTeam"] = in.crashPerTeam;
  if (in.loss) overrides["loss"] = *in.loss;
  if (in.fairLoss) overrides["fairLoss"] = *in.fairLoss;
  if (!overrides.empty()) root["modelOptions"] = overrides;
}

// Fills what the command line left open from the trace file's header (a `check --json` root).
// Returns an error in words, or "".
std::string modelInputFromTrace(const nlohmann::json& root, ModelInput& in) {
  if (!root.is_object()) return {};
  auto text = [&](const char* key, std::optional<std::string>& into) -> std::string {
    if (!root.contains(key) || into) return {};
    if (!root[key].is_string()) return std::string("\"") + key + "\" must be a string";
    into = root[key].get<std::string>();
    return {};
  };
  std::optional<std::string> input;
  if (in.input.empty()) {
    if (std::string e = text("input", input); !e.empty()) return e;
    if (input) in.input = *input;
  }
  if (std::string e = text("strategy", in.strategy); !e.empty()) return e;
  if (std::string e = text("robots", in.robotsDir); !e.empty()) return e;
  if (root.contains("modelOptions")) {
    const nlohmann::json& o = root["modelOptions"];
    if (!o.is_object()) return "\"modelOptions\" must be an object";
    if (o.contains("crash") && !in.crash) {
      if (!o["crash"].is_number_integer() || o["crash"].get<std::int64_t>() < 0 || o["crash"].get<std::int64_t>() > 100000) return "\"modelOptions/crash\" must be a count";
      in.crash = o["crash"].get<int>();
    }
    if (o.contains("crashPerTeam") && in.crashPerTeam.empty()) {
      const nlohmann::json& teams = o["crashPerTeam"];
      if (!teams.is_object()) return "\"modelOptions/crashPerTeam\" must be an object (team: count)";
      for (auto it = teams.begin(); it != teams.end(); ++it) {
        if (!it->is_number_integer() || it->get<std::int64_t>() < 0 || it->get<std::int64_t>() > 100000) return "\"modelOptions/crashPerTeam\" must map teams to counts";
        in.crashPerTeam[it.key()] = it->get<int>();
      }
    }
    if (o.contains("loss") && !in.loss) {
      if (!o["loss"].is_string()) return "\"modelOptions/loss\" must be a string";
      in.loss = o["loss"].get<std::string>();
    }
    if (o.contains("fairLoss") && !in.fairLoss) {
      if (!o["fairLoss"].is_boolean()) return "\"modelOptions/fairLoss\" must be true or false";
      in.fairLoss = o["fairLoss"].get<bool>();
    }
  }
  return {};
}

int runParse(const ParseOptions& options) {
  SourceManager sources;
  DiagnosticEngine diags(sources);
  std::string why;
  FileId file = sources.load(options.mission, why);
  if (file == kNoFile) {
    diags.error({}, why);
    diags.print(std::cerr);
    return kBadInput;
  }
  // An IR model (by its extension or its first word) is read as IR, not as a mission.
  if (options.mission.ends_with(".ir") || ir::looksLikeIr(sources.text(file))) {
    std::optional<ir::Model> model = ir::parseText(sources, file, diags);
    diags.sortByPosition();
    diags.print(std::cerr);
    printSummaryLine(diags);
    if (!model) return kBadInput;
    if (options.json) {
      std::cerr << errorPrefix() << "--json prints a mission's syntax tree; an IR file has none (`export --ir` writes IR)\n";
      return kBadInput;
    }
    std::cout << options.mission << ": parsed as an IR model: " << plural(model->robots.size(), "robot") << ", "
              << plural(model->variables.size(), "variable") << ", " << plural(model->rules.size(), "rule") << ", "
              << plural(model->invariants.size(), "invariant") << ", " << model->properties.size()
              << (model->properties.size() == 1 ? " LTL property" : " LTL properties") << "\n";
    return kOk;
  }
  ast::Mission mission = parseMission(sources, file, diags);
  diags.sortByPosition();
  diags.print(std::cerr);
  printSummaryLine(diags);
  if (diags.hasErrors()) return kBadInput;
  std::cout << (options.json ? missionToJson(mission) : options.mission + ": parsed\n" + missionSummary(mission));
  return kOk;
}

int runLint(const LintOptions& options) {
  SourceManager sources;
  DiagnosticEngine diags(sources);
  std::optional<model::MissionModel> model =
      loadMission({options.mission, options.strategy, options.robotsDir}, sources, diags);
  diags.sortByPosition();
  if (options.sarif) {
    std::vector<std::string> inputs = filesRead(sources);
    inputs.insert(inputs.end(), {options.mission, options.strategy, options.robotsDir.value_or("")});
    if (!outputsSpareInputs({{"--sarif", *options.sarif}}, inputs)) return kBadInput;
    if (!writeAtomically(*options.sarif, diagnosticsSarif(sources, diags))) {
      std::cerr << errorPrefix() << "cannot write '" << *options.sarif << "'\n";
      return kBadInput;
    }
  }
  const bool failed = !model || (options.warningsAsErrors && diags.warningCount() > 0);
  if (options.json) {
    auto diagnosticJson = [&sources](const Diagnostic& d) {
      nlohmann::json one = {{"severity", d.severity == Severity::Error ? "error" : d.severity == Severity::Warning ? "warning" : "note"},
                            {"message", d.message}};
      if (d.range.begin.valid()) one["file"] = sources.path(d.range.begin.file);
      if (d.range.begin.hasPosition()) one["line"] = d.range.begin.line, one["column"] = d.range.begin.column, one["length"] = d.range.length;
      return one;
    };
    nlohmann::json list = nlohmann::json::array();
    for (const Diagnostic& d : diags.diagnostics()) {
      nlohmann::json one = diagnosticJson(d);
      for (const Diagnostic& n : d.notes) one["notes"].push_back(diagnosticJson(n));
      list.push_back(std::move(one));
    }
    nlohmann::json out = {{"schemaVersion", 1}, {"tool", std::string("semo-verify ") + kToolVersion}, {"input", options.mission},
                          {"strategy", options.strategy}, {"diagnostics", list}, {"errors", diags.errorCount()},
                          {"warnings", diags.warningCount()}, {"exitCode", failed ? kBadInput : kOk}};
    if (model) {
      out["summary"] = {{"teams", model->teams.size()}, {"robots", model->robots.size()}, {"services", model->services.size()},
                        {"modes", model->modes.size()}, {"groupBlocks", model->groupBlocks.size()}, {"robotTypes", model->catalog.types().size()}};
    }
    std::cout << out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
    return failed ? kBadInput : kOk;
  }
  diags.print(std::cerr);
  printSummaryLine(diags);
  if (failed) return kBadInput;
  std::cout << options.mission << ": ok: " << plural(model->teams.size(), "team") << ", "
            << plural(model->robots.size(), "robot") << ", " << plural(model->services.size(), "service") << ", "
            << plural(model->modes.size(), "mode") << ", " << plural(model->groupBlocks.size(), "group block") << ", "
            << plural(model->catalog.types().size(), "robot type") << "\n";
  return kOk;
}

// Writes through a temporary file and renames it, so that a failure never leaves half a file.
// Text that fits `width` columns: words moved to continuation lines indented by `indent`.
std::string wrapText(const std::string& line, std::size_t indent, std::size_t width) {
  if (line.size() <= width) return line + "\n";
  std::string out, current;
  std::size_t start = 0;
  const std::size_t lead = line.find_first_not_of(' ');
  current = line.substr(0, lead);
  start = lead;
  while (start < line.size()) {
    std::size_t space = line.find(' ', start);
    if (space == std::string::npos) space = line.size();
    const std::string word = line.substr(start, space - start);
    const bool fresh = current.find_first_not_of(' ') == std::string::npos;
    if (!fresh && current.size() + 1 + word.size() > width) {
      out += current + "\n";
      current = std::string(indent, ' ');
      current += word;
    } else {
      current += (fresh ? "" : " ") + word;
    }
    start = space + 1;
  }
  return out + current + "\n";
}

namespace {
bool announceWrites = true;
}  // namespace

void setAnnounceWrites(bool on) { announceWrites = on; }

bool writeAtomically(const std::string& path, const std::string& text) {
  // The temporary file is new (O_EXCL): a name already taken, perhaps by an input of the run
  // ("out.partial" beside "out"), is never opened, let alone renamed over the output.
  std::string temporary;
  int fd = -1;
  for (int attempt = 0; fd < 0 && attempt < 100; ++attempt) {
    temporary = path + ".partial-" + std::to_string(getpid()) + "-" + std::to_string(attempt);
    fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) return false;
  }
  if (fd < 0) return false;
  bool written = true;
  for (std::size_t done = 0; written && done < text.size();) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    written = n > 0;
    if (written) done += static_cast<std::size_t>(n);
  }
  written = ::close(fd) == 0 && written;
  std::error_code ec;
  if (written) std::filesystem::rename(temporary, path, ec);
  if (!written || ec) {
    std::filesystem::remove(temporary, ec);
    return false;
  }
  if (announceWrites) std::cerr << programName() << ": wrote " << path << "\n";
  return true;
}

std::vector<std::string> filesRead(const SourceManager& sources) {
  std::vector<std::string> out;
  for (std::size_t id = 0; id < sources.fileCount(); ++id) out.push_back(sources.path(static_cast<FileId>(id)));
  return out;
}

bool outputsSpareInputs(const std::vector<Output>& outputs, const std::vector<std::string>& inputs) {
  namespace fs = std::filesystem;
  std::vector<std::string> files;
  for (const std::string& in : inputs) {
    std::error_code ec;
    if (in.empty()) continue;
    if (!fs::is_directory(in, ec)) {
      files.push_back(in);
      continue;
    }
    for (fs::directory_iterator it(in, ec), end; !ec && it != end; it.increment(ec)) files.push_back(it->path().string());
  }
  for (const Output& out : outputs) {
    std::error_code ec;
    // Where it cannot be written, nothing is: checked for every output before any is written.
    const fs::path folder = fs::path(out.path).parent_path().empty() ? fs::path(".") : fs::path(out.path).parent_path();
    if (fs::is_directory(out.path, ec)) {
      std::cerr << errorPrefix() << out.flag << " '" << out.path << "' is a folder; give a file name\n";
      return false;
    }
    if (!out.inNewFolder && !fs::is_directory(folder, ec)) {
      std::cerr << errorPrefix() << out.flag << " '" << out.path << "': there is no folder '" << folder.string()
                << "' to write it in\n";
      return false;
    }
    if (!fs::exists(out.path, ec)) continue;  // a file yet to be made replaces nothing
    for (const std::string& in : files) {
      std::error_code same;
      if (fs::equivalent(out.path, in, same) && !same) {
        std::cerr << errorPrefix() << out.flag << " '" << out.path << "' is an input of this run (" << in
                  << "): semo never writes over its inputs; choose another file\n";
        return false;
      }
    }
  }
  return true;
}


}  // namespace semo::cli
