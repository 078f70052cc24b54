#include "robots/rflex/rflex_protocol.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <vector>

namespace coopmap::rflex {
namespace {

std::vector<Packet> decodeAll(Decoder& d, const std::vector<uint8_t>& bytes) {
  std::vector<Packet> out;
  d.feed(bytes.data(), bytes.size(), out);
  return out;
}

std::vector<uint8_t> concat(std::initializer_list<std::vector<uint8_t>> parts) {
  std::vector<uint8_t> out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

TEST(RflexProtocolTest, EncodesAxisCommandBigEndianWithXorChecksum) {
  // Rotation axis, -1000 ticks/s (0x3E8), acceleration 0x01020304, torque 30000 (0x7530).
  const Packet p = makeAxisSetDir(kRotationAxis, -1000, 0x01020304, 30000);
  const std::vector<uint8_t> expected = {
      0x1B,
      0x02,  // ESC STX
      0x02,
      0x00,
      0x07,
      0x0E,  // port MOT, id, MOT_AXIS_SET_DIR, length 14
      0x01,  // axis
      0x00,
      0x00,
      0x03,
      0xE8,  // |velocity|
      0x01,
      0x02,
      0x03,
      0x04,  // acceleration
      0x00,
      0x00,
      0x75,
      0x30,  // torque
      0x00,  // direction: negative
      0x02 ^ 0x07 ^ 0x0E ^ 0x01 ^ 0x03 ^ 0xE8 ^ 0x01 ^ 0x02 ^ 0x03 ^ 0x04 ^ 0x75 ^ 0x30,
      0x1B,
      0x03};  // ESC ETX
  EXPECT_EQ(encode(p), expected);
  const auto c = parseAxisSetDir(p);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->axis, kRotationAxis);
  EXPECT_EQ(c->velocity, -1000);
  EXPECT_EQ(c->acceleration, 0x01020304u);
  EXPECT_EQ(c->torque, 30000u);
}

TEST(RflexProtocolTest, StuffsEscapeBytesAndRoundTrips) {
  Packet p{kMotPort, kEsc, kMotSystemReport, {kEsc, kStx, kEtx, kNul, kSoh, kEsc, kEsc, 0x42}};
  const std::vector<uint8_t> bytes = encode(p);
  // Every ESC of the body is followed by NUL; only the frame's two ESCs are not.
  int esc_nul = 0;
  for (size_t i = 2; i + 2 < bytes.size(); ++i)
    if (bytes[i] == kEsc) {
      ASSERT_EQ(bytes[i + 1], kNul) << "unstuffed ESC at byte " << i;
      ++esc_nul;
    }
  EXPECT_EQ(esc_nul, 4 + (checksum(p) == kEsc ? 1 : 0));
  Decoder d;
  const auto out = decodeAll(d, bytes);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0], p);
  EXPECT_EQ(d.stats().garbage_bytes, 0u);
  EXPECT_EQ(d.stats().bad_checksums, 0u);
}

TEST(RflexProtocolTest, StuffsAChecksumThatIsEsc) {
  Packet p{kDioPort, 0, kDioReport, {}};
  p.data = {static_cast<uint8_t>(kEsc ^ kDioPort ^ kDioReport ^ 1)};  // makes the checksum ESC
  ASSERT_EQ(checksum(p), kEsc);
  const std::vector<uint8_t> bytes = encode(p);
  EXPECT_EQ(bytes[bytes.size() - 4], kEsc);
  EXPECT_EQ(bytes[bytes.size() - 3], kNul);
  Decoder d;
  const auto out = decodeAll(d, bytes);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0], p);
}

TEST(RflexProtocolTest, DecodesByteByByte) {
  const Packet a = makeSystemReport({1, 2, kTranslationAxis, -5, 7, 8, 9});
  const Packet b = makeDioReport({3, kBumperAddress, 0x001B});
  const std::vector<uint8_t> bytes = concat({encode(a), encode(b), encode(a)});
  Decoder d;
  std::vector<Packet> out;
  for (uint8_t byte : bytes) d.feed(&byte, 1, out);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[0], a);
  EXPECT_EQ(out[1], b);
  EXPECT_EQ(out[2], a);
  EXPECT_EQ(d.stats().packets, 3u);
}

TEST(RflexProtocolTest, SkipsGarbageBetweenPacketsAndCountsIt) {
  const Packet a = makeSystemReportRequest(50000);
  // 3 plain bytes, a lone ESC with the byte after it, an ESC ETX outside any frame.
  const std::vector<uint8_t> garbage = {0x00, 0xFF, 0x02, kEsc, 0x41, kEsc, kEtx};
  Decoder d;
  const auto out = decodeAll(d, concat({garbage, encode(a), garbage, encode(a), garbage}));
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[1], a);
  EXPECT_EQ(d.stats().garbage_bytes, 3 * garbage.size());
  EXPECT_EQ(d.stats().malformed, 0u);
}

TEST(RflexProtocolTest, DropsAndCountsBadChecksums) {
  const Packet a = makeDioReportRequest(100000);
  Decoder d;
  const auto out = decodeAll(d, concat({encodeCorrupt(a), encode(a), encodeCorrupt(a)}));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0], a);
  EXPECT_EQ(d.stats().bad_checksums, 2u);
}

TEST(RflexProtocolTest, DropsCutShortAndWrongLengthFrames) {
  const Packet a = makeMotCommand(kMotBrakeRelease);
  std::vector<uint8_t> cut = encode(makeSystemReportRequest(20000));
  cut.resize(cut.size() - 5);  // the line dropped the tail: the next ESC STX starts over
  std::vector<uint8_t> wrong_length = encode(a);
  wrong_length[5] = 3;  // claims 3 data bytes, has none
  Decoder d;
  const auto out = decodeAll(d, concat({cut, encode(a), wrong_length, encode(a)}));
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0], a);
  EXPECT_EQ(d.stats().malformed, 2u);
}

TEST(RflexProtocolTest, ReportsRoundTrip) {
  const AxisReport r{7, 123456, kRotationAxis, -2000000000, -12345, 99, 100};
  const auto back = parseSystemReport(makeSystemReport(r));
  ASSERT_TRUE(back);
  EXPECT_EQ(back->timestamp_ms, 123456u);
  EXPECT_EQ(back->axis, kRotationAxis);
  EXPECT_EQ(back->position, -2000000000);
  EXPECT_EQ(back->velocity, -12345);
  const auto dio = parseDioReport(makeDioReport({5, kBumperAddress, 0x0F}));
  ASSERT_TRUE(dio);
  EXPECT_EQ(dio->address, kBumperAddress);
  EXPECT_EQ(dio->value, 0x0F);
  EXPECT_EQ(parsePeriodRequest(makeSystemReportRequest(50000)), 50000u);
  EXPECT_FALSE(parseSystemReport(makeDioReport({})));
}

TEST(RflexProtocolTest, RejectsOversizeData) {
  Packet p{kSysPort, 0, 0, std::vector<uint8_t>(256, 1)};
  EXPECT_THROW(encode(p), std::invalid_argument);
}

}  // namespace
}  // namespace coopmap::rflex
