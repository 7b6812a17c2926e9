#pragma once
// The constants of the MCAP format (https://mcap.dev/spec) that its reader and writer share:
// the magic and the record opcodes. Every record is <opcode uint8><length uint64><body>, all
// integers little endian.

#include <array>
#include <cstdint>

namespace retrace::logs::internal {

/// 0x89 'M' 'C' 'A' 'P' '0' '\r' '\n': begins and ends every MCAP file ('0' is the major version).
inline constexpr std::array<std::uint8_t, 8> kMcapMagic = {0x89, 'M', 'C',  'A',
                                                           'P',  '0', '\r', '\n'};

/// Opcode and length before every record body.
inline constexpr std::uint64_t kMcapRecordPrefixBytes = 1 + 8;
/// The body of a Footer: summary_start, summary_offset_start (uint64), summary_crc (uint32).
inline constexpr std::uint64_t kMcapFooterBodyBytes = 8 + 8 + 4;

enum class McapOp : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kAttachment = 0x09,
  kAttachmentIndex = 0x0A,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

}  // namespace retrace::logs::internal
