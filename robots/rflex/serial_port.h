// A POSIX serial port in raw mode (termios), non-blocking, with reads and writes that wait
// at most a timeout and report a hang-up instead of failing obscurely.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace coopmap {

class SerialError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class SerialPort {
 public:
  // Opens `device` (a tty: /dev/ttyS0, /dev/ttyUSB0, a pseudo-terminal) at `baud`, 8N1, raw, no
  // flow control. Throws SerialError naming the device and the reason.
  SerialPort(const std::string& device, int baud);
  ~SerialPort();
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  enum class ReadResult { kData, kTimeout, kHangUp, kInterrupted };
  // Waits up to `timeout_s` for bytes (or for `wake_fd`, when >= 0, to become readable:
  // kInterrupted), then reads what is there into buf (at most `size`; `got` bytes).
  // kHangUp on end of file, EIO, or POLLHUP/POLLERR: the device went away.
  ReadResult read(uint8_t* buf, size_t size, size_t& got, double timeout_s, int wake_fd = -1);
  // Writes all bytes, waiting at most `timeout_s` for room. Throws SerialError on a timeout
  // or a hang-up.
  void write(const uint8_t* bytes, size_t n, double timeout_s);

  const std::string& device() const { return device_; }
  int baud() const { return baud_; }

  // Whether `baud` is one of the rates this port can set.
  static bool supportedBaud(int baud);

 private:
  std::string device_;
  int baud_;
  int fd_ = -1;
};

}  // namespace coopmap
