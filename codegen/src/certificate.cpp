// certificate.json (specs/certificate.md): what was proven, by which engine and proof, under which
// assumptions; the SHA-256 of every input and every generated file; where every table row and
// function comes from. Members in a fixed order, so the same run writes the same bytes.
#include "certificate.hpp"

#include <nlohmann/json.hpp>

#include "semo/checker/fingerprint.hpp"
#include "semo/codegen/cpp_tables.hpp"
#include "semo/sdf/consistency.hpp"

namespace semo::codegen {

namespace {

using OrderedJson = nlohmann::ordered_json;

std::string fraction(const sdf::Period& p) { return std::to_string(p.num) + (p.den == 1 ? "" : "/" + std::to_string(p.den)); }

OrderedJson boundsJson(const sdf::Graph& g, const sdf::ChosenBounds& b) {
  OrderedJson caps = OrderedJson::object();
  for (std::size_t c = 0; c < g.channels.size(); ++c) {
    if (!g.channels[c].selfLoop()) caps[g.channels[c].name] = b.capacities[c];
  }
  return OrderedJson{{"total", b.total},
              {"periodMicros", fraction(b.period)},
              {"capacities", caps},
              {"schedule", sdf::scheduleText(g, b.schedule)},
              {"noOverflowNoUnderflow", std::string(sdf::proofStatusName(b.safety)) + " (Z3, any number of iterations)"},
              {"minimal", std::string(sdf::proofStatusName(b.minimality)) + " (Z3: one token less on any channel deadlocks, or the exact period grows)"}};
}

OrderedJson taskGraphsJson(const checker::Report& report) {
  OrderedJson robots = OrderedJson::array();
  for (const checker::TaskGraphReport& r : report.taskGraphs) {
    OrderedJson scenarios = OrderedJson::array();
    for (const sdf::ScenarioAnalysis& a : r.analysis.scenarios) {
      OrderedJson s = {{"scenario", a.scenario}, {"sound", a.sound()}};
      if (a.iteration.deadlockFree && a.unbounded.error.empty()) s["periodMicros"] = fraction(a.unbounded.period);
      if (a.bounds.haveBounds) {
        s["deadlockFreeBounds"] = boundsJson(a.graph, a.bounds.deadlockFree);
        s["maxThroughputBounds"] = boundsJson(a.graph, a.bounds.maxThroughput);
      }
      scenarios.push_back(s);
    }
    OrderedJson caps = OrderedJson::object();
    for (std::size_t c = 0; c < r.graph.channels.size() && c < r.analysis.capacities.size(); ++c) {
      if (r.analysis.capacities[c] > 0) caps[r.graph.channels[c].name] = r.analysis.capacities[c];
    }
    robots.push_back({{"robot", r.graph.robot}, {"tasks", r.graph.tasks.size()}, {"channels", r.graph.channels.size()},
                      {"capacities", caps}, {"scenarios", scenarios}});
  }
  return OrderedJson{{"assumptions", report.taskGraphAssumptions}, {"robots", robots}};
}

OrderedJson propertiesJson(const checker::Report& report) {
  OrderedJson out = OrderedJson::array();
  for (const checker::PropertyVerdict& p : report.properties) {
    OrderedJson j = {{"name", p.name},
              {"kind", checker::propertyKindName(p.kind)},
              {"verdict", checker::verdictName(p.verdict)},
              {"engine", p.engine},
              {"proof", checker::proofKindName(p.proof)}};
    if (p.proof == checker::ProofKind::KInduction) j["k"] = p.k;
    if (p.proof == checker::ProofKind::Ic3) j["conjuncts"] = p.conjuncts;
    // The coverage in the words check prints, without its pointer to the lines above (the
    // assumptions are the model's, in "model").
    std::string coverage = p.coverage;
    for (const std::string cut : {", under the assumptions above", " under the assumptions above"}) {
      if (const std::size_t at = coverage.find(cut); at != std::string::npos) coverage.erase(at, cut.size());
    }
    j["coverage"] = coverage;
    j["origin"] = p.origin;
    out.push_back(j);
  }
  return out;
}

OrderedJson verificationJson(const checker::Report& report) {
  const checker::SearchResult& s = report.safety;
  OrderedJson j = {{"engine", report.engine == checker::Engine::Smt ? "smt" : report.engine == checker::Engine::Counting ? "counting" : "explicit"}};
  if (!report.engineReason.empty()) j["engineChoice"] = report.engineReason;
  if (report.engine == checker::Engine::Smt) {
    j["bmcDepth"] = report.smt->bmcDepth;
  } else {
    j["states"] = s.states;
    j["transitions"] = s.transitions;
    j["depth"] = s.depth;
    j["symmetry"] = s.symmetry;
    j["livenessProductStates"] = report.liveness.states;
  }
  j["complete"] = s.complete && (report.engine != checker::Engine::Explicit || report.liveness.complete);
  j["exitCode"] = report.exitCode;
  return j;
}

std::string compilerName() {
#if defined(__clang__)
  return std::string("clang ") + __clang_version__;
#elif defined(__GNUC__)
  return std::string("g++ ") + __VERSION__;
#else
  return "unknown";
#endif
}

}  // namespace

std::string inputRole(const std::string& path, const EmitOptions& options) {
  if (path == options.missionPath) return "mission";
  if (path == options.strategyPath) return "strategy";
  if (path.size() >= 5 && path.compare(path.size() - 5, 5, ".urdf") == 0) return "robot";
  return "input";
}

std::vector<std::size_t> programRulesPerRobot(const Translation& translation, std::size_t robots) {
  std::vector<std::size_t> out(robots, 0);
  for (const lowering::RuleMeaning& m : translation.lowering.rules) {
    if (m.kind == lowering::RuleMeaning::Kind::ProgramStep && m.robot < robots) ++out[m.robot];
  }
  return out;
}

std::string certificateJson(const model::MissionModel& /*mission*/, const Translation& translation, const SourceManager& sources,
                            const checker::Report& report, const EmitOptions& options, const Emitted& emitted) {
  const runtime::MissionTables& t = emitted.tables;
  OrderedJson root = {{"format", "semo-certificate"}, {"version", kCertificateVersion}, {"certified", emitted.certified}};
  if (!emitted.certified) root["unproven"] = emitted.unproven;
  root["tool"] = {{"name", "semo-verify"}, {"version", options.toolVersion}, {"compiler", compilerName()}, {"z3", checker::z3Version()}};
  OrderedJson inputs = OrderedJson::array();
  for (std::size_t id = 0; id < sources.fileCount(); ++id) {
    const std::string& path = sources.path(static_cast<FileId>(id));
    inputs.push_back({{"role", inputRole(path, options)}, {"path", path}, {"sha256", checker::sha256Hex(sources.text(static_cast<FileId>(id)))}});
  }
  root["inputs"] = inputs;
  OrderedJson build = OrderedJson::object();  // how the model was built from them (certify builds it again so)
  if (!options.robotsDir.empty()) build["robots"] = options.robotsDir;
  if (options.crash) build["crash"] = *options.crash;
  if (options.loss) build["loss"] = *options.loss;
  if (options.fairLoss) build["fairLoss"] = *options.fairLoss;
  root["modelOptions"] = build;
  OrderedJson how = {{"engine", options.engine}, {"maxStates", options.maxStates}, {"symmetry", options.symmetry}, {"safetyOnly", options.safetyOnly},
              {"bmcOnly", options.bmcOnly}, {"proofTimeoutMs", options.proofTimeoutMs}};
  if (options.maxDepth != UINT32_MAX) how["maxDepth"] = options.maxDepth;
  how["liveness"] = {{"slicing", options.slicing},         {"slicesFirst", options.slicesFirst},
                     {"sliceStates", options.sliceStates}, {"symbolic", options.symbolic},
                     {"symbolicSeconds", options.symbolicSeconds}, {"coneSeconds", options.coneSeconds},
                     {"walks", options.walks},             {"seed", options.walkSeed}};
  root["verifyOptions"] = how;
  root["model"] = {{"fingerprint", report.modelFingerprint},
                   {"variables", translation.model.variables.size()},
                   {"rules", translation.model.rules.size()},
                   {"assumptions", report.assumptions}};
  root["verification"] = verificationJson(report);
  root["properties"] = propertiesJson(report);
  root["taskGraphs"] = taskGraphsJson(report);
  root["runtime"] = {{"version", options.toolVersion}, {"tablesLayout", runtime::kTablesLayout}};

  OrderedJson files = OrderedJson::array();
  OrderedJson traceMap = OrderedJson::array();
  for (const GeneratedFile& f : emitted.files) {
    files.push_back({{"path", f.path}, {"sha256", checker::sha256Hex(f.text)}});
  }
  for (const runtime::RobotTable& r : t.robots) {
    const std::string tablesFile = "robots/" + r.name + "/tables.cpp";
    const auto file = std::find_if(emitted.files.begin(), emitted.files.end(), [&](const GeneratedFile& g) { return g.path == tablesFile; });
    if (file == emitted.files.end()) continue;
    traceMap.push_back({{"file", "robots/" + r.name + "/main.cpp"}, {"function", "main"}, {"robot", r.name}, {"what", "the robot's program"}});
    traceMap.push_back({{"file", tablesFile}, {"function", "semo_mission::robot_" + r.name}, {"robot", r.name},
                        {"what", "the robot's step tables and task graph"}});
    for (const cpp::RowLine& l : cpp::rowLines(r, file->text)) {
      const runtime::Row& row = r.plans[l.plan].rows[l.row];
      OrderedJson entry = {{"file", tablesFile}, {"line", l.line}, {"robot", r.name}, {"plan", r.plans[l.plan].name}, {"row", l.row}};
      if (row.irRule == runtime::kNone) {
        entry["irRule"] = nullptr;
        entry["what"] = "stutter: a walk that changes nothing the model sees";
      } else {
        entry["irRule"] = t.rules[row.irRule].name;
        entry["label"] = t.rules[row.irRule].label;
        entry["origin"] = t.rules[row.irRule].origin;
      }
      traceMap.push_back(entry);
    }
  }
  traceMap.push_back({{"file", "mission/mission_tables.cpp"}, {"function", "semo_mission::shared"}, {"what", "the mission's shared tables"}});
  root["files"] = files;
  root["traceMap"] = traceMap;

  const std::vector<std::size_t> programRules = programRulesPerRobot(translation, t.robots.size());
  OrderedJson robots = OrderedJson::array();
  for (std::size_t r = 0; r < t.robots.size(); ++r) {
    std::size_t rows = 0, ruled = 0;
    for (const runtime::PlanTable& p : t.robots[r].plans) {
      rows += p.rows.size();
      ruled += static_cast<std::size_t>(std::count_if(p.rows.begin(), p.rows.end(), [](const runtime::Row& x) { return x.irRule != runtime::kNone; }));
    }
    robots.push_back({{"robot", t.robots[r].name}, {"programRules", programRules[r]}, {"rows", rows}, {"stutterRows", rows - ruled},
                      {"bijection", ruled == programRules[r]}});
  }
  root["translationValidation"] = {
      {"method", "the tables in the generated sources, read back without a compiler, equal the IR's projection onto each robot "
                 "recomputed from the inputs: one row per rule of the robot's program, with the same guards and effects"},
      {"robots", robots}};
  return root.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace semo::codegen
