#pragma once
// The projection, shared by project.cpp (teams, topics, groups, leaders, knowledge, the abstraction
// function) and project_rows.cpp (each robot's plan programs and step rows, with the conditions and
// calls they use).
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "semo/codegen/project.hpp"

namespace semo::codegen::detail {

using runtime::Id;
using runtime::kNone;

class Projector {
 public:
  Projector(const model::MissionModel& m, const Translation& t, const SourceManager& sources)
      : m_(m), t_(t), sources_(sources) {}

  runtime::MissionTables run();

 private:
  // project.cpp
  void teams();
  void topicsAndValues();
  void knowledge();
  void groupBlocks();
  void robots();
  void networkRules();
  void abstraction();
  [[nodiscard]] Id teamModeIndex(model::Index mode) const;
  [[nodiscard]] Id knowledgeItem(model::Index team, const std::string& item) const;

  // project_rows.cpp
  void plans(Id robot);
  runtime::Row row(Id rule, const lowering::RuleMeaning& meaning);
  runtime::ActionRow action(const lowering::Action& a);
  runtime::GuardRow guard(const lowering::Guard& g, Id robot);
  runtime::EffectRow effect(const lowering::Effect& e, Id robot);
  Id condition(const model::Cond& c);
  Id call(const model::Stmt& s);
  runtime::Operand operand(const model::Expr& e);
  Id pcSet(const std::vector<std::size_t>& pcs);
  [[nodiscard]] std::string where(const SourceRange& r) const;

  const model::MissionModel& m_;
  const Translation& t_;
  const SourceManager& sources_;
  runtime::MissionTables out_;
  std::map<const model::Cond*, Id> conditions_;
  std::map<const model::Stmt*, Id> calls_;
  std::map<std::vector<Id>, Id> pcSets_;
  std::map<std::pair<model::Index, std::string>, Id> knowledgeIndex_;  // (team, item)
  std::vector<Id> leaderIndex_;                                         // per model group block
};

}  // namespace semo::codegen::detail
