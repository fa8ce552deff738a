#pragma once
// Helpers of the `semo-verify simulate` end-to-end tests (simulate_test.cpp,
// simulate_examples_test.cpp): run the real CLI from the source tree, read back what it wrote.
// SEMO_SOURCE_DIR, SEMO_VERIFY and SEMO_E2E_WORK come from tests/e2e/CMakeLists.txt.
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace semo_e2e {

namespace fs = std::filesystem;

struct CliRun {
  int exit = -1;
  std::string out, err;
};

// A fresh, empty folder of the build tree for one test.
inline fs::path workDir(const std::string& name) {
  fs::path dir = fs::path(SEMO_E2E_WORK) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs semo-verify with `args` (already quoted where needed), from the source tree; stderr goes
// through a file in `dir`.
inline CliRun verify(const std::string& args, const fs::path& dir) {
  const fs::path err = dir / "stderr.txt";
  const std::string command = "cd '" SEMO_SOURCE_DIR "' && '" SEMO_VERIFY "' " + args + " 2>'" + err.string() + "'";
  CliRun r;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) r.out.append(buffer.data(), n);
  const int status = pclose(pipe);
  r.exit = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = slurp(err);
  return r;
}

// The first group of `pattern` in `text` as a number; -1 when it does not match.
inline double number(const std::string& text, const std::string& pattern) {
  std::smatch m;
  if (!std::regex_search(text, m, std::regex(pattern))) return -1;
  return std::stod(m[1].str());
}

}  // namespace semo_e2e
