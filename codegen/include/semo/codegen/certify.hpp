#pragma once
// `semo-verify certify DIR` (specs/certificate.md): re-validates a tree emit wrote, trusting none of
// it. The inputs the certificate names must still have their SHA-256; every file it lists must have
// its SHA-256; the mission is loaded and translated again from the inputs, projected again onto each
// robot, and the tables in the generated sources, read back without a compiler, must equal that
// projection (one row per rule of each robot's program, the same guards and effects), every other
// generated file must be exactly what emit writes for it. `recheck` also verifies the mission again
// and compares every verdict, and the whole certificate, with the one in DIR.
#include <cstdint>
#include <string>
#include <vector>

#include "semo/frontend/diagnostics.hpp"
#include "semo/frontend/source.hpp"

namespace semo::codegen {

struct CertifyFinding {
  enum class Kind : std::uint8_t {
    Input,        // an input changed since emit, or cannot be read
    File,         // a generated file is missing or its SHA-256 is not the certificate's
    Table,        // a table differs from the projection (or does not read)
    Text,         // a generated file's text is not what emit writes for these tables
    Model,        // the model built again is not the certified one (fingerprint)
    Verdict,      // --recheck: a verdict, or the certificate, differs from a new verification's
  };
  Kind kind = Kind::File;
  SourceRange at;        // into the SourceManager certify read the files with, when the finding has a place
  std::string file;      // relative to DIR (or the input's path)
  std::string message;
  std::string irRule;    // a table row's IR rule, when it is about one
};
const char* findingKindName(CertifyFinding::Kind k);

struct CertifyReport {
  bool readable = false;  // the certificate could be read (else: bad input, diagnostics printed)
  bool certified = false; // what the certificate says
  std::string mission, fingerprint;
  std::size_t inputs = 0, files = 0, robots = 0, rows = 0, programRules = 0;
  bool rechecked = false;
  std::vector<CertifyFinding> findings;
  // Files in DIR the certificate does not list (build folders aside): the user's own, such as
  // user_tasks.cmake and the tasks it adds. Not an error, but not covered by the certificate either.
  std::vector<std::string> notCovered;
  // 0 valid and certified, 1 a finding, 2 the certificate cannot be read, 3 valid but uncertified.
  int exitCode = 2;
};

struct CertifyOptions {
  bool recheck = false;
  std::string toolVersion;  // this tool's: --recheck compares the certificate byte for byte, so it must be the same tool
};

// Reads DIR/certificate.json and checks everything it says. Inputs are found at the paths the
// certificate records, relative to the current folder (where emit ran). Every file read goes into
// `sources` (findings point there); problems reading the certificate itself go to `diags`.
CertifyReport certify(const std::string& dir, const CertifyOptions& options, SourceManager& sources, DiagnosticEngine& diags);

}  // namespace semo::codegen
