#pragma once
// The subcommands of semo-verify. Each returns the process exit code:
// 0 clean, 1 property violated, 2 bad input, 3 resource limit reached.
#include <optional>
#include <string>

namespace semo::cli {

enum ExitCode { kOk = 0, kViolated = 1, kBadInput = 2, kLimit = 3 };

struct ParseOptions {
  std::string mission;
  bool json = false;
};

struct LintOptions {
  std::string mission;
  std::string strategy;
  std::optional<std::string> robotsDir;
  bool warningsAsErrors = false;
};

int runParse(const ParseOptions& options);
int runLint(const LintOptions& options);

}  // namespace semo::cli
