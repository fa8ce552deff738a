#pragma once
// The LTL part of the Promela export (PromelaOptions::liveness), for promela_export.cpp: the
// variables that record the last rule and keep semo's fairness and settling as flags, what each
// step adds to its assignments, the guess before the loop, and one `ltl` claim per property.
#include <cstdint>
#include <functional>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "semo/checker/fairness.hpp"
#include "semo/semantics/ir.hpp"

namespace semo::checker::detail {

// What the writer lends: its expressions in Promela, and fresh identifiers.
struct PromelaText {
  std::function<std::string(const ir::Expr&)> expr;
  std::function<std::string(const ir::Expr&)> negation;
  std::function<std::string(const std::string&)> fresh;  // a new identifier like the one wanted
};

class PromelaLiveness {
 public:
  PromelaLiveness(const ir::Model& model, PromelaText text);

  // The globals and the `inline` that keeps the bookkeeping (before the process).
  void declare(std::ostream& out);
  // Before the loop: the guess per strongly fair group.
  void guess(std::ostream& out) const;
  // What a step of `rule` adds to its assignments (rule = the number of rules: time passing).
  [[nodiscard]] std::vector<std::string> step(std::uint32_t rule) const;
  // The claims (after the process).
  void claims(std::ostream& out) const;

 private:
  void bookkeeping(std::ostream& out);
  void atoms(std::ostream& out);
  [[nodiscard]] std::string ltl(const ir::Ltl& f) const;
  [[nodiscard]] std::string lastIn(const std::vector<std::uint32_t>& rules) const;
  [[nodiscard]] ir::Expr enabledExpr(const std::vector<std::uint32_t>& rules) const;
  [[nodiscard]] std::string enabledAny(const std::vector<std::uint32_t>& rules) const;

  const ir::Model& m_;
  PromelaText text_;
  std::string lastVar_;                  // the rule of the last step
  std::vector<std::string> claimNames_;  // one `ltl` claim per property
  std::vector<std::string> busyFlags_, saidVars_;
  std::string phaseVar_, fairFlag_, quietFlag_, switchFlag_, bookkeeping_;
  Sensing sensing_;
  std::map<std::string, std::string> atomNames_;  // an atom's Promela text -> its flag
  std::string atomsInline_;
};

}  // namespace semo::checker::detail
