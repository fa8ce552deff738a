// Fuzzes the transport's packet decoder: any bytes are either refused with a reason or decode to a
// packet whose encoding is exactly those bytes (the layout has no two spellings of one packet).
#include <cstddef>
#include <cstdint>
#include <span>

#include "semo/runtime/transport.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  semo::runtime::Packet packet;
  const semo::runtime::DecodeError error = semo::runtime::decodePacket(std::span<const std::uint8_t>(data, size), packet);
  if (error != semo::runtime::DecodeError::None) {
    if (semo::runtime::decodeErrorName(error) == "unknown") __builtin_trap();
    return 0;
  }
  if (size != semo::runtime::kPacketBytes) __builtin_trap();
  const semo::runtime::PacketBytes bytes = semo::runtime::encodePacket(packet);
  for (std::size_t i = 0; i < size; ++i) {
    if (bytes[i] != data[i]) __builtin_trap();
  }
  return 0;
}
