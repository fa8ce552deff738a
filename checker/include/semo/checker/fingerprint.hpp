#pragma once
// Which model a result belongs to: a hash of the model's canonical text, written into every
// `check --json` output and its counterexamples, so that a trace read back later (trace_reader.hpp)
// is known to be replayed against the model it was found in.
#include <string>
#include <string_view>

#include "semo/semantics/ir.hpp"

namespace semo::checker {

// The SHA-256 of `bytes`, as 64 lower-case hexadecimal digits.
std::string sha256Hex(std::string_view bytes);

// "sha256:" + sha256Hex(ir::toText(model)): the canonical IR text covers every variable, rule,
// property and assumption, and the rules' origins ("file:line:col" with the mission file's path as
// it was given), so the same mission read through a different path gets another fingerprint.
std::string modelFingerprint(const ir::Model& model);

}  // namespace semo::checker
