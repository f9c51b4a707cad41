#include "asset_envelope.h"

#include <cstring>

#include "byte_codec.h"
#include "wirerig/runtime/rig_asset.h"

namespace wirerig {

std::vector<std::uint8_t> Envelope(const AssetMagic& magic, std::uint32_t version,
                                   const std::vector<std::uint8_t>& payload) {
  bytes::Writer out;
  for (std::uint8_t c : magic) out.U8(c);
  out.U32(version);
  out.U64(payload.size());
  out.U32(Crc32(payload));
  out.bytes().insert(out.bytes().end(), payload.begin(), payload.end());
  return std::move(out.bytes());
}

Status OpenEnvelope(std::span<const std::uint8_t> bytes, const AssetMagic& magic,
                    std::uint32_t version, std::string_view wrong_magic,
                    std::span<const std::uint8_t>* payload) {
  if (bytes.size() < kRigAssetHeaderSize ||
      std::memcmp(bytes.data(), magic.data(), magic.size()) != 0)
    return Status::Invalid("header", wrong_magic);
  bytes::Reader header(bytes.subspan(4, kRigAssetHeaderSize - 4));
  const std::uint32_t found_version = header.U32();
  const std::uint64_t size = header.U64();
  const std::uint32_t checksum = header.U32();
  if (found_version != version)
    return Status::Invalid("version",
                           "is not one this runtime reads (rebuild the asset with this wirerig)");
  if (size != bytes.size() - kRigAssetHeaderSize)
    return Status::Invalid("size", "does not match the file: truncated or padded");
  *payload = bytes.subspan(kRigAssetHeaderSize);
  if (Crc32(*payload) != checksum)
    return Status::Invalid("checksum", "does not match the contents: the file is corrupt");
  return Status::Ok();
}

}  // namespace wirerig
