// The .wrig/.wclip envelope (runtime/rig_asset.h): bytes 8-15 hold the payload size and bytes
// 16-19 the CRC-32 of the payload. Random mutations almost never keep both right, so the asset
// fuzzers parse every input twice: as it is (the envelope checks), then with the size and
// checksum rewritten to match (the payload parser and validation behind them).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "wirerig/runtime/rig_asset.h"

namespace wirerig::fuzz {

// A copy of `bytes` with a consistent size and checksum; empty if too short for a header.
inline std::vector<std::uint8_t> WithConsistentEnvelope(std::span<const std::uint8_t> bytes) {
  if (bytes.size() < kRigAssetHeaderSize) return {};
  std::vector<std::uint8_t> out(bytes.begin(), bytes.end());
  const std::uint64_t size = out.size() - kRigAssetHeaderSize;
  for (int i = 0; i < 8; ++i) out[8 + i] = static_cast<std::uint8_t>(size >> (8 * i));
  const std::uint32_t crc = Crc32(std::span<const std::uint8_t>(out).subspan(kRigAssetHeaderSize));
  for (int i = 0; i < 4; ++i) out[16 + i] = static_cast<std::uint8_t>(crc >> (8 * i));
  return out;
}

// The asset fuzzers' entry: `parse_one` on the input as it is, then with its envelope made
// consistent.
template <class ParseOne>
int ParseAsItIsAndConsistent(const std::uint8_t* data, std::size_t size, ParseOne parse_one) {
  const std::span<const std::uint8_t> bytes(data, size);
  parse_one(bytes);
  const std::vector<std::uint8_t> consistent = WithConsistentEnvelope(bytes);
  if (!consistent.empty()) parse_one(std::span<const std::uint8_t>(consistent));
  return 0;
}

}  // namespace wirerig::fuzz
