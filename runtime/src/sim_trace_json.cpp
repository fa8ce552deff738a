// The simulated trace as JSON (sim_trace.hpp), "semo-simtrace" version 1. The text is built here
// rather than with nlohmann::json's dump, because traces are compared byte for byte (the same run
// gives the same file) and read in diffs: members come in a fixed order, numbers with fixed decimals
// (times and poses to 6), one event and one pose sample per line, optional event members left out
// when empty. Conventions the readers rely on:
//   - an event's "robot" is the robot's name, or null for an event of no robot;
//   - "peer" is a robot's name, or "*" for a message sent to every peer; absent when there is none;
//   - times that never came (completedAt, sinceCrash, a convergence that never happened) are null.
#include <string>

#include "semo/runtime/sim_trace.hpp"
#include "text_output.hpp"

namespace semo::runtime {

namespace {

using detail::fixed;

class Writer {
 public:
  explicit Writer(const SimTrace& trace) : trace_(trace) {}

  std::string write() {
    const SimTrace& tr = trace_;
    out_ += "{\n";
    line("format", quote("semo-simtrace"));
    line("version", "1");
    line("mission", quote(tr.mission));
    line("strategy", quote(tr.strategy));
    line("world", quote(tr.worldFile));
    line("modelFingerprint", quote(tr.modelFingerprint));
    line("seed", std::to_string(tr.seed));
    line("duration", time(tr.duration));
    line("faults", quote(tr.faults));
    out_ += "  \"robots\": [";
    for (std::size_t i = 0; i < tr.robots.size(); ++i) {
      const TraceRobot& r = tr.robots[i];
      out_ += i == 0 ? "\n" : ",\n";
      out_ += "    {\"name\": " + quote(r.name) + ", \"type\": " + quote(r.type) + ", \"team\": " + quote(r.team) + "}";
    }
    out_ += tr.robots.empty() ? "],\n" : "\n  ],\n";
    out_ += "  \"teams\": [";
    for (std::size_t i = 0; i < tr.teams.size(); ++i) out_ += (i == 0 ? "" : ", ") + quote(tr.teams[i]);
    out_ += "],\n";
    out_ += "  \"events\": [";
    for (std::size_t i = 0; i < tr.events.size(); ++i) {
      out_ += i == 0 ? "\n    " : ",\n    ";
      event(tr.events[i]);
    }
    out_ += tr.events.empty() ? "],\n" : "\n  ],\n";
    out_ += "  \"poses\": [";
    for (std::size_t i = 0; i < tr.poses.size(); ++i) {
      out_ += i == 0 ? "\n    " : ",\n    ";
      poseSample(tr.poses[i]);
    }
    out_ += tr.poses.empty() ? "],\n" : "\n  ],\n";
    summary(tr.summary);
    out_ += "}\n";
    return std::move(out_);
  }

 private:
  const SimTrace& trace_;
  std::string out_;

  static std::string quote(std::string_view raw) { return detail::jsonString(raw); }

  static std::string time(double t) { return fixed(t, 6, "null"); }
  // A time that may never have come: negative means it did not.
  static std::string maybeTime(double t) { return t < 0 ? "null" : time(t); }

  std::string robot(std::uint32_t index) const {
    return index < trace_.robots.size() ? quote(trace_.robots[index].name) : "null";
  }

  void line(const char* key, const std::string& value) { out_ += std::string("  \"") + key + "\": " + value + ",\n"; }

  void event(const TraceEvent& e) {
    out_ += "{\"t\": " + time(e.t) + ", \"robot\": " + robot(e.robot) + ", \"kind\": " + quote(eventKindName(e.kind));
    auto optional = [&](const char* key, const std::string& value) {
      if (!value.empty()) out_ += std::string(", \"") + key + "\": " + quote(value);
    };
    optional("rule", e.rule);
    optional("label", e.label);
    optional("origin", e.origin);
    optional("detail", e.detail);
    optional("block", e.block);
    if (e.peer < trace_.robots.size()) out_ += ", \"peer\": " + robot(e.peer);
    else if (e.kind == TraceEvent::Kind::Send && e.peer == kNoRobot) out_ += ", \"peer\": \"*\"";
    if (!e.changes.empty()) {
      out_ += ", \"changes\": [";
      for (std::size_t i = 0; i < e.changes.size(); ++i) {
        const TraceChange& c = e.changes[i];
        out_ += (i == 0 ? "" : ", ") + std::string("{\"var\": ") + quote(c.var) + ", \"from\": " + std::to_string(c.from) +
                ", \"to\": " + std::to_string(c.to) + "}";
      }
      out_ += "]";
    }
    out_ += "}";
  }

  void poseSample(const PoseSample& s) {
    out_ += "{\"t\": " + time(s.t) + ", \"robots\": [";
    for (std::size_t i = 0; i < s.poses.size(); ++i) {
      const Pose& p = s.poses[i];
      out_ += (i == 0 ? "[" : ", [") + fixed(p.x, 6, "null") + ", " + fixed(p.y, 6, "null") + ", " + fixed(p.theta, 6, "null") + "]";
    }
    out_ += "]}";
  }

  // Per robot, one line of counts (specs/runtime.md, "Dataflow"): iterations, the scenarios that ran
  // of those it has, the channels that reached their proven capacity, stalls and overflows.
  std::string dataflow(const std::vector<DataflowRunSummary>& robots) const {
    std::string list = "[";
    for (std::size_t r = 0; r < robots.size(); ++r) {
      const DataflowRunSummary& d = robots[r];
      std::uint64_t iterations = 0, ran = 0, full = 0;
      for (std::uint64_t n : d.iterations) iterations += n, ran += n > 0 ? 1 : 0;
      for (std::size_t c = 0; c < d.capacity.size() && c < d.maxFill.size(); ++c) {
        full += d.capacity[c] > 0 && d.maxFill[c] >= d.capacity[c] ? 1 : 0;
      }
      list += (r == 0 ? "\n      " : ",\n      ") +
              fmt::format("{{\"robot\": {}, \"iterations\": {}, \"scenariosRun\": {}, \"scenarios\": {}, \"notRun\": {}, "
                          "\"channelsAtCapacity\": {}, \"channels\": {}, \"stalls\": {}, \"overflows\": {}}}",
                          robot(static_cast<std::uint32_t>(r)), iterations, ran, d.scenarios.size(), d.notRun.size(), full,
                          d.channels.size(), d.stalls, d.overflows);
    }
    return list + (robots.empty() ? "]" : "\n    ]");
  }

  void summary(const TraceSummary& s) {
    out_ += "  \"summary\": {\n";
    auto field = [&](const char* key, const std::string& value, bool last = false) {
      out_ += std::string("    \"") + key + "\": " + value + (last ? "\n" : ",\n");
    };
    field("goalStated", s.goalStated ? "true" : "false");
    field("completed", s.completed ? "true" : "false");
    field("completedAt", maybeTime(s.completedAt));
    std::string list = "[";
    for (std::size_t i = 0; i < s.modeChanges.size(); ++i) {
      list += (i == 0 ? "\n      " : ",\n      ") + std::string("{\"t\": ") + time(s.modeChanges[i].first) +
              ", \"change\": " + quote(s.modeChanges[i].second) + "}";
    }
    field("modeChanges", list + (s.modeChanges.empty() ? "]" : "\n    ]"));
    list = "[";
    for (std::size_t i = 0; i < s.leaderChanges.size(); ++i) {
      const LeaderChange& c = s.leaderChanges[i];
      list += (i == 0 ? "\n      " : ",\n      ") + std::string("{\"block\": ") + quote(c.block) + ", \"t\": " + time(c.t) +
              ", \"from\": " + robot(c.from) + ", \"to\": " + robot(c.to) + ", \"sinceCrash\": " + maybeTime(c.sinceCrash) + "}";
    }
    field("leaderChanges", list + (s.leaderChanges.empty() ? "]" : "\n    ]"));
    list = "[";
    for (std::size_t i = 0; i < s.convergedAt.size(); ++i) {
      list += (i == 0 ? "" : ", ") + std::string("{\"knowledge\": ") + quote(s.convergedAt[i].first) +
              ", \"t\": " + maybeTime(s.convergedAt[i].second) + "}";
    }
    field("convergedAt", list + "]");
    field("messagesSent", std::to_string(s.messagesSent));
    field("messagesLost", std::to_string(s.messagesLost));
    field("stepsChecked", std::to_string(s.stepsChecked));
    field("mismatches", std::to_string(s.mismatches));
    field("outsideAssumptions", quote(s.outsideAssumptions));
    list = "[";
    for (std::size_t i = 0; i < s.violations.size(); ++i) list += (i == 0 ? "" : ", ") + quote(s.violations[i]);
    field("violations", list + "]");
    field("dataflow", dataflow(s.dataflow), true);
    out_ += "  }\n";
  }
};

}  // namespace

std::string simTraceToJson(const SimTrace& trace) { return Writer(trace).write(); }

}  // namespace semo::runtime
