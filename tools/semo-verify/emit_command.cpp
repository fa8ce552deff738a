// `emit`: verify (checker/verify.hpp, the same engines and options as check, and every robot's task
// graph), then write the generated tree (codegen/emit.hpp) all at once, or refuse.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "progress_line.hpp"
#include "semo/codegen/emit.hpp"

namespace semo::cli {

namespace {

namespace fs = std::filesystem;

// The top-level entries emit writes; anything else in an earlier emit's folder (a build folder, say)
// is the user's and is kept.
bool generatedEntry(const std::string& name) {
  return name == "CMakeLists.txt" || name == "README.md" || name == "certificate.json" || name == "mission" || name == "robots";
}

// An earlier emit's folder: it holds a semo certificate.
bool earlierEmit(const fs::path& dir) {
  std::ifstream in(dir / "certificate.json");
  if (!in) return false;
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  return j.is_object() && j.value("format", "") == "semo-certificate";
}

// Writes `files` into `dir`: into a new folder next to it first, which then takes its place, so that
// a failure leaves `dir` as it was. The user's own entries of an earlier emit's folder move along.
bool writeTree(const fs::path& dir, const std::vector<codegen::GeneratedFile>& files, std::string& error) {
  std::error_code ec;
  const bool exists = fs::exists(dir, ec);
  if (exists && !fs::is_directory(dir, ec)) {
    error = "'" + dir.string() + "' exists and is not a folder";
    return false;
  }
  if (exists && !fs::is_empty(dir, ec) && !earlierEmit(dir)) {
    error = "'" + dir.string() + "' is neither empty nor an earlier emit's folder (no semo certificate.json): give a new or empty folder";
    return false;
  }
  const fs::path absolute = fs::absolute(dir, ec).lexically_normal();
  const fs::path parent = absolute.has_filename() ? absolute.parent_path() : absolute.parent_path().parent_path();
  const std::string name = (absolute.has_filename() ? absolute : absolute.parent_path()).filename().string();
  fs::create_directories(parent, ec);
  const fs::path staging = parent / ("." + name + ".emit-" + std::to_string(getpid()));
  const fs::path old = parent / ("." + name + ".old-" + std::to_string(getpid()));
  fs::remove_all(staging, ec);
  auto fail = [&](const std::string& why) {
    fs::remove_all(staging, ec);
    error = why;
    return false;
  };
  for (const codegen::GeneratedFile& f : files) {
    const fs::path path = staging / f.path;
    fs::create_directories(path.parent_path(), ec);
    std::ofstream out(path, std::ios::binary);
    out << f.text;
    if (!out) return fail("cannot write '" + (dir / f.path).string() + "'");
  }
  if (!exists) {
    fs::rename(staging, absolute, ec);
    return ec ? fail("cannot create '" + dir.string() + "': " + ec.message()) : true;
  }
  // The user's entries move into the new tree (a build folder keeps its path, so its cache stays valid).
  std::vector<std::string> kept;
  for (const fs::directory_entry& e : fs::directory_iterator(absolute, ec)) {
    const std::string entry = e.path().filename().string();
    if (generatedEntry(entry)) continue;
    fs::rename(e.path(), staging / entry, ec);
    if (ec) {
      for (const std::string& k : kept) fs::rename(staging / k, absolute / k, ec);
      return fail("cannot keep '" + e.path().string() + "' in the new tree");
    }
    kept.push_back(entry);
  }
  fs::rename(absolute, old, ec);
  if (!ec) fs::rename(staging, absolute, ec);
  if (ec) {
    fs::rename(old, absolute, ec);
    for (const std::string& k : kept) fs::rename(staging / k, absolute / k, ec);
    return fail("cannot replace '" + dir.string() + "'");
  }
  fs::remove_all(old, ec);
  return true;
}

}  // namespace

int runEmit(const EmitOptions& options) {
  const ModelInput& in = options.check.model;
  if (!in.strategy || in.input.ends_with(".ir")) {
    std::cerr << errorPrefix() << "emit needs a mission and its strategy (an IR file has no robots to generate)\n";
    return kBadInput;
  }
  if (!in.crashPerTeam.empty()) {
    // The certificate records one --crash for every team (certify rebuilds the model from it).
    std::cerr << errorPrefix() << "--crash N:TEAM is for check; emit takes --crash N for every team, or the verify block's "
                 "`assume crash <= N in TEAM`\n";
    return kBadInput;
  }
  ProgressLine line(!options.check.json);
  std::unique_ptr<BuiltModel> built = buildModel(in, &line);
  if (!built) return kBadInput;
  std::vector<std::string> inputs = filesRead(built->sources);
  if (in.robotsDir) inputs.push_back(*in.robotsDir);
  for (const std::string& input : inputs) {  // the tree replaces --out whole: no input may lie inside it
    std::error_code ec;
    const fs::path a = fs::weakly_canonical(input, ec), o = fs::weakly_canonical(options.out, ec);
    const auto [end, _] = std::mismatch(o.begin(), o.end(), a.begin(), a.end());
    if (end == o.end()) {
      std::cerr << errorPrefix() << "--out '" << options.out << "' holds the input '" << input << "', which emit would replace\n";
      return kBadInput;
    }
  }

  checker::VerifyOptions verify = verifyOptions(options.check, &line);
  verify.taskGraphs = true;
  verify.bounds.timeoutMs = options.proofTimeoutMs;
  DiagnosticEngine diags(built->sources);
  if (built->translation) {
    verify.smt.lemmas = built->translation->lowering.countDefinitions;  // the SMT engine proves them first; counting reads them
    verify.countedTeamsFrom = TranslationOptions{}.countTeamsAbove + 1;
  }
  announceSearch(*built, options.check, line);
  std::optional<checker::Report> report = checker::verify(*built->model, &*built->mission, verify, diags);
  line.stop();
  diags.sortByPosition();
  diags.print(std::cerr);
  if (!report) return kBadInput;
  std::cout << reportText(*report, *built->model, in.input, options.check.bmcOnly);

  codegen::EmitOptions eo;
  eo.missionPath = in.input;
  eo.strategyPath = *in.strategy;
  eo.robotsDir = in.robotsDir.value_or("");
  eo.crash = in.crash;
  eo.loss = in.loss;
  eo.fairLoss = in.fairLoss;
  eo.engine = options.check.engine;
  eo.maxStates = options.check.maxStates;
  eo.maxDepth = options.check.maxDepth;
  eo.symmetry = options.check.symmetry;
  eo.safetyOnly = options.check.safetyOnly;
  eo.bmcOnly = options.check.bmcOnly;
  eo.proofTimeoutMs = options.proofTimeoutMs;
  eo.slicing = options.check.slicing;
  eo.slicesFirst = options.check.slicesFirst;
  eo.sliceStates = options.check.sliceStates;
  eo.symbolic = options.check.symbolic;
  eo.symbolicSeconds = options.check.symbolicSeconds;
  eo.coneSeconds = options.check.coneSeconds;
  eo.walks = options.check.walks;
  eo.walkSeed = options.check.walkSeed;
  eo.toolVersion = kToolVersion;
  eo.uncertified = options.uncertified;
  codegen::Emitted emitted = codegen::emit(*built->mission, *built->translation, built->sources, *report, eo);
  if (!emitted.certified) {
    std::cout << "\nnot proven:\n";
    for (const std::string& u : emitted.unproven) std::cout << "  " << u << "\n";
    if (!options.uncertified) {
      std::cout << "emit: refused: nothing written (--uncertified writes the programs anyway, marked as uncertified)\n";
      return kViolated;
    }
  }
  std::string error;
  if (!writeTree(options.out, emitted.files, error)) {
    std::cerr << errorPrefix() << error << "\n";
    return kBadInput;
  }
  std::size_t rows = 0;
  for (const runtime::RobotTable& r : emitted.tables.robots) {
    for (const runtime::PlanTable& p : r.plans) rows += p.rows.size();
  }
  std::cout << "\nemitted " << emitted.files.size() << " files into " << options.out << ": " << emitted.tables.robots.size()
            << " robot programs, " << rows << " table rows; "
            << (emitted.certified ? "certified (every property and every buffer bound proven)"
                                  : "UNCERTIFIED (--uncertified: not everything is proven; every file says so)")
            << "\n";
  return kOk;
}

}  // namespace semo::cli
