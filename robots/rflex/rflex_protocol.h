// The rFLEX serial protocol of RWI's B-14/B-21/ATRV bases, as the public Player and CARMEN
// rflex drivers describe it, written from that description.
//
// A packet on the wire:
//
//   ESC STX | port id opcode length data[length] checksum | ESC ETX
//   1B  02  |  u8  u8   u8     u8     u8 x length     u8  | 1B  03
//
// - The body (port .. checksum) is byte-stuffed: an ESC (0x1B) in it is sent as ESC NUL
//   (1B 00); the receiver drops the NUL. ESC SOH (1B 01) inside a body is ignored, as the
//   controller may send it. ESC STX inside a body abandons the frame and starts a new one.
// - checksum = XOR of port, id, opcode, length and the data bytes (before stuffing).
// - Multi-byte fields are big-endian (network order); length <= 255.
//
// Ports and the messages used here (data offsets from the first data byte):
//
//   MOT (2) MOT_AXIS_SET_DIR (7), host -> base, 14 bytes: axis u8 (0 translation,
//     1 rotation), |velocity| u32 (ticks/s), acceleration u32 (ticks/s^2), torque u32,
//     direction u8 (1 positive: forward / counter-clockwise, 0 negative).
//   MOT (2) MOT_SYSTEM_REPORT_REQ (34), host -> base, 8 bytes: period u32 (microseconds,
//     0 stops the reports), axis mask u32 (3: both axes).
//   MOT (2) MOT_SYSTEM_REPORT (33), base -> host, 25 bytes: status u32, timestamp u32 (ms),
//     axis u8, position i32 (encoder ticks, wrapping), velocity i32 (ticks/s),
//     acceleration u32, torque u32. One report per axis and period.
//   MOT (2) MOT_SET_DEFAULTS (10), MOT_BRAKE_SET (11), MOT_BRAKE_RELEASE (12): no data.
//   DIO (5) DIO_REPORTS_REQ (0), host -> base, 4 bytes: period u32 (microseconds).
//   DIO (5) DIO_REPORT (1), base -> host, 7 bytes: timestamp u32 (ms), address u8,
//     value u16. Address 0x40 carries the bump panel: any set bit is a contact.
//   SONAR (4), SYS (1), JSTK (3), IR (6): recognised on receipt and ignored.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace coopmap::rflex {

inline constexpr uint8_t kEsc = 0x1B;
inline constexpr uint8_t kStx = 0x02;
inline constexpr uint8_t kEtx = 0x03;
inline constexpr uint8_t kNul = 0x00;
inline constexpr uint8_t kSoh = 0x01;

enum Port : uint8_t {
  kSysPort = 1,
  kMotPort = 2,
  kJoystickPort = 3,
  kSonarPort = 4,
  kDioPort = 5,
  kIrPort = 6
};

enum MotOpcode : uint8_t {
  kMotAxisSetDir = 7,
  kMotSetDefaults = 10,
  kMotBrakeSet = 11,
  kMotBrakeRelease = 12,
  kMotSystemReport = 33,
  kMotSystemReportReq = 34
};

enum DioOpcode : uint8_t { kDioReportsReq = 0, kDioReport = 1 };

inline constexpr uint8_t kBumperAddress = 0x40;
inline constexpr uint8_t kTranslationAxis = 0;
inline constexpr uint8_t kRotationAxis = 1;

// One packet, unframed and unstuffed.
struct Packet {
  uint8_t port = 0;
  uint8_t id = 0;  // sequence / device id; echoed, not interpreted
  uint8_t opcode = 0;
  std::vector<uint8_t> data;  // at most 255 bytes

  bool operator==(const Packet&) const = default;
};

// XOR of port, id, opcode, length and data.
uint8_t checksum(const Packet& p);
// The framed, stuffed bytes of a packet (throws std::invalid_argument for > 255 data bytes).
std::vector<uint8_t> encode(const Packet& p);
// The same frame with a wrong checksum, to inject faults in tests.
std::vector<uint8_t> encodeCorrupt(const Packet& p);

// Big-endian field helpers.
void putU32(std::vector<uint8_t>& out, uint32_t v);
void putU16(std::vector<uint8_t>& out, uint16_t v);
uint32_t getU32(const uint8_t* p);
uint16_t getU16(const uint8_t* p);

// What a decoder has seen so far.
struct DecoderStats {
  uint64_t packets = 0;        // good packets
  uint64_t garbage_bytes = 0;  // bytes outside any frame, skipped
  uint64_t bad_checksums = 0;  // complete frames whose checksum did not match: dropped
  uint64_t malformed = 0;      // frames cut short, too long, or with a wrong length: dropped
};

// Turns a byte stream into packets, resynchronizing on ESC STX after garbage, dropping
// frames with a bad checksum or length.
class Decoder {
 public:
  // Feeds bytes; complete good packets are appended to `out`.
  void feed(const uint8_t* bytes, size_t n, std::vector<Packet>& out);
  const DecoderStats& stats() const { return stats_; }

 private:
  enum class State { kIdle, kIdleEsc, kBody, kBodyEsc };
  void finishFrame(std::vector<Packet>& out);
  State state_ = State::kIdle;
  std::vector<uint8_t> body_;
  DecoderStats stats_;
};

// MOT_AXIS_SET_DIR: drive one axis at a signed velocity (ticks/s).
Packet makeAxisSetDir(uint8_t axis, int32_t velocity, uint32_t acceleration, uint32_t torque);
// MOT_SYSTEM_REPORT_REQ: reports of both axes every `period_us` (0: off).
Packet makeSystemReportRequest(uint32_t period_us);
// DIO_REPORTS_REQ: digital I/O reports every `period_us` (0: off).
Packet makeDioReportRequest(uint32_t period_us);
// A MOT packet without data (kMotSetDefaults, kMotBrakeSet, kMotBrakeRelease).
Packet makeMotCommand(MotOpcode opcode);

// A decoded MOT_AXIS_SET_DIR.
struct AxisCommand {
  uint8_t axis = 0;
  int32_t velocity = 0;  // ticks/s, signed
  uint32_t acceleration = 0;
  uint32_t torque = 0;
};
std::optional<AxisCommand> parseAxisSetDir(const Packet& p);

// A decoded MOT_SYSTEM_REPORT.
struct AxisReport {
  uint32_t status = 0;
  uint32_t timestamp_ms = 0;
  uint8_t axis = 0;
  int32_t position = 0;  // ticks, wrapping
  int32_t velocity = 0;  // ticks/s
  uint32_t acceleration = 0;
  uint32_t torque = 0;
};
Packet makeSystemReport(const AxisReport& r);
std::optional<AxisReport> parseSystemReport(const Packet& p);

// A decoded DIO_REPORT.
struct DioReport {
  uint32_t timestamp_ms = 0;
  uint8_t address = 0;
  uint16_t value = 0;
};
Packet makeDioReport(const DioReport& r);
std::optional<DioReport> parseDioReport(const Packet& p);

// The period field of a report request (MOT_SYSTEM_REPORT_REQ or DIO_REPORTS_REQ).
std::optional<uint32_t> parsePeriodRequest(const Packet& p);

}  // namespace coopmap::rflex
