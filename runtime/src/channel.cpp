#include "semo/runtime/channel.hpp"

#include <algorithm>

namespace semo::runtime {

StaticSchedule::StaticSchedule(std::vector<Firing> schedule, std::vector<Channel> channels)
    : schedule_(std::move(schedule)), channels_(std::move(channels)) {
  Id tasks = 0;
  for (const Firing& f : schedule_) tasks = std::max(tasks, f.task + 1);
  for (const Channel& c : channels_) tasks = std::max({tasks, c.from + 1, c.to + 1});
  tokens_.reserve(channels_.size());
  for (const Channel& c : channels_) tokens_.emplace_back(c.capacity, c.initialTokens);
  maxTokens_.reserve(channels_.size());
  for (const Channel& c : channels_) maxTokens_.push_back(c.initialTokens);
  // Counting sort of the channels by task; a self-loop (from == to) is one port of its task.
  portStart_.assign(tasks + 1, 0);
  for (const Channel& c : channels_) {
    ++portStart_[c.from + 1];
    if (c.to != c.from) ++portStart_[c.to + 1];
  }
  for (Id t = 0; t < tasks; ++t) portStart_[t + 1] += portStart_[t];
  ports_.resize(portStart_[tasks]);
  std::vector<std::uint32_t> next(portStart_.begin(), portStart_.end() - 1);
  for (Id c = 0; c < channels_.size(); ++c) {
    ports_[next[channels_[c].from]++] = c;
    if (channels_[c].to != channels_[c].from) ports_[next[channels_[c].to]++] = c;
  }
}

bool StaticSchedule::fireOnce(Id task) {
  const auto stallAt = [&](Stall why, Id c) {
    stall_ = why;
    stalledTask_ = task;
    stalledChannel_ = c;
    return false;
  };
  if (task + 1 >= portStart_.size()) return true;  // a task without channels
  const std::uint32_t first = portStart_[task], last = portStart_[task + 1];
  for (std::uint32_t i = first; i < last; ++i) {
    const Id c = ports_[i];
    if (channels_[c].to == task && !tokens_[c].canConsume(channels_[c].consumption)) return stallAt(Stall::Starved, c);
  }
  for (std::uint32_t i = first; i < last; ++i) {
    const Id c = ports_[i];
    const Channel& ch = channels_[c];
    if (ch.from != task) continue;
    // A self-loop gives its consumed tokens back before producing.
    const std::int64_t after = tokens_[c].tokens() - (ch.to == task ? ch.consumption : 0) + ch.production;
    if (after > ch.capacity) return stallAt(Stall::Overflow, c);
  }
  for (std::uint32_t i = first; i < last; ++i) {
    const Id c = ports_[i];
    if (channels_[c].to == task) tokens_[c].tryConsume(channels_[c].consumption);
  }
  for (std::uint32_t i = first; i < last; ++i) {
    const Id c = ports_[i];
    if (channels_[c].from == task) {
      tokens_[c].tryProduce(channels_[c].production);
      maxTokens_[c] = std::max(maxTokens_[c], tokens_[c].tokens());
    }
  }
  return true;
}

StaticSchedule StaticSchedule::forScenario(const ScenarioTable& scenario) {
  std::vector<Firing> schedule;
  schedule.reserve(scenario.schedule.size());
  for (const ScenarioTable::Firing& f : scenario.schedule) schedule.push_back({f.task, f.repetitions});
  std::vector<Channel> channels;
  channels.reserve(scenario.channels.size());
  for (const ScenarioTable::Channel& c : scenario.channels) {
    channels.push_back({c.from, c.to, c.production, c.consumption, c.initialTokens, c.capacity});
  }
  return {std::move(schedule), std::move(channels)};
}

void StaticSchedule::reset() {
  for (std::size_t c = 0; c < channels_.size(); ++c) tokens_[c] = TokenCounter(channels_[c].capacity, channels_[c].initialTokens);
  stall_ = Stall::None;
  stalledTask_ = stalledChannel_ = kNone;
}

bool StaticSchedule::atInitialTokens() const {
  for (std::size_t c = 0; c < channels_.size(); ++c) {
    if (tokens_[c].tokens() != channels_[c].initialTokens) return false;
  }
  return true;
}

}  // namespace semo::runtime
