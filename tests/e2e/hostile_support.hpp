#pragma once
// What the hostile-input tests share (hostile_inputs_test.cpp, hostile_outputs_test.cpp): running
// semo-verify with a time bound, a run's folder with its inputs copied in and a snapshot of every
// file in it, the checks every case makes, and the generated inputs.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_run.hpp"


namespace hostile {

namespace fs = std::filesystem;

// A run is killed after this long, and must have finished well within it (a release build takes
// well under a second for every case; the sanitizer build about ten times that).
constexpr double kTimeoutSeconds = 60;
// How wide and how deep the generated inputs are.
constexpr std::size_t kHuge = 100'000;

// ---- running semo-verify ------------------------------------------------------------------------

struct Outcome {
  int exit = -1;    // the exit code, when it exited
  int signal = 0;   // the signal that ended it, when one did
  bool timedOut = false;
  double seconds = 0;
  std::string out, err;
};

using semo::e2e::slurp;

inline void writeFile(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << text;
}

// Runs semo-verify with `args` (no shell: every argument as it is) from the source tree, stdout and
// stderr into files of `logs`, killed after kTimeoutSeconds. Outside a sanitizer build its address
// space is limited (8 GiB), so that a reader whose memory runs away fails here (std::bad_alloc, a
// signal) instead of taking the machine's memory.
inline Outcome run(const std::vector<std::string>& args, const fs::path& logs) {
  fs::create_directories(logs);
  const fs::path outFile = logs / "stdout.txt", errFile = logs / "stderr.txt";
  std::vector<std::string> argv{SEMO_VERIFY};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> cargv;
  for (std::string& a : argv) cargv.push_back(a.data());
  cargv.push_back(nullptr);
  const auto started = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    if (!SEMO_HOSTILE_SANITIZED) {
      const rlimit memory{8ull << 30, 8ull << 30};
      setrlimit(RLIMIT_AS, &memory);
    }
    const rlimit noCore{0, 0};
    setrlimit(RLIMIT_CORE, &noCore);
    const int out = open(outFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = open(errFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (out < 0 || err < 0 || chdir(SEMO_SOURCE_DIR) != 0) _exit(126);
    dup2(out, STDOUT_FILENO);
    dup2(err, STDERR_FILENO);
    execv(cargv[0], cargv.data());
    _exit(127);
  }
  Outcome o;
  if (pid < 0) return o;
  int status = 0;
  for (;;) {
    const pid_t done = waitpid(pid, &status, WNOHANG);
    o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (done == pid) break;
    if (o.seconds > kTimeoutSeconds) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      o.timedOut = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (WIFEXITED(status)) o.exit = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) o.signal = WTERMSIG(status);
  o.out = slurp(outFile);
  o.err = slurp(errFile);
  return o;
}

// ---- the run's folder: inputs copied in, and a snapshot of everything in it --------------------

// Every entry under `root`: a file's content, a symlink's target, or "<folder>".
using Snapshot = std::map<std::string, std::string>;

inline Snapshot snapshot(const fs::path& root) {
  Snapshot s;
  for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator(); ++it) {
    const std::string name = fs::relative(it->path(), root).string();
    if (it->is_symlink()) s[name] = "<symlink to " + fs::read_symlink(it->path()).string() + ">";
    else if (it->is_directory()) s[name] = "<folder>";
    else s[name] = slurp(it->path());
  }
  return s;
}

// What differs between two snapshots, in words (empty when nothing does).
inline std::string differences(const Snapshot& before, const Snapshot& after) {
  std::string out;
  for (const auto& [name, content] : before) {
    const auto it = after.find(name);
    if (it == after.end()) out += "  removed: " + name + "\n";
    else if (it->second != content) out += "  changed: " + name + "\n";
  }
  for (const auto& [name, content] : after) {
    if (!before.contains(name)) out += "  added: " + name + "\n";
  }
  return out;
}

inline const fs::path kSource = SEMO_SOURCE_DIR;

// A fresh folder for one test: `in/` holds the inputs (the run may not change anything there),
// `log/` the runs' stdout and stderr. The inputs: the robots' URDF files, two missions with their
// strategies (the strategies name the URDF files as ../robots/NAME.urdf), swarm3's world, an IR
// model, a task graph and an SDF3 graph.
struct Work {
  fs::path root, in, log;

  explicit Work(const std::string& name) {
    root = fs::path(SEMO_E2E_WORK) / name;
    fs::remove_all(root);
    in = root / "in";
    log = root / "log";
    fs::create_directories(in / "robots");
    fs::create_directories(in / "missions");
    fs::create_directories(log);
    for (const auto& e : fs::directory_iterator(kSource / "specs/robots")) fs::copy_file(e.path(), in / "robots" / e.path().filename());
    fs::copy_file(kSource / "specs/defects/lone_lidar.semo", mission());
    fs::copy_file(kSource / "specs/defects/lone_lidar_fixed.semo", in / "missions/lone_lidar_fixed.semo");
    fs::copy_file(kSource / "specs/defects/strategy.xml", strategy());
    fs::copy_file(kSource / "specs/examples/swarm/swarm3.semo", swarm());
    fs::copy_file(kSource / "specs/examples/swarm/swarm3.world.json", world());
    std::string swarmStrategy = slurp(kSource / "specs/examples/swarm/strategy.xml");
    swarmStrategy = std::regex_replace(swarmStrategy, std::regex(R"(\.\./\.\./robots/)"), "../robots/");
    writeFile(swarmStrategy_(), swarmStrategy);
    fs::copy_file(kSource / "tests/e2e/ir/mutex_bug.ir", ir());
    fs::copy_file(kSource / "tests/e2e/sdf/taskgraph_drive.json", taskGraph());
    fs::copy_file(kSource / "specs/benchmarks/sdf3/samplerate.xml", sdf3());
    fs::copy_file(kSource / "specs/examples/quantitative/broadcast.ir", at("broadcast.ir"));
  }

  [[nodiscard]] std::string mission() const { return (in / "missions/lone_lidar.semo").string(); }
  [[nodiscard]] std::string fixedMission() const { return (in / "missions/lone_lidar_fixed.semo").string(); }
  [[nodiscard]] std::string strategy() const { return (in / "missions/strategy.xml").string(); }
  [[nodiscard]] std::string swarm() const { return (in / "missions/swarm3.semo").string(); }
  [[nodiscard]] std::string swarmStrategy() const { return swarmStrategy_().string(); }
  [[nodiscard]] std::string world() const { return (in / "missions/swarm3.world.json").string(); }
  [[nodiscard]] std::string urdf() const { return (in / "robots/turtlebot3_burger.urdf").string(); }
  [[nodiscard]] std::string ir() const { return (in / "mutex_bug.ir").string(); }
  [[nodiscard]] std::string taskGraph() const { return (in / "taskgraph_drive.json").string(); }
  [[nodiscard]] std::string sdf3() const { return (in / "samplerate.xml").string(); }
  [[nodiscard]] std::string at(const std::string& relative) const { return (in / relative).string(); }

  // A counterexample of the mission (check --trace-out), for show and replay.
  std::string trace() {
    const std::string path = at("trace.json");
    if (!fs::exists(path)) {
      const Outcome o = run({"check", mission(), "--strategy", strategy(), "--trace-out", path}, log);
      EXPECT_EQ(o.exit, 1) << o.err;
    }
    return path;
  }

 private:
  [[nodiscard]] fs::path swarmStrategy_() const { return in / "missions/swarm_strategy.xml"; }
};

// ---- what every case checks -------------------------------------------------------------------

enum class Where {
  Caret,       // file:line:col: error: ..., then the source line and a caret under the column
  Position,    // file:line:col: error: ... (an empty file has no line to show)
  NoPosition,  // a clear "error:" line: there is no position (a missing file, a folder)
};

inline std::string regexQuoted(const std::string& text) {
  static const std::regex special(R"([.^$|()\[\]{}*+?\\])");
  return std::regex_replace(text, special, R"(\$&)");
}

// The case must be refused: exit code 2, not by a signal, within the bound, `diagnostic` (a regular
// expression) in stderr, in the form `where` says for the file named `file` (its name), and nothing
// in the test's `in/` folder changed.
inline Outcome refused(Work& w, const std::vector<std::string>& args, const std::string& diagnostic, Where where = Where::Caret,
                const std::string& file = "") {
  std::string shown;
  for (const std::string& a : args) shown += (shown.empty() ? "" : " ") + (a.size() > 200 ? a.substr(0, 200) + "..." : a);
  SCOPED_TRACE("semo-verify " + shown);
  const Snapshot before = snapshot(w.in);
  const Outcome o = run(args, w.log);
  const std::string err = o.err.size() > 3000 ? o.err.substr(0, 3000) + "\n[...]" : o.err;
  EXPECT_FALSE(o.timedOut) << "still running after " << kTimeoutSeconds << " s";
  EXPECT_EQ(o.signal, 0) << "killed by signal " << o.signal << " (" << strsignal(o.signal) << ")\n" << err;
  EXPECT_LT(o.seconds, kTimeoutSeconds);
  EXPECT_EQ(o.exit, 2) << err;
  EXPECT_TRUE(std::regex_search(o.err, std::regex(diagnostic))) << "expected /" << diagnostic << "/ in:\n" << err;
  const std::string name = regexQuoted(file);
  switch (where) {
    case Where::Caret:
      EXPECT_TRUE(std::regex_search(o.err, std::regex(name + ":[0-9]+:[0-9]+: error: [^\n]*\n[^\n]+\n[ \t]*\\^")))
          << "expected '" << file << ":LINE:COL: error: ...', the line and a caret in:\n" << err;
      break;
    case Where::Position:
      EXPECT_TRUE(std::regex_search(o.err, std::regex(name + ":[0-9]+:[0-9]+: error: "))) << "expected '" << file << ":LINE:COL: error:' in:\n"
                                                                                         << err;
      break;
    case Where::NoPosition: EXPECT_TRUE(std::regex_search(o.err, std::regex("(^|\n)[^\n]*error: "))) << err; break;
  }
  EXPECT_EQ(differences(before, snapshot(w.in)), "") << "the run changed its folder";
  return o;
}

// ---- generated text -----------------------------------------------------------------------------

inline std::string repeat(const std::string& s, std::size_t n) {
  std::string out;
  out.reserve(s.size() * n);
  for (std::size_t i = 0; i < n; ++i) out += s;
  return out;
}

// Pseudo-random bytes, the same on every run, from 0x7f 0x80 0x81 NUL on.
inline std::string garbage(std::size_t n) {
  std::string out(n, '\0');
  std::uint32_t x = 12345;
  for (std::size_t i = 0; i < n; ++i) {
    x = x * 1103515245u + 12345u;
    out[i] = static_cast<char>((x >> 16) & 0xff);
  }
  // No line break before the NUL: it is at line 1, column 4.
  out[0] = '\x7f', out[1] = '\x80', out[2] = '\x81', out[3] = '\0';
  return out;
}

// Bytes that are not UTF-8: a lone continuation byte, an overlong form, a surrogate, 0xFF.
inline const std::string kBadUtf8 = "\x80\xc0\xaf\xed\xa0\x80\xff\xfe";

// A file of megabytes: `lines` comment lines (each `comment` followed by 78 x), then `tail`.
inline std::string megabytes(const std::string& comment, const std::string& end, std::size_t lines, const std::string& tail) {
  return repeat(comment + std::string(78, 'x') + end + "\n", lines) + tail;
}

}  // namespace hostile
