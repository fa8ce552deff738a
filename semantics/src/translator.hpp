#pragma once
// The translator from MissionModel to IR, shared by translate.cpp (variables and robot programs),
// translate_network.cpp (events, messages, crashes, leaders, modes) and translate_properties.cpp.
#include <functional>
#include <map>
#include <optional>
#include <tuple>

#include "semo/semantics/lowering.hpp"
#include "semo/semantics/robot_program.hpp"
#include "semo/semantics/translate.hpp"

namespace semo::detail {

using ir::Expr;
using ir::Op;
using lowering::BlockRange;
using lowering::Instr;
using lowering::PlanProgram;
using lowering::RuleMeaning;
using lowering::VariableRole;
using model::Index;

inline Expr eq(Expr a, std::int32_t v) { return Expr::binary(Op::Eq, std::move(a), Expr::constant(v)); }
inline Expr lnot(Expr a) { return Expr::unary(Op::Not, std::move(a)); }

class Translator {
 public:
  Translator(const model::MissionModel& m, const TranslationOptions& o, const SourceManager& sources, DiagnosticEngine& diags)
      : m_(m), options_(o), sources_(sources), diags_(diags) {}

  std::optional<Translation> run();

 private:
  struct RobotVars {
    std::optional<ir::VarId> alive, mode;
    std::vector<std::optional<ir::VarId>> pc;  // per plan of the team
    std::map<Index, ir::VarId> event;          // per event index of the team
    std::map<Index, ir::VarId> view, msg;      // per topic
    std::map<std::string, ir::VarId> knows;    // knowledge item -> how many of its facts the robot holds
    std::map<Index, ir::VarId> leads;          // leader block -> the robot believes it is the leader
    std::map<Index, ir::VarId> silence;        // leader block -> heartbeat periods without a heartbeat
    std::map<Index, ir::VarId> lossRun;        // leader block -> heartbeats lost in a row
  };

  // Where robots of a team work in a group service: (plan index, instruction).
  struct ServiceSite {
    std::size_t plan;
    std::size_t instr;
  };

  // A rule under construction while walking from a control point: its IR guard, updates and
  // label, and the same step in the mission's terms (actions, guards, effects) for the runtime.
  struct Path {
    std::vector<Expr> guard;
    std::vector<ir::Assignment> updates;
    std::vector<std::string> words;
    bool changesMode = false;
    std::vector<lowering::Action> actions;
    std::vector<lowering::Guard> guards;
    std::vector<lowering::Effect> effects;
    std::vector<ir::SensedOutcome> sensed;
  };

  void assumptions();
  void variables();
  void programRules(Index robot, std::size_t planIndex);
  // Group formation: the live candidates of `arms`, together, are at least the robots they need.
  [[nodiscard]] Expr enoughLive(const std::vector<const model::GroupArm*>& arms) const;
  // Blocks of up to this many arms get an invariant per set of arms (Hall's condition); larger ones
  // one per arm only.
  static constexpr std::size_t kHallArms = 6;
  // A sensed condition as text, the same for every place it is written: `negated` flips when the
  // text is of its negation (x >= 1 is !(x < 1)).
  [[nodiscard]] std::string sensedText(const model::Cond& c, bool& negated) const;
  // Whether every value the condition reads comes from one source for its team (source="team").
  [[nodiscard]] bool readsTeamSourcesOnly(const model::Cond& c) const;
  void walk(Index robot, std::size_t planIndex, std::size_t at, Path path, std::size_t start, int depth);
  void finish(Index robot, std::size_t planIndex, std::size_t start, std::size_t target, Path path);
  void effect(Index robot, std::size_t planIndex, const Instr& in, Path& path, std::vector<Path>& out);
  void knowledgeRules();
  // Counts of a large team (translate_counts.cpp).
  [[nodiscard]] bool counted(Index team) const { return m_.teams[team].robots.size() > options_.countTeamsAbove; }
  // The variable counting the live robots of `team` whose `role` variable (knows `knowledge`, or
  // the pc of `planIndex`) is one of `values`; made on first use.
  ir::VarId teamCount(Index team, VariableRole::Kind role, std::size_t planIndex, const std::string& knowledge,
                      std::vector<std::int32_t> values);
  // How many of the counted robots other than `robot` there are, given that `robot` is alive and
  // its counted variable is `own` (an expression, or a constant when the caller knows it).
  [[nodiscard]] Expr othersCounted(ir::VarId count, Index robot, Expr own) const;
  // Every rule that changes a counted variable or a counted robot's `alive` updates the count.
  void maintainCounts();
  void groupServiceRules(Index robot, std::size_t planIndex, std::size_t at);
  void blockExitRules(Index robot, std::size_t planIndex, std::size_t at);
  // The synchronised start of the group service at `at`; `pcs` (if given) receives the program
  // points another robot must not be at.
  [[nodiscard]] Expr groupStarted(Index robot, std::size_t planIndex, std::size_t at, std::vector<std::size_t>* pcs = nullptr);
  [[nodiscard]] Expr inService(Index robot, const std::string& service) const;
  void eventRules();
  void messageRules();
  void crashRules();
  void leaderRules();
  void defaultRules();
  void invariants();
  void livenessProperties();
  // A temporal property of the verify block; nullopt (and `why`) if an atom cannot be expressed.
  [[nodiscard]] std::optional<ir::Ltl> temporalFormula(const model::Ltl& f, std::string& why) const;
  // A property without temporal operators as a state expression; else nullopt and `why`.
  [[nodiscard]] std::optional<Expr> stateFormula(const model::Ltl& f, std::string& why) const;

  ir::VarId addVar(std::string name, std::int32_t min, std::int32_t max, std::int32_t init, std::int32_t robot,
                   VariableRole role, std::vector<std::string> valueNames = {});
  [[nodiscard]] Expr alive(Index robot) const;
  [[nodiscard]] std::optional<Expr> condition(Index robot, const model::Cond& c) const;
  [[nodiscard]] std::optional<Expr> operand(Index robot, const model::Expr& e) const;
  [[nodiscard]] std::int32_t symbolValue(Index topic, const model::Expr& e) const;
  [[nodiscard]] std::vector<ir::Assignment> enterMode(Index robot, Index mode) const;
  [[nodiscard]] std::vector<Index> modesRunning(Index team, std::size_t planIndex, Index service) const;
  [[nodiscard]] ir::Origin origin(const SourceRange& r, std::string construct) const;
  [[nodiscard]] static std::string constructOf(const Instr& in);
  [[nodiscard]] bool topicRead(Index team, Index topic) const;
  [[nodiscard]] std::int32_t crashBudget(Index team) const;
  [[nodiscard]] std::vector<Index> preferenceOrder(Index block) const;
  [[nodiscard]] Expr bestFormingCandidate(Index block, std::size_t planIndex, std::size_t formPoint) const;
  [[nodiscard]] Expr suspects(Index robot, Index block) const;
  [[nodiscard]] const std::vector<Index>& candidates(Index block) const;
  [[nodiscard]] Expr noLeader(Index block) const;
  [[nodiscard]] Expr waitingForHeartbeats(Index robot, Index block) const;
  [[nodiscard]] std::int32_t timeoutPeriods(Index block) const;
  void roundRules(Index block);
  void addRule(ir::Rule rule, RuleMeaning meaning) {
    out_.rules.push_back(std::move(rule));
    lowering_.rules.push_back(std::move(meaning));
  }
  // A one-outcome rule of `robot`, named "<robot>.<what>".
  [[nodiscard]] ir::Rule robotRule(const std::string& what, Index robot, ir::RuleKind kind, std::string label, Expr guard,
                                   std::vector<ir::Assignment> updates) const;
  [[nodiscard]] bool wants(const std::string& check) const {
    return std::find(m_.assumptions.checks.begin(), m_.assumptions.checks.end(), check) != m_.assumptions.checks.end();
  }

  const model::MissionModel& m_;
  const TranslationOptions& options_;
  const SourceManager& sources_;
  DiagnosticEngine& diags_;
  ir::Model out_;
  lowering::Lowering lowering_;
  std::vector<RobotVars> vars_;
  std::vector<std::vector<PlanProgram>> programs_;  // per team, per plan
  std::vector<std::optional<ir::VarId>> crashed_;   // per team
  std::map<Index, ir::VarId> channel_;              // per reliable topic
  std::vector<Index> leaderBlocks_;
  // Per (team, group service name), in that order: the service (index into the strategy's) and
  // where the team's robots work in it.
  struct ServiceSites {
    Index service = model::kNone;
    std::vector<ServiceSite> at;
  };
  std::map<std::pair<Index, std::string>, ServiceSites> sites_;
  bool losePublish_ = false, loseEvents_ = false, loseHeartbeats_ = false, loseKnowledge_ = false;
  bool fairLoss_ = false;
  std::size_t rulesPerPoint_ = 0;
  struct TeamCount {
    ir::VarId var;
    Index team;
    std::vector<std::optional<ir::VarId>> of;  // per robot of the team (in its order): the variable counted
    std::vector<std::int32_t> values;           // ascending
  };
  std::vector<TeamCount> counts_;
  using CountKey = std::tuple<Index, VariableRole::Kind, std::size_t, std::string, std::vector<std::int32_t>>;
  std::map<CountKey, ir::VarId> countIndex_;
  [[nodiscard]] const TeamCount& countOf(ir::VarId var) const;
  // Each count's definition as a state predicate (Lowering::countDefinitions).
  [[nodiscard]] std::vector<Expr> countDefinitions() const;
};

}  // namespace semo::detail
