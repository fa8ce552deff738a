#pragma once
// The elaboration passes share one class; each elaborate_*.cpp holds one pass.
#include <map>
#include <set>
#include <unordered_map>
#include <string>
#include <vector>

#include "semo/frontend/ast.hpp"
#include "semo/frontend/diagnostics.hpp"
#include "semo/semantics/mission_model.hpp"

namespace semo::detail {

using model::Index;

Index eventIndex(model::Team& team, const std::string& name);  // finds or adds
std::string withHint(std::string message, const std::string& name, const std::vector<std::string>& candidates);

class Elaborator {
 public:
  Elaborator(const ast::Mission& mission, model::MissionModel& model, DiagnosticEngine& diags)
      : ast_(mission), m_(model), diags_(diags) {}
  void run();

 private:
  using RobotSet = std::vector<bool>;  // indexed by global robot index

  // elaborate_structure.cpp
  void declareTeams();
  void declareServices();
  void declareModes();
  void declareMains();
  void checkEvents();
  void computeReachability();
  Index teamOrError(const ast::Name& name, const std::string& role);
  void checkStrategyAgainstMission();

  // elaborate_bodies.cpp
  void collectTopics(const std::vector<ast::Stmt>& body, Index team);
  void lowerServices();
  std::vector<model::Stmt> lowerBody(const std::vector<ast::Stmt>& body, Index team, Index service);
  model::Stmt lowerStmt(const ast::Stmt& s, Index team, Index service);
  void lowerCall(const ast::Stmt& s, model::Stmt& out, Index team);
  void lowerGroupBlock(const ast::Stmt& s, model::Stmt& out, Index team, Index service);
  std::unique_ptr<model::Cond> lowerCond(const ast::Cond& c, Index team);
  model::Expr lowerExpr(const ast::Expr& e, Index team);
  Index topicFor(const ast::Name& owner, const ast::Name& var, bool reliable, bool writing, SourceRange at);

  // elaborate_lint.cpp
  void checkTopics();
  void checkCrashBudgets();

  // elaborate_robots.cpp
  void checkRobotSets();
  void walkService(Index service, const RobotSet& robots, std::vector<Index>& stack);
  void walkBody(const std::vector<model::Stmt>& body, const RobotSet& robots, std::vector<Index>& stack, bool insideGroup);
  void walkCond(const model::Cond& c, const RobotSet& robots);
  void requireImplementation(const model::Stmt& call, const RobotSet& robots);
  [[nodiscard]] bool containsGroups(Index service, std::set<Index>& seen) const;
  [[nodiscard]] std::string robotsOfType(const RobotSet& robots, const std::string& type) const;

  // elaborate_verify.cpp
  void elaborateVerify();
  std::unique_ptr<model::Ltl> lowerLtl(const ast::Ltl& f);
  void lowerAtom(const ast::Ltl& f, model::Ltl& out);

  [[nodiscard]] std::vector<std::string> teamNames() const;
  [[nodiscard]] std::vector<std::string> modeNames(Index team) const;

  static constexpr std::int64_t kMaxRobots = 100000;

  const ast::Mission& ast_;
  model::MissionModel& m_;
  DiagnosticEngine& diags_;
  std::unordered_map<std::string, Index> robotByName_;
  std::vector<const ast::Service*> serviceAst_;  // parallel to m_.services
  std::set<std::pair<Index, RobotSet>> walked_;
  std::set<std::pair<Index, std::string>> reportedMissing_;  // (call site line key) dedupe
};

}  // namespace semo::detail
