// A robot's dataflow runner (dataflow.hpp).
#include "semo/runtime/dataflow.hpp"

#include <algorithm>

namespace semo::runtime {

DataflowRunner::DataflowRunner(const DataflowTable& table) : table_(&table) {
  schedules_.reserve(table.scenarios.size());
  for (const ScenarioTable& s : table.scenarios) schedules_.push_back(StaticSchedule::forScenario(s));
  stopped_.assign(table.scenarios.size(), 0);
}

bool DataflowRunner::runnable(Id s) const {
  if (s >= table_->scenarios.size()) return false;
  const ScenarioTable& t = table_->scenarios[s];
  return t.proven && !t.schedule.empty() && t.periodNum > 0 && t.periodDen > 0;
}

void DataflowRunner::select(Id s) {
  if (s == selected_) return;
  selected_ = s;
  elapsed_ = 0;
  started_ = 0;
  if (s != kNone && stopped_[s] == 0) schedules_[s].reset();
}

DataflowRunner::Advance DataflowRunner::advance(std::int64_t micros) {
  Advance out;
  if (selected_ == kNone || micros <= 0 || !runnable(selected_) || stopped_[selected_] != 0) return out;
  const ScenarioTable& t = table_->scenarios[selected_];
  // Iteration k starts at k * num / den microseconds; those before elapsed + micros are due. Exact:
  // num / den is the analysis' fraction, and 128 bits hold a day of microseconds times any den.
  __extension__ typedef __int128 Wide;
  elapsed_ += micros;
  const Wide scaled = static_cast<Wide>(elapsed_) * t.periodDen;
  const auto due = static_cast<std::uint64_t>((scaled + t.periodNum - 1) / t.periodNum);
  StaticSchedule& schedule = schedules_[selected_];
  for (; started_ < due; ++started_) {
    if (!schedule.runIteration([](Id) {})) {
      stopped_[selected_] = 1;
      out.stall = schedule.stall();
      out.task = schedule.stalledTask();
      out.channel = schedule.stalledChannel() == kNone ? kNone : t.channels[schedule.stalledChannel()].channel;
      return out;
    }
    ++out.iterations;
  }
  return out;
}

std::int64_t DataflowRunner::maxFill(Id c) const {
  std::int64_t most = 0;
  for (std::size_t s = 0; s < schedules_.size(); ++s) {
    if (schedules_[s].iterations() == 0 && stopped_[s] == 0) continue;  // never ran: its initial tokens were never there
    const std::vector<ScenarioTable::Channel>& channels = table_->scenarios[s].channels;
    for (std::size_t k = 0; k < channels.size(); ++k) {
      if (channels[k].channel == c) most = std::max(most, schedules_[s].maxTokens(static_cast<Id>(k)));
    }
  }
  return most;
}

}  // namespace semo::runtime
