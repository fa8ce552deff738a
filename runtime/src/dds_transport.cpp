// DdsTransport (dds_transport.hpp), when semo_runtime is built with Cyclone DDS (SEMO_WITH_DDS).
#include "semo/runtime/dds_transport.hpp"

#ifdef SEMO_WITH_DDS
#include <dds/dds.h>

#include "semo_packet.h"
#endif

namespace semo::runtime {

#ifndef SEMO_WITH_DDS

bool ddsBuilt() { return false; }

std::unique_ptr<Transport> makeDdsTransport(const MissionTables&, Id, const DdsOptions&, std::string& error) {
  error = "this semo_runtime was built without Eclipse Cyclone DDS (install cyclonedds-dev and cyclonedds-tools, and build again)";
  return nullptr;
}

#else

bool ddsBuilt() { return true; }

namespace {

bool reliableKind(Packet::Kind k) {
  return k == Packet::Kind::ChannelSend || k == Packet::Kind::ChannelReceive || k == Packet::Kind::LeaderAnnouncement;
}

class DdsTransport final : public Transport {
 public:
  explicit DdsTransport(std::uint32_t robots) : robots_(robots) {}
  ~DdsTransport() override {
    if (participant_ > 0) dds_delete(participant_);
    if (domain_ > 0) dds_delete(domain_);
  }

  bool open(const MissionTables& mission, const DdsOptions& o, std::string& error) {
    if (!o.interfaceAddress.empty()) {
      const std::string config = "<CycloneDDS><Domain id=\"any\"><General><Interfaces><NetworkInterface address=\"" + o.interfaceAddress +
                                 "\" multicast=\"true\"/></Interfaces></General></Domain></CycloneDDS>";
      domain_ = dds_create_domain(static_cast<dds_domainid_t>(o.domain), config.c_str());
      if (domain_ < 0) return fail(error, "cannot create DDS domain " + std::to_string(o.domain), domain_);
    }
    participant_ = dds_create_participant(static_cast<dds_domainid_t>(o.domain), nullptr, nullptr);
    if (participant_ < 0) return fail(error, "cannot create a DDS participant", participant_);
    // Topic names: the model's fingerprint (without "sha256:"), so that two missions never mix.
    std::string id = mission.modelFingerprint.substr(mission.modelFingerprint.find(':') + 1).substr(0, 16);
    if (id.empty()) id = "unnamed";
    std::int64_t channelRoom = 0;  // the proven capacities: how many channel operations can be in flight at once
    for (const TopicTable& t : mission.topics) channelRoom += t.reliable ? t.capacity + 1 : 0;
    const std::int32_t reliableSamples = static_cast<std::int32_t>(std::max<std::int64_t>(64, 4 * channelRoom * robots_));

    dds_qos_t* best = dds_create_qos();
    dds_qset_reliability(best, DDS_RELIABILITY_BEST_EFFORT, 0);
    dds_qset_history(best, DDS_HISTORY_KEEP_LAST, 1024);
    dds_qos_t* reliable = dds_create_qos();
    dds_qset_reliability(reliable, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
    dds_qset_history(reliable, DDS_HISTORY_KEEP_ALL, 0);
    dds_qset_resource_limits(reliable, reliableSamples, DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED);
    bool ok = true;
    for (int k = 0; k < 2 && ok; ++k) {
      dds_qos_t* q = k == 0 ? best : reliable;
      const std::string name = "semo_" + id + (k == 0 ? "_best_effort" : "_reliable");
      const dds_entity_t topic = dds_create_topic(participant_, &semo_Packet_desc, name.c_str(), q, nullptr);
      writer_[k] = topic < 0 ? topic : dds_create_writer(participant_, topic, q, nullptr);
      reader_[k] = topic < 0 ? topic : dds_create_reader(participant_, topic, q, nullptr);
      ok = topic >= 0 && writer_[k] >= 0 && reader_[k] >= 0;
      if (!ok) fail(error, "cannot create DDS topic " + name + " with its reader and writer", topic < 0 ? topic : writer_[k] < 0 ? writer_[k] : reader_[k]);
    }
    dds_delete_qos(best);
    dds_delete_qos(reliable);
    return ok;
  }

  void send(std::uint32_t to, const Packet& p) override {
    ++counters_.sent;
    semo_Packet s{to, static_cast<std::uint8_t>(p.kind), p.sender, p.index, p.value, p.aux, p.word, p.sequence};
    if (dds_write(writer_[reliableKind(p.kind) ? 1 : 0], &s) < 0) ++counters_.lost;
  }

  bool poll(std::uint32_t self, Packet& p) override {
    for (int k = 0; k < 2; ++k) {
      for (;;) {
        semo_Packet s{};
        void* samples[1] = {&s};
        dds_sample_info_t info[1];
        if (dds_take(reader_[k], samples, info, 1, 1) <= 0) break;
        if (!info[0].valid_data || s.to != self || s.sender == self || s.sender >= robots_ || s.kind < 1 || s.kind > Packet::kLastKind) continue;
        p = Packet{static_cast<Packet::Kind>(s.kind), s.sender, s.index, s.value, s.aux, s.word, s.serial};
        ++counters_.delivered;
        return true;
      }
    }
    return false;
  }

  [[nodiscard]] TransportCounters counters() const override { return counters_; }

 private:
  static bool fail(std::string& error, const std::string& what, dds_return_t code) {
    error = what + ": " + dds_strretcode(code);
    return false;
  }

  std::uint32_t robots_;
  dds_entity_t domain_ = 0, participant_ = 0;
  dds_entity_t writer_[2] = {0, 0}, reader_[2] = {0, 0};
  TransportCounters counters_;
};

}  // namespace

std::unique_ptr<Transport> makeDdsTransport(const MissionTables& mission, Id self, const DdsOptions& options, std::string& error) {
  (void)self;  // a sample names its receiver; poll is told who it is for
  auto t = std::make_unique<DdsTransport>(static_cast<std::uint32_t>(mission.robots.size()));
  if (!t->open(mission, options, error)) return nullptr;
  return t;
}

#endif

}  // namespace semo::runtime
