// The envelope shared by the runtime's binary assets (.wrig, .wclip): 4-byte magic, u32 version,
// u64 payload size, u32 CRC-32 of the payload, then the payload (rig_asset.h).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "wirerig/runtime/status.h"

namespace wirerig {

using AssetMagic = std::array<std::uint8_t, 4>;

std::vector<std::uint8_t> Envelope(const AssetMagic& magic, std::uint32_t version,
                                   const std::vector<std::uint8_t>& payload);

// The payload inside `bytes`, or a refusal: `wrong_magic` (a static string saying what the
// file is not), an unread version, a size or checksum that does not match.
Status OpenEnvelope(std::span<const std::uint8_t> bytes, const AssetMagic& magic,
                    std::uint32_t version, std::string_view wrong_magic,
                    std::span<const std::uint8_t>* payload);

}  // namespace wirerig
