// certify (certify.hpp): every claim of a certificate checked again, from the inputs up.
#include "semo/codegen/certify.hpp"

#include <filesystem>

#include "certificate.hpp"
#include "semo/checker/fingerprint.hpp"
#include "semo/checker/verify.hpp"
#include "semo/codegen/cpp_tables.hpp"
#include "semo/codegen/emit.hpp"
#include "semo/codegen/project.hpp"
#include "semo/codegen/project_dataflow.hpp"
#include "semo/frontend/json_text.hpp"
#include "semo/semantics/load.hpp"
#include "semo/semantics/translate.hpp"
#include "table_schema.hpp"

namespace semo::codegen {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using Kind = CertifyFinding::Kind;

struct Certificate {
  bool certified = false;
  std::string toolVersion, fingerprint;
  struct Entry {
    std::string role, path, sha256;
  };
  std::vector<Entry> inputs, files;
  std::string mission, strategy, robotsDir;
  std::optional<int> crash;
  std::optional<std::string> loss;
  std::optional<bool> fairLoss;
  EmitOptions verify;  // engine, limits and proof timeout, as emit ran them
};

// A relative path that stays inside the tree: no root, no "..".
bool insideTree(const std::string& path) {
  const fs::path p(path);
  if (p.empty() || p.is_absolute() || p.has_root_name()) return false;
  return std::none_of(p.begin(), p.end(), [](const fs::path& part) { return part == ".."; });
}

std::optional<Certificate> readCertificate(const SourceManager& sources, FileId file, DiagnosticEngine& diags) {
  std::optional<Json> j = parseJsonFile(sources, file, diags);
  if (!j) return std::nullopt;
  const SourceRange whole{{file, 0, 0}, 1};
  auto bad = [&](const std::string& why) {
    diags.error(whole, "not a certificate semo can read: " + why);
    return std::nullopt;
  };
  if (!j->is_object() || j->value("format", Json()) != "semo-certificate") return bad("\"format\" is not \"semo-certificate\"");
  if (j->value("version", Json()) != kCertificateVersion) return bad("\"version\" is not " + std::to_string(kCertificateVersion));
  Certificate c;
  try {
    c.certified = j->at("certified").get<bool>();
    c.toolVersion = j->at("tool").at("version").get<std::string>();
    c.fingerprint = j->at("model").at("fingerprint").get<std::string>();
    for (const char* list : {"inputs", "files"}) {
      for (const Json& e : j->at(list)) {
        Certificate::Entry entry{e.value("role", ""), e.at("path").get<std::string>(), e.at("sha256").get<std::string>()};
        if (std::string(list) == "files" && !insideTree(entry.path)) return bad("the file '" + entry.path + "' lies outside the tree");
        (std::string(list) == "inputs" ? c.inputs : c.files).push_back(entry);
        if (entry.role == "mission") c.mission = entry.path;
        if (entry.role == "strategy") c.strategy = entry.path;
      }
    }
    const Json& options = j->at("modelOptions");
    c.robotsDir = options.value("robots", "");
    if (options.contains("crash")) c.crash = options.at("crash").get<int>();
    if (options.contains("loss")) c.loss = options.at("loss").get<std::string>();
    if (options.contains("fairLoss")) c.fairLoss = options.at("fairLoss").get<bool>();
    const Json& how = j->at("verifyOptions");
    c.verify.engine = how.at("engine").get<std::string>();
    c.verify.maxStates = how.at("maxStates").get<std::uint64_t>();
    c.verify.maxDepth = how.value("maxDepth", UINT32_MAX);
    c.verify.symmetry = how.at("symmetry").get<bool>();
    c.verify.safetyOnly = how.at("safetyOnly").get<bool>();
    c.verify.bmcOnly = how.at("bmcOnly").get<bool>();
    c.verify.proofTimeoutMs = how.at("proofTimeoutMs").get<unsigned>();
    if (how.contains("liveness")) {  // absent from a certificate of an earlier version: the defaults then
      const Json& l = how.at("liveness");
      c.verify.slicing = l.at("slicing").get<bool>();
      c.verify.slicesFirst = l.at("slicesFirst").get<bool>();
      c.verify.sliceStates = l.at("sliceStates").get<std::uint64_t>();
      c.verify.symbolic = l.at("symbolic").get<bool>();
      c.verify.symbolicSeconds = l.at("symbolicSeconds").get<double>();
      c.verify.coneSeconds = l.at("coneSeconds").get<double>();
      c.verify.walks = l.at("walks").get<bool>();
      c.verify.walkSeed = l.at("seed").get<std::uint64_t>();
    }
  } catch (const Json::exception& e) {
    return bad(e.what());
  }
  if (c.mission.empty() || c.strategy.empty()) return bad("it names no mission or no strategy among its inputs");
  return c;
}

class Checker {
 public:
  Checker(const std::string& dir, SourceManager& sources, CertifyReport& report) : dir_(dir), sources_(sources), report_(report) {}

  void finding(Kind kind, std::string file, std::string message, SourceRange at = {}, std::string irRule = {}) {
    report_.findings.push_back({kind, at, std::move(file), std::move(message), std::move(irRule)});
  }

  // The file at `path` (inside the tree unless `input`), loaded into sources: kNoFile when it cannot be read.
  FileId load(const std::string& path, bool input) {
    std::string why;
    const FileId id = sources_.load(input ? path : (fs::path(dir_) / path).string(), why);
    if (id == kNoFile) finding(input ? Kind::Input : Kind::File, path, input ? "cannot read this input: " + why : "missing: " + why);
    return id;
  }

  void hashes(const Certificate& c, std::vector<FileId>& files) {
    for (const Certificate::Entry& e : c.inputs) {
      const FileId id = load(e.path, true);
      if (id != kNoFile && checker::sha256Hex(sources_.text(id)) != e.sha256) {
        finding(Kind::Input, e.path, "changed since emit: its SHA-256 is not the one the certificate records");
      }
    }
    for (const Certificate::Entry& e : c.files) {
      const FileId id = load(e.path, false);
      files.push_back(id);
      if (id != kNoFile && checker::sha256Hex(sources_.text(id)) != e.sha256) {
        finding(Kind::File, e.path, "changed since emit: its SHA-256 is not the one the certificate records");
      }
    }
    report_.inputs = c.inputs.size();
    report_.files = c.files.size();
  }

  // The tables of one generated file against the projection's.
  template <class Table, class Read, class Compare>
  void tables(FileId file, const std::string& path, const char* declaration, const Table& expected, Read read, Compare compare,
              const runtime::MissionTables& all) {
    DiagnosticEngine diags(sources_);
    std::optional<cpp::Node> node = cpp::parseInitializer(sources_, file, declaration, diags);
    Table actual;
    if (node) read(*node, actual, diags);
    if (diags.hasErrors()) {
      const Diagnostic& d = diags.diagnostics().front();
      finding(Kind::Table, path, "the tables do not read: " + d.message, d.range);
      return;
    }
    const std::optional<cpp::Difference> diff = compare(expected, actual, *node);
    if (!diff) return;
    std::string message;
    std::string rule;
    if (diff->irRule != runtime::kNone && diff->irRule < all.rules.size()) {
      const runtime::RuleInfo& r = all.rules[diff->irRule];
      rule = r.name;
      message = "the row of IR rule " + r.name + " (" + r.label + ", " + r.origin + "): ";
    }
    message += diff->what.empty() ? diff->path + " is " + diff->actual + " where the verified model's projection has " + diff->expected
                                  : diff->path + " " + diff->what;
    finding(Kind::Table, path, message, diff->at, rule);
  }

  // Every generated file's text against emit's for the same tables: the first line that differs.
  void texts(const std::vector<GeneratedFile>& expected) {
    for (const GeneratedFile& g : expected) {
      const bool reported = std::any_of(report_.findings.begin(), report_.findings.end(), [&](const CertifyFinding& f) {
        return f.file == g.path && f.kind == Kind::Table;  // where the tables differ says more than the text
      });
      const FileId id = fileOf(g.path);
      if (reported || id == kNoFile) continue;
      const std::string& text = sources_.text(id);
      if (text == g.text) continue;
      std::uint32_t line = 1;
      std::size_t i = 0;
      for (; i < text.size() && i < g.text.size() && text[i] == g.text[i]; ++i) line += text[i] == '\n' ? 1 : 0;
      finding(Kind::Text, g.path, "differs from what emit writes for the verified model here (its tables may be equal, the text is not)",
              {{id, line, 1}, 1});
    }
  }

  FileId fileOf(const std::string& path) const {
    const std::string full = (fs::path(dir_) / path).string();
    for (std::size_t id = 0; id < sources_.fileCount(); ++id) {
      if (sources_.path(static_cast<FileId>(id)) == full) return static_cast<FileId>(id);
    }
    return kNoFile;
  }

 private:
  std::string dir_;
  SourceManager& sources_;
  CertifyReport& report_;
};

}  // namespace

const char* findingKindName(CertifyFinding::Kind k) {
  switch (k) {
    case Kind::Input: return "input";
    case Kind::File: return "file";
    case Kind::Table: return "table";
    case Kind::Text: return "text";
    case Kind::Model: return "model";
    case Kind::Verdict: return "verdict";
  }
  return "file";
}

CertifyReport certify(const std::string& dir, const CertifyOptions& options, SourceManager& sources, DiagnosticEngine& diags) {
  CertifyReport report;
  std::string why;
  const FileId certFile = sources.load((fs::path(dir) / "certificate.json").string(), why);
  if (certFile == kNoFile) {
    diags.error({}, "cannot read " + (fs::path(dir) / "certificate.json").string() + ": " + why + " (is it a folder emit wrote?)");
    return report;
  }
  std::optional<Certificate> c = readCertificate(sources, certFile, diags);
  if (!c) return report;
  report.readable = true;
  report.certified = c->certified;
  report.mission = c->mission;
  report.fingerprint = c->fingerprint;
  Checker check(dir, sources, report);
  std::vector<FileId> files;
  check.hashes(*c, files);

  // The model again, from the inputs as they are now.
  SourceManager inputs;
  DiagnosticEngine inputDiags(inputs);
  std::optional<model::MissionModel> mission =
      loadMission({c->mission, c->strategy, c->robotsDir.empty() ? std::nullopt : std::optional<std::string>(c->robotsDir)}, inputs, inputDiags);
  std::optional<Translation> translation;
  if (mission) translation = translateMission(*mission, {c->crash, c->loss, c->fairLoss, {}}, inputs, inputDiags);
  if (!translation) {
    check.finding(Kind::Model, c->mission, "the inputs no longer make a model: " + (inputDiags.diagnostics().empty() ? std::string("?") : inputDiags.format(inputDiags.diagnostics().front())));
  } else if (checker::modelFingerprint(translation->model) != c->fingerprint) {
    check.finding(Kind::Model, c->mission, "the model built from the inputs is not the certified one (fingerprint " +
                                               checker::modelFingerprint(translation->model) + ", certificate " + c->fingerprint + ")");
  }
  if (translation) {
    // The projection again, with each robot's dataflow from its task graph's analysis (the schedules'
    // safety: the capacities are chosen before any proof, so they are emit's).
    runtime::MissionTables expected = project(*mission, *translation, inputs);
    expected.modelFingerprint = checker::modelFingerprint(translation->model);
    DiagnosticEngine dataflowDiags(inputs);
    projectDataflow(*mission, expected, dataflowDiags);
    const std::vector<std::size_t> programRules = programRulesPerRobot(*translation, expected.robots.size());
    runtime::MissionTables shared = expected;
    for (runtime::RobotTable& r : shared.robots) r = schema::robotIdentity(r);
    if (const FileId f = check.fileOf("mission/mission_tables.cpp"); f != kNoFile) {
      check.tables(f, "mission/mission_tables.cpp", "static const MissionTables tables", shared, cpp::readMission, cpp::compareMission, expected);
    }
    for (std::size_t r = 0; r < expected.robots.size(); ++r) {
      const std::string path = "robots/" + expected.robots[r].name + "/tables.cpp";
      const FileId f = check.fileOf(path);
      if (f == kNoFile) {
        if (std::none_of(c->files.begin(), c->files.end(), [&](const Certificate::Entry& e) { return e.path == path; })) {
          check.finding(Kind::File, path, "robot " + expected.robots[r].name + " of the mission has no tables in the tree");
        }
        continue;
      }
      check.tables(f, path, "static const RobotTable table", expected.robots[r], cpp::readRobot, cpp::compareRobot, expected);
      ++report.robots;
      report.programRules += programRules[r];
      for (const runtime::PlanTable& p : expected.robots[r].plans) report.rows += p.rows.size();
    }
    EmitOptions eo;
    eo.missionPath = c->mission;
    eo.strategyPath = c->strategy;
    eo.toolVersion = c->toolVersion;
    std::vector<GeneratedFile> regenerated = generateSources(expected, eo, c->certified);
    for (const GeneratedFile& g : regenerated) {
      if (std::none_of(c->files.begin(), c->files.end(), [&](const Certificate::Entry& e) { return e.path == g.path; })) {
        check.finding(Kind::File, g.path, "emit writes this file for the verified model, but the certificate does not list it");
      }
    }
    check.texts(regenerated);

    if (options.recheck) {
      // Everything again: the verification, then the whole tree, certificate included, byte for byte.
      report.rechecked = true;
      const EmitOptions& how = c->verify;
      checker::VerifyOptions vo;
      vo.engine = how.engine == "smt"        ? checker::Engine::Smt
                  : how.engine == "auto"     ? checker::Engine::Auto
                  : how.engine == "counting" ? checker::Engine::Counting
                                             : checker::Engine::Explicit;
      vo.limits.maxStates = how.maxStates;
      vo.limits.maxDepth = how.maxDepth;
      vo.limits.symmetry = how.symmetry;
      vo.limits.threads = checker::defaultThreads();
      vo.safetyOnly = how.safetyOnly;
      vo.smt.induction = vo.smt.ic3 = !how.bmcOnly;
      vo.bounds.timeoutMs = how.proofTimeoutMs;
      vo.liveness.slicing = how.slicing;
      vo.liveness.slicesFirst = how.slicesFirst;
      vo.liveness.sliceStates = how.sliceStates;
      vo.liveness.symbolic = how.symbolic;
      vo.liveness.symbolicSeconds = how.symbolicSeconds;
      vo.liveness.coneSeconds = how.coneSeconds;
      vo.liveness.walks = how.walks;
      vo.liveness.walkSeed = how.walkSeed;
      vo.taskGraphs = true;
      vo.crashOverride = c->crash;
      vo.smt.lemmas = translation->lowering.countDefinitions;  // as emit verifies: the counts' definitions, for smt and counting
      vo.countedTeamsFrom = TranslationOptions{}.countTeamsAbove + 1;
      DiagnosticEngine verifyDiags(inputs);
      std::optional<checker::Report> again = checker::verify(translation->model, &*mission, vo, verifyDiags);
      if (again) {
        const bool certifiedNow = again->unproven().empty();
        if (certifiedNow != c->certified) {
          check.finding(Kind::Verdict, "certificate.json",
                        std::string("the certificate says ") + (c->certified ? "certified" : "uncertified") + ", a new verification says " +
                            (certifiedNow ? "everything is proven" : "not everything is proven: " + again->unproven().front()));
        }
        eo = how;
        eo.missionPath = c->mission;
        eo.strategyPath = c->strategy;
        eo.robotsDir = c->robotsDir;
        eo.crash = c->crash;
        eo.loss = c->loss;
        eo.fairLoss = c->fairLoss;
        eo.toolVersion = options.toolVersion;
        const Emitted fresh = emit(*mission, *translation, inputs, *again, eo);
        if (fresh.files.back().text != sources.text(certFile)) {
          check.finding(Kind::Verdict, "certificate.json", "differs from the certificate a new verification writes (tool " + options.toolVersion +
                                                               ", certificate from " + c->toolVersion + ")");
        }
      }
    }
  }
  // What else is there: the user's own files (a build folder, one holding a CMakeCache.txt, aside).
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (it->is_directory(ec) && fs::exists(it->path() / "CMakeCache.txt", ec)) {
      it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file(ec)) continue;
    const std::string rel = fs::relative(it->path(), dir, ec).generic_string();
    if (rel == "certificate.json" || std::any_of(c->files.begin(), c->files.end(), [&](const Certificate::Entry& e) { return e.path == rel; })) continue;
    report.notCovered.push_back(rel);
  }
  std::sort(report.notCovered.begin(), report.notCovered.end());
  report.exitCode = !report.findings.empty() ? 1 : report.certified ? 0 : 3;
  return report;
}

}  // namespace semo::codegen
