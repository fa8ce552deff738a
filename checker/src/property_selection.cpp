// --prop: choosing which properties a run decides (verify.hpp).
#include <stdexcept>

#include "semo/checker/verify.hpp"

namespace semo::checker {

bool globMatches(std::string_view glob, std::string_view name) {
  // The usual greedy match with one backtrack point (the last `*`): linear in practice, at most
  // glob size times name size.
  std::size_t g = 0, n = 0, star = std::string_view::npos, resume = 0;
  while (n < name.size()) {
    if (g < glob.size() && (glob[g] == '?' || glob[g] == name[n])) {
      ++g, ++n;
    } else if (g < glob.size() && glob[g] == '*') {
      star = g++, resume = n;
    } else if (star != std::string_view::npos) {
      g = star + 1, n = ++resume;
    } else {
      return false;
    }
  }
  while (g < glob.size() && glob[g] == '*') ++g;
  return g == glob.size();
}

std::vector<std::string> selectProperties(ir::Model& model, const std::vector<std::string>& globs) {
  // A glob without a bracket names a family too, as the verify block's `check unique_leader` does:
  // `unique_leader` matches unique_leader[ReportPapers].
  auto matches = [](const std::string& g, const std::string& name) {
    return globMatches(g, name) || (g.find('[') == std::string::npos && globMatches(g + "[*]", name));
  };
  auto chosen = [&](const std::string& name) {
    for (const std::string& g : globs) {
      if (matches(g, name)) return true;
    }
    return false;
  };
  std::vector<std::string> all, kept;
  for (const ir::Invariant& i : model.invariants) all.push_back(i.name);
  if (model.validEnd) all.push_back("deadlock_freedom");
  for (const ir::Property& p : model.properties) all.push_back(p.name);
  for (const std::string& g : globs) {
    bool any = false;
    for (const std::string& name : all) any = any || matches(g, name);
    if (!any) {
      std::string names;
      for (const std::string& name : all) names += (names.empty() ? "" : ", ") + name;
      throw std::invalid_argument("--prop '" + g + "' matches no property of the model; its properties: " +
                                  (names.empty() ? std::string("none") : names));
    }
  }
  std::erase_if(model.invariants, [&](const ir::Invariant& i) { return !chosen(i.name); });
  std::erase_if(model.properties, [&](const ir::Property& p) { return !chosen(p.name); });
  if (model.validEnd && !chosen("deadlock_freedom")) model.validEnd.reset();
  for (const std::string& name : all) {
    if (chosen(name)) kept.push_back(name);
  }
  return kept;
}

}  // namespace semo::checker
