// Hostile outputs, end to end: every output option of every command pointed onto an input (directly,
// through a symlink, through dir/../file, through a hard link), into a missing folder and onto a
// folder. No output ever replaces an input, and a run that cannot write one of its outputs writes
// none (hostile_inputs_test.cpp has the readers' side; hostile_support.hpp what both share).
#include "hostile_support.hpp"

namespace {

using namespace hostile;
namespace fs = std::filesystem;

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
      {"world -o", [](Work& w, const std::string& f) { return std::vector<std::string>{"world", w.swarm(), "-s", w.swarmStrategy(), "-o", f}; }, swarm},
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
