#include "robots/rflex/serial_port.h"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>

namespace coopmap {
namespace {

speed_t speedOf(int baud) {
  switch (baud) {
    case 9600:
      return B9600;
    case 19200:
      return B19200;
    case 38400:
      return B38400;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    case 230400:
      return B230400;
    default:
      return B0;
  }
}

int timeoutMs(double s) { return s <= 0.0 ? 0 : static_cast<int>(std::ceil(s * 1000.0)); }

bool hangUpErrno(int e) { return e == EIO || e == ENXIO || e == ENODEV || e == EPIPE; }

}  // namespace

bool SerialPort::supportedBaud(int baud) { return speedOf(baud) != B0; }

SerialPort::SerialPort(const std::string& device, int baud) : device_(device), baud_(baud) {
  if (!supportedBaud(baud))
    throw SerialError("serial port " + device + ": baud rate " + std::to_string(baud) +
                      " not supported (9600, 19200, 38400, 57600, 115200 or 230400)");
  fd_ = ::open(device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0)
    throw SerialError("serial port " + device + ": cannot open: " + std::strerror(errno));
  termios t{};
  if (!::isatty(fd_) || ::tcgetattr(fd_, &t) != 0) {
    const std::string why = std::strerror(errno);
    ::close(fd_);
    fd_ = -1;
    throw SerialError("serial port " + device + ": not a terminal device (" + why + ")");
  }
  // Raw 8N1: no echo, no line editing, no character translation, no flow control.
  t.c_iflag &= ~static_cast<tcflag_t>(IGNBRK | BRKINT | PARMRK | ISTRIP | INLCR | IGNCR | ICRNL |
                                      IXON | IXOFF | IXANY);
  t.c_oflag &= ~static_cast<tcflag_t>(OPOST);
  t.c_lflag &= ~static_cast<tcflag_t>(ECHO | ECHONL | ICANON | ISIG | IEXTEN);
  t.c_cflag &= ~static_cast<tcflag_t>(CSIZE | PARENB | CSTOPB | CRTSCTS);
  t.c_cflag |= CS8 | CREAD | CLOCAL;
  t.c_cc[VMIN] = 0;
  t.c_cc[VTIME] = 0;
  cfsetispeed(&t, speedOf(baud));
  cfsetospeed(&t, speedOf(baud));
  if (::tcsetattr(fd_, TCSANOW, &t) != 0) {
    const std::string why = std::strerror(errno);
    ::close(fd_);
    fd_ = -1;
    throw SerialError("serial port " + device + ": cannot set raw mode at " + std::to_string(baud) +
                      " baud: " + why);
  }
  ::tcflush(fd_, TCIOFLUSH);
}

SerialPort::~SerialPort() {
  if (fd_ >= 0) ::close(fd_);
}

SerialPort::ReadResult SerialPort::read(uint8_t* buf, size_t size, size_t& got, double timeout_s,
                                        int wake_fd) {
  got = 0;
  pollfd fds[2] = {{fd_, POLLIN, 0}, {wake_fd, POLLIN, 0}};
  const nfds_t nfds = wake_fd >= 0 ? 2 : 1;
  int r = ::poll(fds, nfds, timeoutMs(timeout_s));
  if (r < 0) return errno == EINTR ? ReadResult::kTimeout : ReadResult::kHangUp;
  if (r == 0) return ReadResult::kTimeout;
  if (nfds == 2 && (fds[1].revents & POLLIN) && !(fds[0].revents & POLLIN))
    return ReadResult::kInterrupted;
  if (fds[0].revents & POLLIN) {
    const ssize_t n = ::read(fd_, buf, size);
    if (n > 0) {
      got = static_cast<size_t>(n);
      return ReadResult::kData;
    }
    if (n == 0) return ReadResult::kHangUp;  // end of file
    if (errno == EAGAIN || errno == EINTR) return ReadResult::kTimeout;
    return ReadResult::kHangUp;
  }
  if (fds[0].revents & (POLLHUP | POLLERR | POLLNVAL)) return ReadResult::kHangUp;
  return ReadResult::kTimeout;
}

void SerialPort::write(const uint8_t* bytes, size_t n, double timeout_s) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
  size_t done = 0;
  while (done < n) {
    const ssize_t w = ::write(fd_, bytes + done, n - done);
    if (w > 0) {
      done += static_cast<size_t>(w);
      continue;
    }
    if (w < 0 && hangUpErrno(errno))
      throw SerialError("serial port " + device_ + ": hung up (" + std::strerror(errno) + ")");
    if (w < 0 && errno != EAGAIN && errno != EINTR)
      throw SerialError("serial port " + device_ + ": write failed: " + std::strerror(errno));
    const double left = std::chrono::duration<double>(deadline - Clock::now()).count();
    if (left <= 0.0)
      throw SerialError("serial port " + device_ + ": write timed out after " +
                        std::to_string(timeout_s) + " s (device not draining)");
    pollfd p{fd_, POLLOUT, 0};
    if (::poll(&p, 1, timeoutMs(left)) > 0 && (p.revents & (POLLHUP | POLLERR | POLLNVAL)))
      throw SerialError("serial port " + device_ + ": hung up");
  }
}

}  // namespace coopmap
