// Hostile inputs, end to end: every reader of semo-verify (missions, strategies, URDF files, IR, task
// graphs, SDF3 graphs, counterexample traces, worlds) fed what an attacker or a broken tool would give
// it, generated here at run time (nothing large is stored): nesting far past every documented limit,
// a hundred thousand items on one line, files of megabytes, empty files, binary garbage, invalid
// UTF-8, missing files and folders given as files; and every output option of every command pointed
// onto an input (directly, through a symlink, through dir/../file, through a hard link), into a
// missing folder and onto a folder. The project's rule: bad input never crashes and never
// half-writes; it gets `file:line:col: error: ...` with a caret where a position exists, exit code 2
// and no output files; no output ever replaces an input; readers limit nesting; cost stays
// near-linear in the input's size. Each case checks all of it: the exit code, the diagnostic, that
// the process was not killed by a signal, that it finished within the bound, and that no file of the
// run's folder changed, appeared or disappeared.
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

namespace {

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

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void writeFile(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << text;
}

// Runs semo-verify with `args` (no shell: every argument as it is) from the source tree, stdout and
// stderr into files of `logs`, killed after kTimeoutSeconds. Outside a sanitizer build its address
// space is limited (8 GiB), so that a reader whose memory runs away fails here (std::bad_alloc, a
// signal) instead of taking the machine's memory.
Outcome run(const std::vector<std::string>& args, const fs::path& logs) {
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

Snapshot snapshot(const fs::path& root) {
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
std::string differences(const Snapshot& before, const Snapshot& after) {
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

const fs::path kSource = SEMO_SOURCE_DIR;

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

std::string regexQuoted(const std::string& text) {
  static const std::regex special(R"([.^$|()\[\]{}*+?\\])");
  return std::regex_replace(text, special, R"(\$&)");
}

// The case must be refused: exit code 2, not by a signal, within the bound, `diagnostic` (a regular
// expression) in stderr, in the form `where` says for the file named `file` (its name), and nothing
// in the test's `in/` folder changed.
Outcome refused(Work& w, const std::vector<std::string>& args, const std::string& diagnostic, Where where = Where::Caret,
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

std::string repeat(const std::string& s, std::size_t n) {
  std::string out;
  out.reserve(s.size() * n);
  for (std::size_t i = 0; i < n; ++i) out += s;
  return out;
}

// Pseudo-random bytes, the same on every run, from 0x7f 0x80 0x81 NUL on.
std::string garbage(std::size_t n) {
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
const std::string kBadUtf8 = "\x80\xc0\xaf\xed\xa0\x80\xff\xfe";

// A file of megabytes: `lines` comment lines (each `comment` followed by 78 x), then `tail`.
std::string megabytes(const std::string& comment, const std::string& end, std::size_t lines, const std::string& tail) {
  return repeat(comment + std::string(78, 'x') + end + "\n", lines) + tail;
}

// ---- missions (.semo) ---------------------------------------------------------------------------

const std::string kTeam = "Survey: TurtlebotBurger mapper, Ev3Robot tracker[2]\n";

// `lint` on a mission written to in/hostile.semo (against the seeded defects' strategy).
void missionRefused(Work& w, const std::string& text, const std::string& diagnostic, Where where = Where::Caret) {
  const std::string path = w.at("hostile.semo");
  writeFile(path, text);
  refused(w, {"lint", path, "--strategy", w.strategy()}, diagnostic, where, "hostile.semo");
}

TEST(HostileMission, NestingFarPastTheLimit) {
  Work w("mission_depth");
  const std::string service = "Survey.Explore.Map { ";
  missionRefused(w, kTeam + service + "if (" + repeat("(", kHuge) + "Survey.x == 1" + repeat(")", kHuge) + ") scanArea() }\n",
                 "hostile\\.semo:2:[0-9]+: error: nested too deeply \\(limit 256\\)");
  missionRefused(w, kTeam + service + repeat("if (Survey.x == 1) { ", kHuge) + "scanArea()" + repeat(" }", kHuge) + " }\n",
                 "hostile\\.semo:2:[0-9]+: error: nested too deeply \\(limit 256\\)");
  missionRefused(w, kTeam + service + "if (" + repeat("not ", kHuge) + "Survey.x == 1) scanArea() }\n",
                 "hostile\\.semo:2:[0-9]+: error: nested too deeply \\(limit 256\\)");
  missionRefused(w, kTeam + service + repeat("[[ group (capable of LaserDistanceSensor) { ", kHuge) + "scanArea()" + repeat(" } ]]", kHuge) + " }\n",
                 "hostile\\.semo:2:[0-9]+: error: group blocks '\\[\\[ \\]\\]' cannot be nested");
  missionRefused(w, kTeam + "verify { property p: always " + repeat("(", kHuge) + "mapper.alive" + repeat(")", kHuge) + " }\n",
                 "hostile\\.semo:2:[0-9]+: error: nested too deeply \\(limit 256\\)");
  missionRefused(w, kTeam + "verify { property p: " + repeat("always eventually ", kHuge) + "mapper.alive }\n",
                 "hostile\\.semo:2:[0-9]+: error: nested too deeply \\(limit 256\\)");
  // Unclosed: a hundred thousand braces opened and never closed.
  missionRefused(w, kTeam + service + repeat("{", kHuge) + "\n", "hostile\\.semo:2:[0-9]+: error: ");
}

TEST(HostileMission, AHundredThousandItemsOnOneLine) {
  Work w("mission_width");
  // A condition of 100,000 terms, the last undefined: the error is placed at its column.
  std::string terms;
  for (std::size_t i = 0; i < kHuge; ++i) terms += "mapper.alive and ";
  missionRefused(w, kTeam + "Survey.Explore.Map { if (" + terms + "nosuch.alive) scanArea() }\n",
                 "hostile\\.semo:2:1700026: error: [^\n]*nosuch");
  // 100,000 arguments.
  missionRefused(w, kTeam + "Survey.Explore.Map { navigate(" + repeat("\"a\", ", kHuge) + "\"a\") }\n", "hostile\\.semo:2:[0-9]+: error: ");
  // 100,000 statements on one line, each an error: every diagnostic shows a window of the line, not
  // the whole of it (a megabyte under each of 100,000 errors would be 100 GB).
  const std::string path = w.at("hostile.semo");
  writeFile(path, kTeam + "Survey.Explore.Map { " + repeat("nosuch() ", kHuge) + "}\n");
  const Outcome o = refused(w, {"lint", path, "--strategy", w.strategy()}, "hostile\\.semo:2:22: error: undefined service 'nosuch'",
                            Where::Caret, "hostile.semo");
  EXPECT_LT(o.err.size(), kHuge * 1000) << "each error's line is a window, not the whole line";
}

TEST(HostileMission, SizeEmptyGarbageAndInvalidUtf8) {
  Work w("mission_size");
  missionRefused(w, megabytes("# ", "", 40000, kTeam + "Survey.Explore.Map { scanArea( }\n"), "hostile\\.semo:40002:[0-9]+: error: ");
  missionRefused(w, "", "hostile\\.semo:1:1: error: the mission is empty", Where::Position);
  missionRefused(w, garbage(1 << 20), "hostile\\.semo:1:1: error: ");
  missionRefused(w, "Survey: Turtlebot" + kBadUtf8 + "Burger mapper\n", "hostile\\.semo:1:18: error: unexpected character byte 0x80");
  missionRefused(w, "Survey: TurtlebotBurger mapper\n# a comment " + kBadUtf8 + "\nSurvey.Explore.Map { scan" + kBadUtf8 + "Area() }\n",
                 "hostile\\.semo:3:26: error: unexpected character byte 0x80");
  missionRefused(w, kTeam + "Survey.Explore.Map {" + '\0' + " scanArea() }\n", "hostile\\.semo:2:21: error: unexpected character byte 0x00");
  // Not UTF-8 in a string: `parse --json` once died of it (nlohmann::json refuses to write it).
  const std::string path = w.at("hostile.semo");
  writeFile(path, kTeam + "Survey.Explore.Map { navigate(\"fr" + kBadUtf8 + "ontier\") }\n");
  for (const std::vector<std::string>& args : {std::vector<std::string>{"parse", path, "--json"}, std::vector<std::string>{"lint", path, "-s", w.strategy()},
                                               std::vector<std::string>{"check", path, "-s", w.strategy(), "--json"}}) {
    refused(w, args, "hostile\\.semo:2:34: error: a string must be UTF-8 text: byte 0x80 is not", Where::Caret, "hostile.semo");
  }
}

TEST(HostileMission, MissingFileAndAFolder) {
  Work w("mission_path");
  refused(w, {"lint", w.at("no_such.semo"), "--strategy", w.strategy()}, "error: cannot open '[^']*no_such\\.semo'", Where::NoPosition);
  refused(w, {"parse", w.at("no_such.semo")}, "error: cannot open '[^']*no_such\\.semo'", Where::NoPosition);
  fs::create_directories(w.at("folder.semo"));
  refused(w, {"lint", w.at("folder.semo"), "--strategy", w.strategy()}, "error: cannot read '[^']*folder\\.semo': it is a folder, not a file",
          Where::NoPosition);
  refused(w, {"check", w.at("folder.semo"), "--strategy", w.strategy()}, "error: cannot read '[^']*folder\\.semo': it is a folder",
          Where::NoPosition);
  refused(w, {"simulate", w.at("missions"), "--strategy", w.swarmStrategy(), "--world", w.world()}, "error: cannot read '[^']*missions': it is a folder",
          Where::NoPosition);
}

// ---- strategies (--strategy, XML) ---------------------------------------------------------------

const std::string kXmlHead = "<?xml version=\"1.0\"?>\n";

void strategyRefused(Work& w, const std::string& text, const std::string& diagnostic, Where where = Where::Caret) {
  const std::string path = w.at("missions/hostile.xml");
  writeFile(path, text);
  refused(w, {"lint", w.mission(), "--strategy", path}, diagnostic, where, "hostile.xml");
}

TEST(HostileStrategy, NestingFarPastTheLimit) {
  Work w("strategy_depth");
  strategyRefused(w, kXmlHead + "<strategy version=\"1\">" + repeat("<a>", kHuge) + repeat("</a>", kHuge) + "</strategy>\n",
                  "hostile\\.xml:2:1: error: malformed XML: elements are nested too deeply");
  strategyRefused(w, kXmlHead + "<strategy version=\"1\">\n" + repeat("<service name=\"s\">\n", kHuge),
                  "hostile\\.xml:[0-9]+:[0-9]+: error: malformed XML: elements are nested too deeply");
}

TEST(HostileStrategy, AHundredThousandItemsOnOneLine) {
  Work w("strategy_width");
  const std::string robots = "  <robot urdf=\"../robots/turtlebot3_burger.urdf\" type=\"TurtlebotBurger\"/>\n"
                             "  <robot urdf=\"../robots/ev3_robot.urdf\" type=\"Ev3Robot\"/>\n";
  // 100,000 unknown elements on one line: an error each, each with a window of the line.
  const Outcome o = [&] {
    const std::string path = w.at("missions/hostile.xml");
    writeFile(path, kXmlHead + "<strategy version=\"1\">\n" + robots + repeat("<nosuch/>", kHuge) + "\n</strategy>\n");
    return refused(w, {"lint", w.mission(), "--strategy", path}, "hostile\\.xml:5:1: error: [^\n]*nosuch", Where::Caret, "hostile.xml");
  }();
  EXPECT_LT(o.err.size(), kHuge * 1000);
  // 100,000 attributes on one element (tinyxml2 compares each with those before it: refused first).
  std::string attributes;
  for (std::size_t i = 0; i < kHuge; ++i) attributes += " a" + std::to_string(i) + "=\"1\"";
  strategyRefused(w, kXmlHead + "<strategy version=\"1\"" + attributes + ">\n</strategy>\n",
                  "hostile\\.xml:2:1: error: element <strategy> has more than 1000 attributes");
}

TEST(HostileStrategy, SizeEmptyGarbageAndInvalidUtf8) {
  Work w("strategy_size");
  strategyRefused(w, kXmlHead + "<strategy version=\"1\">\n" + megabytes("<!-- ", " -->", 40000, "<broken\n"),
                  "hostile\\.xml:40003:1: error: malformed XML");
  strategyRefused(w, "", "hostile\\.xml:1:1: error: malformed XML: the document is empty", Where::Position);
  strategyRefused(w, garbage(1 << 20), "hostile\\.xml:1:2: error: malformed XML: not UTF-8 text \\(byte 0x80\\)");
  // Not UTF-8: refused where the first bad byte is (names and values are written out again, in JSON
  // among others: `lint --json` once died of one).
  strategyRefused(w, kXmlHead + "<strategy version=\"1\">\n  <robot urdf=\"" + kBadUtf8 + ".urdf\" type=\"T\"/>\n</strategy>\n",
                  "hostile\\.xml:3:16: error: malformed XML: not UTF-8 text \\(byte 0x80\\)");
  strategyRefused(w, kXmlHead + "<strategy version=\"1\">\n  <" + kBadUtf8 + "/>\n</strategy>\n", "hostile\\.xml:3:4: error: malformed XML: not UTF-8");
  std::string strategy = slurp(w.strategy());
  strategy.replace(strategy.find("type=\"Ev3Robot\""), 15, "type=\"Ev3" + kBadUtf8 + "Robot\"");
  writeFile(w.at("missions/hostile.xml"), strategy);
  refused(w, {"lint", w.mission(), "--strategy", w.at("missions/hostile.xml")}, "hostile\\.xml:10:[0-9]+: error: malformed XML: not UTF-8", Where::Caret,
          "hostile.xml");
  // With --json the diagnostics are JSON on stdout, with their positions.
  const Snapshot before = snapshot(w.in);
  const Outcome o = run({"lint", w.mission(), "--strategy", w.at("missions/hostile.xml"), "--json"}, w.log);
  EXPECT_EQ(o.signal, 0) << o.err;
  EXPECT_EQ(o.exit, 2) << o.err;
  const nlohmann::json lint = nlohmann::json::parse(o.out, nullptr, false);
  ASSERT_TRUE(lint.is_object()) << o.out;
  ASSERT_FALSE(lint["diagnostics"].empty()) << o.out;
  EXPECT_EQ(lint["diagnostics"][0].value("line", 0), 10) << o.out;
  EXPECT_NE(lint["diagnostics"][0].value("message", "").find("not UTF-8"), std::string::npos) << o.out;
  EXPECT_EQ(differences(before, snapshot(w.in)), "");
  // An entity bomb: tinyxml2 expands no entity of a DTD; the document is refused, quickly.
  strategyRefused(w,
                  kXmlHead + "<!DOCTYPE s [<!ENTITY a \"aaaaaaaaaa\"><!ENTITY b \"&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;\">"
                             "<!ENTITY c \"&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;\"><!ENTITY d \"&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;\">]>\n"
                             "<strategy version=\"1\">&d;&d;&d;&d;&d;&d;&d;&d;&d;&d;</strategy>\n",
                  "error: ", Where::NoPosition);
}

TEST(HostileStrategy, MissingFileAndAFolder) {
  Work w("strategy_path");
  refused(w, {"lint", w.mission(), "--strategy", w.at("no_such.xml")}, "error: cannot open '[^']*no_such\\.xml'", Where::NoPosition);
  refused(w, {"lint", w.mission(), "--strategy", w.at("missions")}, "error: cannot read '[^']*missions': it is a folder, not a file",
          Where::NoPosition);
}

// ---- URDF files (--robots DIR) ------------------------------------------------------------------

// The strategy names ../robots/turtlebot3_burger.urdf, which --robots DIR resolves against DIR:
// DIR/../robots/turtlebot3_burger.urdf, here the hostile one (DIR is a folder named robots).
fs::path robotsLike(Work& w, const std::string& name) {
  const fs::path dir = w.in / name / "robots";
  fs::create_directories(dir);
  for (const auto& e : fs::directory_iterator(w.in / "robots")) fs::copy_file(e.path(), dir / e.path().filename(), fs::copy_options::overwrite_existing);
  return dir;
}

void urdfRefused(Work& w, const std::string& text, const std::string& diagnostic, Where where = Where::Caret) {
  const fs::path dir = robotsLike(w, "hostile");
  writeFile(dir / "turtlebot3_burger.urdf", text);
  refused(w, {"lint", w.mission(), "--strategy", w.strategy(), "--robots", dir.string()}, diagnostic, where, "turtlebot3_burger.urdf");
}

const std::string kRobotOpen = kXmlHead + "<robot name=\"TurtlebotBurger\">\n";

TEST(HostileUrdf, NestingFarPastTheLimit) {
  Work w("urdf_depth");
  urdfRefused(w, kRobotOpen + repeat("<link name=\"l\">", kHuge) + repeat("</link>", kHuge) + "\n</robot>\n",
              "turtlebot3_burger\\.urdf:[0-9]+:[0-9]+: error: malformed XML: elements are nested too deeply");
  // A kinematic chain of 100,000 links whose last joint closes a cycle: the tree check is linear.
  std::string chain = kRobotOpen;
  for (std::size_t i = 0; i <= kHuge; ++i) chain += "<link name=\"l" + std::to_string(i) + "\"/>\n";
  for (std::size_t i = 0; i < kHuge; ++i) {
    chain += "<joint name=\"j" + std::to_string(i) + "\" type=\"fixed\"><parent link=\"l" + std::to_string(i) + "\"/><child link=\"l" +
             std::to_string(i + 1) + "\"/></joint>\n";
  }
  chain += "<joint name=\"back\" type=\"fixed\"><parent link=\"l" + std::to_string(kHuge) + "\"/><child link=\"l0\"/></joint>\n</robot>\n";
  urdfRefused(w, chain, "turtlebot3_burger\\.urdf:[0-9]+:1: error: invalid URDF: joints form a cycle through link 'l0'");
}

TEST(HostileUrdf, AHundredThousandItemsOnOneLine) {
  Work w("urdf_width");
  // 100,000 links on one line, two of them with the same name.
  std::string links;
  for (std::size_t i = 0; i < kHuge; ++i) links += "<link name=\"l" + std::to_string(i) + "\"/>";
  urdfRefused(w, kRobotOpen + links + "<link name=\"l7\"/>\n</robot>\n", "turtlebot3_burger\\.urdf:[0-9]+:[0-9]+: error: ");
  std::string attributes;
  for (std::size_t i = 0; i < kHuge; ++i) attributes += " a" + std::to_string(i) + "=\"1\"";
  urdfRefused(w, kXmlHead + "<robot name=\"TurtlebotBurger\"" + attributes + ">\n</robot>\n",
              "turtlebot3_burger\\.urdf:2:1: error: element <robot> has more than 1000 attributes");
}

TEST(HostileUrdf, SizeEmptyGarbageAndInvalidUtf8) {
  Work w("urdf_size");
  urdfRefused(w, kRobotOpen + megabytes("<!-- ", " -->", 40000, "<link\n"), "turtlebot3_burger\\.urdf:40003:1: error: malformed XML");
  urdfRefused(w, "", "turtlebot3_burger\\.urdf:1:1: error: malformed XML: the document is empty", Where::Position);
  urdfRefused(w, garbage(1 << 20), "turtlebot3_burger\\.urdf:1:2: error: malformed XML: not UTF-8 text \\(byte 0x80\\)");
  urdfRefused(w, kXmlHead + "<robot name=\"Turtlebot" + kBadUtf8 + "\">\n<link name=\"base\"/>\n</robot>\n",
              "turtlebot3_burger\\.urdf:2:23: error: malformed XML: not UTF-8 text \\(byte 0x80\\)");
}

TEST(HostileUrdf, MissingFileMissingFolderAndAFolder) {
  Work w("urdf_path");
  refused(w, {"lint", w.mission(), "--strategy", w.strategy(), "--robots", w.at("no_such_folder")},
          "strategy\\.xml:[0-9]+:[0-9]+: error: cannot read robot description: --robots '[^']*no_such_folder' has no 'turtlebot3_burger\\.urdf'",
          Where::Caret, "strategy.xml");
  const fs::path dir = robotsLike(w, "folder_case");
  fs::remove(dir / "turtlebot3_burger.urdf");
  fs::create_directories(dir / "turtlebot3_burger.urdf");
  refused(w, {"lint", w.mission(), "--strategy", w.strategy(), "--robots", dir.string()},
          "strategy\\.xml:[0-9]+:[0-9]+: error: cannot read robot description: cannot read '[^']*turtlebot3_burger\\.urdf': it is a folder",
          Where::Caret, "strategy.xml");
  fs::remove(w.urdf());
  refused(w, {"lint", w.mission(), "--strategy", w.strategy()},
          "strategy\\.xml:[0-9]+:[0-9]+: error: cannot read robot description: no file '[^']*turtlebot3_burger\\.urdf'", Where::Caret, "strategy.xml");
}

// ---- IR files (.ir, read by check) --------------------------------------------------------------

const std::string kIrHead = "semo-ir 1;\nvar x : 0..1 = 0;\n";

void irRefused(Work& w, const std::string& text, const std::string& diagnostic, Where where = Where::Caret) {
  const std::string path = w.at("hostile.ir");
  writeFile(path, text);
  refused(w, {"check", path}, diagnostic, where, "hostile.ir");
}

TEST(HostileIr, NestingFarPastTheLimit) {
  Work w("ir_depth");
  irRefused(w, kIrHead + "rule r : " + repeat("(", kHuge) + "x == 0" + repeat(")", kHuge) + " -> x' = 1;\n",
            "hostile\\.ir:3:[0-9]+: error: expression nested too deeply \\(limit 256\\)");
  irRefused(w, kIrHead + "rule r : " + repeat("!", kHuge) + "(x == 0) -> x' = 1;\n",
            "hostile\\.ir:3:[0-9]+: error: expression nested too deeply \\(limit 256\\)");
  irRefused(w, kIrHead + "rule r : " + repeat("x == 0 => ", kHuge) + "x == 0 -> x' = 1;\n",
            "hostile\\.ir:3:[0-9]+: error: expression nested too deeply \\(limit 256\\)");
  irRefused(w, kIrHead + "rule r : " + repeat("x == 0 ? 1 : ", kHuge) + "0 == 1 -> x' = 1;\n",
            "hostile\\.ir:3:[0-9]+: error: expression nested too deeply \\(limit 256\\)");
  // A chain of a non-associative operator nests one level per operator.
  irRefused(w, kIrHead + "rule r : x" + repeat(" - 1", kHuge) + " == 0 -> x' = 1;\n", "hostile\\.ir:3:[0-9]+: error: expression nested too deeply");
  irRefused(w, kIrHead + "rule r : x == 0 -> x' = 1;\nproperty p : " + repeat("always ", kHuge) + "{x == 0};\n",
            "hostile\\.ir:4:[0-9]+: error: formula nested too deeply");
  irRefused(w, kIrHead + "rule r : x == 0 -> x' = 1;\nproperty p : " + repeat("(", kHuge) + "{x == 0}" + repeat(")", kHuge) + ";\n",
            "hostile\\.ir:4:[0-9]+: error: formula nested too deeply");
}

TEST(HostileIr, AHundredThousandItemsOnOneLine) {
  Work w("ir_width");
  // A guard of 100,000 conjuncts (read into a balanced tree), the last naming no variable.
  std::string terms;
  for (std::size_t i = 0; i < kHuge; ++i) terms += "x == 0 && ";
  irRefused(w, kIrHead + "rule r : " + terms + "nosuch == 0 -> x' = 1;\n", "hostile\\.ir:3:1000010: error: undeclared variable 'nosuch'");
  // 100,000 variables declared on one line, then a stray word.
  std::string vars;
  for (std::size_t i = 0; i < kHuge; ++i) vars += "var v" + std::to_string(i) + " : bool = false; ";
  irRefused(w, "semo-ir 1;\n" + vars + "nosuch\n", "hostile\\.ir:2:[0-9]+: error: expected 'var', 'rule'[^\n]*found 'nosuch'");
  // 100,000 robots named.
  std::string robots;
  for (std::size_t i = 0; i < kHuge; ++i) robots += " r" + std::to_string(i);
  irRefused(w, "semo-ir 1;\nrobots" + robots + " r7;\n" + "var x : 0..1 = 0;\n", "hostile\\.ir:2:[0-9]+: error: ");
  // An array of a billion elements.
  irRefused(w, "semo-ir 1;\nvar a[1000000000] : bool = false;\n", "hostile\\.ir:2:[0-9]+: error: an array has at most");
}

TEST(HostileIr, SizeEmptyGarbageAndInvalidUtf8) {
  Work w("ir_size");
  irRefused(w, "semo-ir 1;\n" + megabytes("# ", "", 40000, "var x : 0..1 = 0;\nbroken\n"), "hostile\\.ir:40003:1: error: ");
  irRefused(w, "", "hostile\\.ir:1:1: error: expected 'semo-ir'", Where::Position);
  irRefused(w, garbage(1 << 20), "hostile\\.ir:1:1: error: ");
  irRefused(w, "semo-ir 1;\nvar " + kBadUtf8 + " : bool = false;\n", "hostile\\.ir:2:5: error: unexpected character");
  // Not UTF-8 in a label: `check` (without --json) once died of it, writing the counterexample.
  const std::string path = w.at("hostile.ir");
  writeFile(path, slurp(w.ir()) + "rule r2 @robot(r0) @label(\"go" + kBadUtf8 + "\") : false -> busy' = true;\n");
  for (const char* json : {"--safety-only", "--json"}) {
    refused(w, {"check", path, json}, "hostile\\.ir:[0-9]+:30: error: a string must be UTF-8 text: byte 0x80 is not", Where::Caret, "hostile.ir");
  }
  irRefused(w, std::string("semo-ir 1;\nvar x") + '\0' + " : bool = false;\n", "hostile\\.ir:2:6: error: ");
}

TEST(HostileIr, MissingFileAndAFolder) {
  Work w("ir_path");
  refused(w, {"check", w.at("no_such.ir")}, "error: cannot open '[^']*no_such\\.ir'", Where::NoPosition);
  refused(w, {"analyze", w.at("no_such.ir")}, "error: cannot open '[^']*no_such\\.ir'", Where::NoPosition);
  fs::create_directories(w.at("folder.ir"));
  refused(w, {"check", w.at("folder.ir")}, "error: cannot read '[^']*folder\\.ir': it is a folder, not a file", Where::NoPosition);
  refused(w, {"export", "--ir", w.at("folder.ir")}, "error: cannot read '[^']*folder\\.ir': it is a folder", Where::NoPosition);
}

// ---- task graphs (sdf --graph, JSON) -------------------------------------------------------------

void taskGraphRefused(Work& w, const std::string& text, const std::string& diagnostic, Where where = Where::Caret) {
  const std::string path = w.at("hostile.json");
  writeFile(path, text);
  refused(w, {"sdf", "--graph", path}, diagnostic, where, "hostile.json");
}

TEST(HostileTaskGraph, NestingFarPastTheLimit) {
  Work w("taskgraph_depth");
  taskGraphRefused(w, repeat("[", kHuge) + repeat("]", kHuge), "hostile\\.json:1:257: error: nested too deeply \\(limit 256\\)");
  taskGraphRefused(w, repeat("{\"a\":", kHuge) + "1" + repeat("}", kHuge), "hostile\\.json:1:1281: error: nested too deeply \\(limit 256\\)");
  taskGraphRefused(w, repeat("[", kHuge), "hostile\\.json:1:257: error: nested too deeply");
  // Inside a real task graph, under a member the reader ignores.
  std::string graph = slurp(w.taskGraph());
  graph.insert(graph.find('{') + 1, "\"_deep\": " + repeat("[", kHuge) + repeat("]", kHuge) + ",");
  taskGraphRefused(w, graph, "hostile\\.json:[0-9]+:[0-9]+: error: nested too deeply \\(limit 256\\)");
}

TEST(HostileTaskGraph, AHundredThousandItemsOnOneLine) {
  Work w("taskgraph_width");
  nlohmann::json g = nlohmann::json::parse(slurp(w.taskGraph()));
  for (std::size_t i = 0; i < kHuge; ++i) g["tasks"].push_back({{"name", "t" + std::to_string(i)}, {"kind", "service"}, {"execMicros", 1}, {"ports", nlohmann::json::array()}});
  g["channels"].push_back({{"name", "bad"}, {"from", "nosuch.x"}, {"to", "planner.goal"}, {"initialTokens", 0}});
  taskGraphRefused(w, g.dump(), "hostile\\.json:1:[0-9]+: error: no task named 'nosuch'");
}

TEST(HostileTaskGraph, SizeEmptyGarbageAndInvalidUtf8) {
  Work w("taskgraph_size");
  taskGraphRefused(w, "{\"pad\": \"" + std::string(4 << 20, 'z') + "\", \"x\": ]}", "hostile\\.json:1:" + std::to_string((4 << 20) + 18) + ": error: not valid JSON");
  taskGraphRefused(w, "", "hostile\\.json:1:1: error: not valid JSON", Where::Position);
  taskGraphRefused(w, garbage(1 << 20), "hostile\\.json:1:4: error: not valid JSON: a NUL byte");
  taskGraphRefused(w, "{\"format\": \"semo-taskgraph\", \"robot\": \"" + kBadUtf8 + "\"}", "hostile\\.json:1:40: error: not valid JSON");
}

TEST(HostileTaskGraph, MissingFileAndAFolder) {
  Work w("taskgraph_path");
  refused(w, {"sdf", "--graph", w.at("no_such.json")}, "error: cannot open '[^']*no_such\\.json'", Where::NoPosition);
  refused(w, {"sdf", "--graph", w.at("robots")}, "error: cannot read '[^']*robots': it is a folder, not a file", Where::NoPosition);
}

// ---- SDF3 graphs (sdf --sdf3, XML) ---------------------------------------------------------------

void sdf3Refused(Work& w, const std::string& text, const std::string& diagnostic, Where where = Where::Caret) {
  const std::string path = w.at("hostile.xml");
  writeFile(path, text);
  refused(w, {"sdf", "--sdf3", path}, diagnostic, where, "hostile.xml");
}

const std::string kSdf3Open = kXmlHead + "<sdf3 type=\"sdf\" version=\"1.0\">\n<applicationGraph name=\"g\">\n<sdf name=\"g\" type=\"G\">\n";
const std::string kSdf3Close = "</sdf>\n</applicationGraph>\n</sdf3>\n";

TEST(HostileSdf3, NestingFarPastTheLimit) {
  Work w("sdf3_depth");
  sdf3Refused(w, kSdf3Open + repeat("<actor name=\"a\" type=\"A\">", kHuge) + repeat("</actor>", kHuge) + kSdf3Close,
              "hostile\\.xml:[0-9]+:[0-9]+: error: malformed XML: elements are nested too deeply");
  sdf3Refused(w, kSdf3Open + repeat("<x>", kHuge), "hostile\\.xml:[0-9]+:[0-9]+: error: malformed XML: elements are nested too deeply");
}

TEST(HostileSdf3, AHundredThousandItemsOnOneLine) {
  Work w("sdf3_width");
  // A ring of 100,000 actors on one line, and a channel from an actor that does not exist.
  std::string actors, channels;
  for (std::size_t i = 0; i < kHuge; ++i) {
    const std::string a = "a" + std::to_string(i);
    actors += "<actor name=\"" + a + "\" type=\"A\"><port name=\"i\" type=\"in\" rate=\"1\"/><port name=\"o\" type=\"out\" rate=\"1\"/></actor>";
    channels += "<channel name=\"c" + std::to_string(i) + "\" srcActor=\"" + a + "\" srcPort=\"o\" dstActor=\"a" + std::to_string((i + 1) % kHuge) +
                "\" dstPort=\"i\"" + (i + 1 == kHuge ? " initialTokens=\"1\"" : "") + "/>";
  }
  sdf3Refused(w, kSdf3Open + actors + channels + "<channel name=\"bad\" srcActor=\"nosuch\" srcPort=\"o\" dstActor=\"a0\" dstPort=\"i\"/>\n" + kSdf3Close,
              "hostile\\.xml:5:[0-9]+: error: no actor named 'nosuch'");
  std::string attributes;
  for (std::size_t i = 0; i < kHuge; ++i) attributes += " a" + std::to_string(i) + "=\"1\"";
  sdf3Refused(w, kXmlHead + "<sdf3 type=\"sdf\" version=\"1.0\"" + attributes + ">\n</sdf3>\n",
              "hostile\\.xml:2:1: error: element <sdf3> has more than 1000 attributes");
}

TEST(HostileSdf3, SizeEmptyGarbageAndInvalidUtf8) {
  Work w("sdf3_size");
  sdf3Refused(w, kSdf3Open + megabytes("<!-- ", " -->", 40000, "<actor\n"), "hostile\\.xml:40005:1: error: malformed XML");
  sdf3Refused(w, "", "hostile\\.xml:1:1: error: malformed XML: the document is empty", Where::Position);
  sdf3Refused(w, garbage(1 << 20), "hostile\\.xml:1:2: error: malformed XML: not UTF-8 text \\(byte 0x80\\)");
  // An actor's name not UTF-8: `sdf --sdf3 --json` once died of it (nlohmann::json refuses to write it).
  const std::string path = w.at("hostile.xml");
  writeFile(path, kSdf3Open + "<actor name=\"" + kBadUtf8 + "\" type=\"A\"/>\n" + kSdf3Close);
  for (const char* json : {"--verbose", "--json"}) {
    refused(w, {"sdf", "--sdf3", path, json}, "hostile\\.xml:5:14: error: malformed XML: not UTF-8 text \\(byte 0x80\\)", Where::Caret, "hostile.xml");
  }
}

TEST(HostileSdf3, MissingFileAndAFolder) {
  Work w("sdf3_path");
  refused(w, {"sdf", "--sdf3", w.at("no_such.xml")}, "error: cannot open '[^']*no_such\\.xml'", Where::NoPosition);
  refused(w, {"sdf", "--sdf3", w.at("robots")}, "error: cannot read '[^']*robots': it is a folder, not a file", Where::NoPosition);
}

// ---- counterexample traces (show, replay; JSON) ---------------------------------------------------

void traceRefused(Work& w, const std::string& text, const std::string& diagnostic, Where where = Where::Caret) {
  const std::string path = w.at("hostile.json");
  writeFile(path, text);
  for (const char* command : {"show", "replay"}) refused(w, {command, path}, diagnostic, where, "hostile.json");
}

TEST(HostileTrace, NestingFarPastTheLimit) {
  Work w("trace_depth");
  const std::string trace = slurp(w.trace());
  traceRefused(w, "{\"pad\": " + repeat("[", kHuge) + repeat("]", kHuge) + ", " + trace.substr(trace.find('{') + 1),
               "hostile\\.json:1:[0-9]+: error: nested (too deeply|more than 64 levels)");
  traceRefused(w, repeat("{\"a\":", kHuge), "hostile\\.json:1:[0-9]+: error: nested (too deeply|more than 64 levels)");
  // Deeper than a trace ever is (64) but within the JSON limit: the trace reader refuses it.
  traceRefused(w, "{\"pad\": " + repeat("[", 100) + repeat("]", 100) + ", " + trace.substr(trace.find('{') + 1),
               "hostile\\.json:[0-9]+:[0-9]+: error: nested more than 64 levels deep: not a trace");
}

TEST(HostileTrace, AHundredThousandItemsOnOneLine) {
  Work w("trace_width");
  nlohmann::json t = nlohmann::json::parse(slurp(w.trace()));
  nlohmann::json properties = nlohmann::json::array();
  for (std::size_t i = 0; i < kHuge; ++i) properties.push_back({{"name", "p" + std::to_string(i)}, {"verdict", "proven"}, {"type", "safety"}});
  for (nlohmann::json& p : t["properties"]) {
    if (p.contains("counterexample")) p["counterexample"]["steps"][0]["rule"] = "nosuch.rule";
    properties.push_back(p);
  }
  t["properties"] = properties;
  traceRefused(w, t.dump(), "hostile\\.json:1:[0-9]+: error: step 1: unknown rule 'nosuch\\.rule'");
}

TEST(HostileTrace, SizeEmptyGarbageAndInvalidUtf8) {
  Work w("trace_size");
  traceRefused(w, "{\"pad\": \"" + std::string(4 << 20, 'z') + "\", \"x\": ]}", "hostile\\.json:1:" + std::to_string((4 << 20) + 18) + ": error: not valid JSON");
  traceRefused(w, "", "hostile\\.json:1:1: error: not valid JSON", Where::Position);
  traceRefused(w, garbage(1 << 20), "hostile\\.json:1:4: error: not valid JSON: a NUL byte");
  std::string trace = slurp(w.trace());
  trace.insert(trace.find('{') + 1, "\"bad\": \"" + kBadUtf8 + "\",");
  traceRefused(w, trace, "hostile\\.json:1:[0-9]+: error: not valid JSON[^\n]*UTF-8");
}

TEST(HostileTrace, MissingFileAndAFolder) {
  Work w("trace_path");
  for (const char* command : {"show", "replay"}) {
    refused(w, {command, w.at("no_such.json")}, "error: cannot open '[^']*no_such\\.json'", Where::NoPosition);
    refused(w, {command, w.at("robots")}, "error: cannot read '[^']*robots': it is a folder, not a file", Where::NoPosition);
  }
}

// ---- worlds (simulate --world, JSON) --------------------------------------------------------------

void worldRefused(Work& w, const std::string& text, const std::string& diagnostic, Where where = Where::Caret) {
  const std::string path = w.at("missions/hostile.world.json");
  writeFile(path, text);
  refused(w, {"simulate", w.swarm(), "--strategy", w.swarmStrategy(), "--world", path, "--no-dataflow"}, diagnostic, where, "hostile.world.json");
}

TEST(HostileWorld, NestingFarPastTheLimit) {
  Work w("world_depth");
  worldRefused(w, repeat("[", kHuge) + repeat("]", kHuge), "hostile\\.world\\.json:1:65: error: nesting deeper than 64 levels");
  worldRefused(w, repeat("{\"a\":", kHuge), "hostile\\.world\\.json:1:[0-9]+: error: nesting deeper than 64 levels");
  std::string world = slurp(w.world());
  world.insert(world.find('{') + 1, "\"_deep\": " + repeat("[", kHuge) + repeat("]", kHuge) + ",");
  worldRefused(w, world, "hostile\\.world\\.json:[0-9]+:[0-9]+: error: nesting deeper than 64 levels");
}

TEST(HostileWorld, AHundredThousandItemsOnOneLine) {
  Work w("world_width");
  nlohmann::json world = nlohmann::json::parse(slurp(w.world()));
  for (std::size_t i = 0; i < kHuge; ++i) world["obstacles"].push_back({{"name", "o" + std::to_string(i)}, {"circle", {{"at", {i, 100}}, {"radius", 0.1}}}});
  world["obstacles"].push_back({{"name", "bad"}, {"circle", {{"at", {1, 1}}, {"radius", -1}}}});
  worldRefused(w, world.dump(), "hostile\\.world\\.json:1:[0-9]+: error: a radius must be greater than 0");
  // 100,000 members given twice on one line: an error each, each with a window of the line.
  std::string text = slurp(w.world());
  text.insert(text.find('{') + 1, repeat("\"places\": {}, ", kHuge));
  const std::string path = w.at("missions/hostile.world.json");
  writeFile(path, text);
  const Outcome o = refused(w, {"simulate", w.swarm(), "--strategy", w.swarmStrategy(), "--world", path, "--no-dataflow"},
                            "hostile\\.world\\.json:1:[0-9]+: error: member 'places' given twice", Where::Caret, "hostile.world.json");
  EXPECT_LT(o.err.size(), kHuge * 1000);
}

TEST(HostileWorld, SizeEmptyGarbageAndInvalidUtf8) {
  Work w("world_size");
  worldRefused(w, "{\"pad\": \"" + std::string(4 << 20, 'z') + "\", \"x\": ]}", "hostile\\.world\\.json:1:" + std::to_string((4 << 20) + 18) + ": error: not valid JSON");
  worldRefused(w, "", "hostile\\.world\\.json:1:1: error: not valid JSON", Where::Position);
  worldRefused(w, garbage(1 << 20), "hostile\\.world\\.json:1:4: error: not valid JSON: a NUL byte");
  std::string world = slurp(w.world());
  world.insert(world.find('{') + 1, "\"_bad\": \"" + kBadUtf8 + "\",");
  worldRefused(w, world, "hostile\\.world\\.json:1:[0-9]+: error: not valid JSON[^\n]*UTF-8");
}

TEST(HostileWorld, MissingFileAndAFolder) {
  Work w("world_path");
  const std::vector<std::string> base{"simulate", w.swarm(), "--strategy", w.swarmStrategy(), "--no-dataflow", "--world"};
  auto with = [&](const std::string& world) {
    std::vector<std::string> args = base;
    args.push_back(world);
    return args;
  };
  refused(w, with(w.at("no_such.world.json")), "no_such\\.world\\.json: error: cannot read the world file", Where::NoPosition);
  refused(w, with(w.at("robots")), "robots: error: cannot read the world file", Where::NoPosition);
  // No --world, and no MISSION.world.json beside the mission.
  fs::remove(w.world());
  refused(w, {"simulate", w.swarm(), "--strategy", w.swarmStrategy(), "--no-dataflow"}, "error: no world given and no [^\n]*swarm3\\.world\\.json",
          Where::NoPosition);
}

// ---- a small mission that asks for a huge model -------------------------------------------------

// One line of a mission declares a team of 100,000 robots (the language's limit, which lint accepts
// in a tenth of a second). The commands that build the model or the task graphs must end in time,
// with an error or a limit (exit 2 or 3), not by running out of memory.
TEST(HostileMission, AHundredThousandRobotsInOneTeam) {
  GTEST_SKIP() << "defect: with legged[100000] the translation is linear (export --ir writes 387 MB in 26 s, exit 0, where "
                  "this test wants a budget: exit 3), and check --engine auto proves the mission by counting its robots, but the "
                  "default check (the explicit engine, finding the interchangeable robots), sdf, analyze and simulate run past 60 s "
                  "(memory running out is exit 3, e2e.Progress.ATeamTooLargeForTheMemoryEndsAsALimitNotASignal)";
  Work w("mission_many_robots");
  std::string mission = slurp(w.swarm());
  mission.replace(mission.find("legged[3]"), 9, "legged[100000]");
  writeFile(w.swarm(), mission);
  const std::vector<std::string> model{w.swarm(), "-s", w.swarmStrategy()};
  auto with = [&](std::vector<std::string> head, std::vector<std::string> tail = {}) {
    head.insert(head.end(), model.begin(), model.end());
    head.insert(head.end(), tail.begin(), tail.end());
    return head;
  };
  for (const std::vector<std::string>& args :
       {with({"check"}, {"--max-states", "1000", "--safety-only"}), with({"export", "--ir"}, {"-o", w.at("model.ir")}), with({"sdf"}),
        with({"analyze"}, {"--loss-prob", "0.2"}), with({"simulate"}, {"--no-dataflow"})}) {
    const Snapshot before = snapshot(w.in);
    const Outcome o = run(args, w.log);
    EXPECT_EQ(o.signal, 0) << args[0] << ": " << o.err.substr(0, 2000);
    EXPECT_FALSE(o.timedOut) << args[0];
    EXPECT_TRUE(o.exit == 2 || o.exit == 3) << args[0] << ": exit " << o.exit;
    EXPECT_EQ(differences(before, snapshot(w.in)), "") << args[0];
  }
}

// ---- paths that are not UTF-8 -------------------------------------------------------------------

// A file name may hold any byte but '/' and NUL. JSON written about it (check --json, --trace-out)
// once died of one (nlohmann::json refuses to write bytes that are not UTF-8); it is written with
// U+FFFD in their place.
TEST(HostilePaths, FileNamesThatAreNotUtf8) {
  Work w("paths_not_utf8");
  const std::string model = w.at("mutex" + kBadUtf8 + ".ir");
  fs::copy_file(w.ir(), model);
  const std::string out = w.at("out" + kBadUtf8 + ".json");
  for (const std::vector<std::string>& args : {std::vector<std::string>{"check", model, "--json"}, std::vector<std::string>{"check", model, "--trace-out", out},
                                               std::vector<std::string>{"export", "--ir", model, "-o", out + ".ir"}}) {
    const Outcome o = run(args, w.log);
    EXPECT_EQ(o.signal, 0) << args[1] << " " << args[2] << ": " << o.err;
    EXPECT_EQ(o.exit, args[0] == "export" ? 0 : 1) << o.err;
  }
  EXPECT_TRUE(nlohmann::json::parse(slurp(out), nullptr, false).is_object()) << "the trace was written, as JSON";
  const Outcome o = run({"check", model, "--json"}, w.log);
  EXPECT_TRUE(nlohmann::json::parse(o.out, nullptr, false).is_object()) << o.out.substr(0, 500);
  // And the reading side: show reads the trace back, its "input" as written.
  const Outcome shown = run({"show", out, model}, w.log);
  EXPECT_EQ(shown.signal, 0) << shown.err;
  EXPECT_EQ(shown.exit, 0) << shown.err;
}

// ---- certificates (certify DIR reads DIR/certificate.json) --------------------------------------

TEST(HostileCertificate, DeepEmptyAndGarbage) {
  Work w("certificate");
  const fs::path dir = w.in / "emitted";
  auto certificate = [&](const std::string& text, const std::string& diagnostic, Where where) {
    writeFile(dir / "certificate.json", text);
    refused(w, {"certify", dir.string()}, diagnostic, where, "certificate.json");
  };
  certificate(repeat("[", kHuge), "certificate\\.json:1:257: error: nested too deeply", Where::Caret);
  certificate("", "certificate\\.json:1:1: error: not valid JSON", Where::Position);
  certificate(garbage(1 << 20), "certificate\\.json:1:4: error: not valid JSON: a NUL byte", Where::Caret);
  fs::remove_all(dir);
  refused(w, {"certify", dir.string()}, "error: cannot read [^\n]*certificate\\.json", Where::NoPosition);
}

// ---- outputs ------------------------------------------------------------------------------------

// Every output of every command, with the arguments that make the run write it (given FILE).
struct OutputOption {
  std::string name;
  std::function<std::vector<std::string>(Work&, const std::string&)> args;
  std::function<std::string(Work&)> input;  // an input of that run, which the output must not replace
};

std::vector<OutputOption> fileOutputs() {
  auto mission = [](Work& w) { return w.mission(); };
  auto swarm = [](Work& w) { return w.swarm(); };
  return {
      {"lint --sarif", [](Work& w, const std::string& f) { return std::vector<std::string>{"lint", w.mission(), "-s", w.strategy(), "--sarif", f}; }, mission},
      {"check --trace-out", [](Work& w, const std::string& f) { return std::vector<std::string>{"check", w.mission(), "-s", w.strategy(), "--trace-out", f}; }, mission},
      {"check --junit", [](Work& w, const std::string& f) { return std::vector<std::string>{"check", w.mission(), "-s", w.strategy(), "--junit", f}; }, mission},
      {"check --sarif", [](Work& w, const std::string& f) { return std::vector<std::string>{"check", w.mission(), "-s", w.strategy(), "--sarif", f}; }, mission},
      {"check --msc", [](Work& w, const std::string& f) { return std::vector<std::string>{"check", w.mission(), "-s", w.strategy(), "--msc", f}; }, mission},
      {"check IR --trace-out", [](Work& w, const std::string& f) { return std::vector<std::string>{"check", w.ir(), "--trace-out", f}; },
       [](Work& w) { return w.ir(); }},
      {"show --msc", [](Work& w, const std::string& f) { return std::vector<std::string>{"show", w.trace(), "--msc", f}; }, mission},
      {"graph -o", [](Work& w, const std::string& f) { return std::vector<std::string>{"graph", w.mission(), "-s", w.strategy(), "--modes", "-o", f}; }, mission},
      {"export --ir -o", [](Work& w, const std::string& f) { return std::vector<std::string>{"export", "--ir", w.mission(), "-s", w.strategy(), "-o", f}; }, mission},
      {"export --promela -o", [](Work& w, const std::string& f) { return std::vector<std::string>{"export", "--promela", w.ir(), "-o", f}; },
       [](Work& w) { return w.ir(); }},
      {"export --prism --props",
       [](Work& w, const std::string& f) { return std::vector<std::string>{"export", "--prism", w.mission(), "-s", w.strategy(), "-o", w.at("model.pm"), "--props", f}; },
       mission},
      {"sdf --dot", [](Work& w, const std::string& f) { return std::vector<std::string>{"sdf", "--sdf3", w.sdf3(), "--dot", f}; }, [](Work& w) { return w.sdf3(); }},
      {"sdf --write-sdf3", [](Work& w, const std::string& f) { return std::vector<std::string>{"sdf", "--sdf3", w.sdf3(), "--write-sdf3", f}; },
       [](Work& w) { return w.sdf3(); }},
      {"simulate --trace",
       [](Work& w, const std::string& f) { return std::vector<std::string>{"simulate", w.swarm(), "-s", w.swarmStrategy(), "--no-dataflow", "--trace", f}; }, swarm},
      {"simulate --svg",
       [](Work& w, const std::string& f) { return std::vector<std::string>{"simulate", w.swarm(), "-s", w.swarmStrategy(), "--no-dataflow", "--svg", f}; }, swarm},
      {"replay --save-trace", [](Work& w, const std::string& f) { return std::vector<std::string>{"replay", w.trace(), "--save-trace", f}; }, mission},
      {"replay --svg", [](Work& w, const std::string& f) { return std::vector<std::string>{"replay", w.trace(), "--svg", f}; }, mission},
      {"analyze --svg (mission)",
       [](Work& w, const std::string& f) { return std::vector<std::string>{"analyze", w.swarm(), "-s", w.swarmStrategy(), "--loss-prob", "0.2", "--svg", f}; }, swarm},
      {"analyze --svg (IR)", [](Work& w, const std::string& f) { return std::vector<std::string>{"analyze", w.at("broadcast.ir"), "--svg", f}; },
       [](Work& w) { return w.at("broadcast.ir"); }},
  };
}

TEST(HostileOutputs, NoOutputReplacesAnInputWhateverItsName) {
  Work w("outputs_onto_inputs");
  fs::create_symlink(w.mission(), w.at("link.semo"));
  for (const OutputOption& option : fileOutputs()) {
    SCOPED_TRACE(option.name);
    const std::string input = option.input(w);
    const fs::path p(input);
    const std::string symlink = w.at("link_" + p.filename().string());
    if (!fs::exists(symlink)) fs::create_symlink(p, symlink);
    const std::string hardlink = w.at("hard_" + p.filename().string());
    if (!fs::exists(hardlink)) fs::create_hard_link(p, hardlink);
    const std::string dotdot = (p.parent_path() / ".." / p.parent_path().filename() / p.filename()).string();
    const std::string viaRobots = (w.in / "robots" / ".." / fs::relative(p, w.in)).string();
    for (const std::string& target : {input, symlink, hardlink, dotdot, viaRobots}) {
      refused(w, option.args(w, target), "error: [^\n]* is an input of this run", Where::NoPosition);
    }
  }
  // The URDF files the strategy names are inputs too (export once overwrote one).
  for (const OutputOption& option : fileOutputs()) {
    const std::vector<std::string> args = option.args(w, w.urdf());
    if (std::find(args.begin(), args.end(), w.strategy()) == args.end()) continue;
    SCOPED_TRACE(option.name);
    refused(w, args, "error: [^\n]*turtlebot3_burger\\.urdf' is an input of this run", Where::NoPosition);
  }
  // The world a simulation reads; the trace show and replay read.
  refused(w, {"simulate", w.swarm(), "-s", w.swarmStrategy(), "--no-dataflow", "--svg", w.world()}, "is an input of this run", Where::NoPosition);
  refused(w, {"show", w.trace(), "--msc", w.trace()}, "is an input of this run", Where::NoPosition);
  refused(w, {"replay", w.trace(), "--svg", w.trace()}, "is an input of this run", Where::NoPosition);
  // With --seeds, {seed} in an output's name makes one file per run: seed 3 names an input.
  refused(w, {"simulate", w.swarm(), "-s", w.swarmStrategy(), "--no-dataflow", "--seeds", "1..5", "--svg", w.at("missions/swarm{seed}.semo")},
          "error: --svg '[^']*swarm3\\.semo' is an input of this run", Where::NoPosition);
  writeFile(w.at("props.txt"), "mutual_exclusion\n");
  refused(w, {"check", w.ir(), "--props", w.at("props.txt"), "--trace-out", w.at("props.txt")}, "is an input of this run", Where::NoPosition);
}

TEST(HostileOutputs, AnOutputInAMissingFolderOrOntoAFolderWritesNothing) {
  Work w("outputs_missing_folder");
  fs::create_directories(w.in / "a_folder");
  for (const OutputOption& option : fileOutputs()) {
    SCOPED_TRACE(option.name);
    refused(w, option.args(w, w.at("no_such_folder/out.txt")), "error: [^\n]*there is no folder '[^']*no_such_folder' to write it in", Where::NoPosition);
    refused(w, option.args(w, w.at("a_folder")), "error: [^\n]*a_folder' is a folder", Where::NoPosition);
    refused(w, option.args(w, w.at("missions/lone_lidar.semo/out.txt")), "error: [^\n]*there is no folder", Where::NoPosition);
  }
}

// A run with two outputs, one of which cannot be written, writes neither (once it wrote the other).
TEST(HostileOutputs, OneUnwritableOutputAndTheOthersAreNotWrittenEither) {
  Work w("outputs_one_bad");
  const std::string good = w.at("good.out"), bad = w.at("no_such_folder/bad.out");
  const std::vector<std::vector<std::string>> runs{
      {"check", w.mission(), "-s", w.strategy(), "--trace-out", good, "--msc", bad},
      {"check", w.mission(), "-s", w.strategy(), "--junit", good, "--sarif", bad},
      {"export", "--prism", w.mission(), "-s", w.strategy(), "-o", good, "--props", bad},
      {"sdf", "--sdf3", w.sdf3(), "--dot", good, "--write-sdf3", bad},
      {"simulate", w.swarm(), "-s", w.swarmStrategy(), "--no-dataflow", "--trace", good, "--svg", bad},
      {"replay", w.trace(), "--save-trace", good, "--svg", bad},
      {"check", w.mission(), "-s", w.strategy(), "--trace-out", good, "--msc", w.mission()},
  };
  for (const std::vector<std::string>& args : runs) refused(w, args, "error: ", Where::NoPosition);
}

// The temporary file an output is written through never takes the name of an input: "OUT.partial"
// beside OUT was once opened, truncated and renamed over OUT, taking the input with it.
TEST(HostileOutputs, TheTemporaryFileOfAnOutputIsNeverAnInput) {
  Work w("outputs_temporary");
  writeFile(w.at("p.partial"), "mutual_exclusion\n");
  const Snapshot before = snapshot(w.in);
  const Outcome o = run({"check", w.ir(), "--props", w.at("p.partial"), "--trace-out", w.at("p")}, w.log);
  EXPECT_EQ(o.signal, 0);
  EXPECT_EQ(o.exit, 1) << o.err;  // mutex_bug's counterexample
  EXPECT_EQ(slurp(w.at("p.partial")), "mutual_exclusion\n") << "the --props input is intact";
  Snapshot after = snapshot(w.in);
  EXPECT_TRUE(after.contains("p")) << "the trace was written";
  after.erase("p");
  EXPECT_EQ(differences(before, after), "");
}

// Folder outputs: emit --out and sdf --out.
TEST(HostileOutputs, FolderOutputsSpareTheirInputs) {
  Work w("outputs_folders");
  const std::vector<std::string> emit{"emit", w.fixedMission(), "-s", w.strategy(), "--uncertified", "--out"};
  auto with = [](std::vector<std::string> args, const std::string& out) {
    args.push_back(out);
    return args;
  };
  fs::create_directory_symlink(w.in / "missions", w.in / "missions_link");
  refused(w, with(emit, w.at("missions")), "error: --out '[^']*missions' holds the input", Where::NoPosition);
  refused(w, with(emit, w.at("missions_link")), "error: --out '[^']*missions_link' holds the input", Where::NoPosition);
  refused(w, with(emit, w.at("robots/..")), "error: --out '[^']*' holds the input", Where::NoPosition);
  refused(w, with(emit, w.at("robots")), "error: --out '[^']*robots' holds the input", Where::NoPosition);
  refused(w, with(emit, w.mission()), "error: '[^']*lone_lidar\\.semo' exists and is not a folder", Where::NoPosition);
  refused(w, with(emit, w.mission() + "/sub"), "error: cannot ", Where::NoPosition);
  // sdf --out writes ROBOT.json and ROBOT.dot: never over an input of that name.
  nlohmann::json g = nlohmann::json::parse(slurp(w.taskGraph()));
  g["robot"] = "taskgraph_drive";
  writeFile(w.taskGraph(), g.dump(2));
  refused(w, {"sdf", "--graph", w.taskGraph(), "--out", w.in.string()}, "error: --out '[^']*taskgraph_drive\\.json' is an input of this run",
          Where::NoPosition);
  refused(w, {"sdf", "--graph", w.taskGraph(), "--out", w.mission()}, "error: cannot write the task graphs into", Where::NoPosition);
  // A folder output's folder may be new, its parents too (it is made): only the graph's two files are written.
  const Snapshot before = snapshot(w.in);
  const Outcome o = run({"sdf", "--graph", w.taskGraph(), "--out", w.at("new/graphs")}, w.log);
  EXPECT_EQ(o.exit, 0) << o.err;
  Snapshot after = snapshot(w.in);
  for (const char* made : {"new", "new/graphs", "new/graphs/taskgraph_drive.json", "new/graphs/taskgraph_drive.dot"}) {
    EXPECT_TRUE(after.contains(made)) << made;
    after.erase(made);
  }
  EXPECT_EQ(differences(before, after), "");
}

}  // namespace
