// `certify DIR`: print what codegen::certify found (codegen/certify.hpp).
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "semo/codegen/certify.hpp"

namespace semo::cli {

int runCertify(const CertifyOptions& options) {
  SourceManager sources;
  DiagnosticEngine diags(sources);
  codegen::CertifyOptions co;
  co.recheck = options.recheck;
  co.toolVersion = kToolVersion;
  const codegen::CertifyReport report = codegen::certify(options.dir, co, sources, diags);
  diags.print(std::cerr);
  if (!report.readable) return kBadInput;

  if (options.json) {
    nlohmann::json findings = nlohmann::json::array();
    for (const codegen::CertifyFinding& f : report.findings) {
      nlohmann::json j = {{"kind", codegen::findingKindName(f.kind)}, {"file", f.file}, {"message", f.message}};
      if (f.at.begin.hasPosition()) j["line"] = f.at.begin.line, j["column"] = f.at.begin.column;
      if (!f.irRule.empty()) j["irRule"] = f.irRule;
      findings.push_back(j);
    }
    std::cout << nlohmann::json{{"dir", options.dir},
                                {"mission", report.mission},
                                {"modelFingerprint", report.fingerprint},
                                {"valid", report.findings.empty()},
                                {"certified", report.certified},
                                {"rechecked", report.rechecked},
                                {"inputs", report.inputs},
                                {"files", report.files},
                                {"robots", report.robots},
                                {"rows", report.rows},
                                {"programRules", report.programRules},
                                {"findings", findings},
                                {"notCovered", report.notCovered},
                                {"exitCode", report.exitCode}}
                     .dump(2, ' ', false, nlohmann::json::error_handler_t::replace)
              << "\n";
    return report.exitCode;
  }

  // Each finding as a diagnostic: file:line:col: error: ..., with its line and a caret.
  DiagnosticEngine findings(sources);
  for (const codegen::CertifyFinding& f : report.findings) {
    if (f.at.begin.valid()) {
      findings.error(f.at, f.message);
    } else {
      findings.error({}, f.file + ": " + f.message);
    }
  }
  findings.print(std::cout);
  std::cout << "certify: " << options.dir << " (" << report.mission << ", model " << report.fingerprint << ")\n";
  std::cout << "  inputs: " << report.inputs << " files; generated: " << report.files << " files; tables of " << report.robots << " robots, "
            << report.rows << " rows for " << report.programRules << " rules of their programs\n";
  if (!report.notCovered.empty()) {
    std::cout << "  not covered by the certificate (your own files):";
    for (const std::string& f : report.notCovered) std::cout << " " << f;
    std::cout << "\n";
  }
  if (!report.findings.empty()) {
    std::cout << "  INVALID: " << report.findings.size() << (report.findings.size() == 1 ? " finding" : " findings") << " above\n";
  } else {
    std::cout << "  valid: every SHA-256 as recorded; the tables read back equal the verified model's projection, made again from "
                 "the inputs (one row per rule of each robot's program); every other file is what emit writes"
              << (report.rechecked ? "; verified again: the same verdicts and the same certificate" : "") << "\n";
    std::cout << (report.certified ? "  certified: every property and every buffer bound proven (certificate.json)\n"
                                   : "  UNCERTIFIED: emitted with --uncertified, not everything is proven (certificate.json, \"unproven\")\n");
  }
  return report.exitCode;
}

}  // namespace semo::cli
