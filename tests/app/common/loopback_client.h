// A blocking TCP client of 127.0.0.1:port for the tests of the live page server and of
// `refine --watch --serve`: send bytes, read until a marker arrives, the peer closes, or a
// bounded wait passes. Talks to this machine only.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <string>

namespace occlude::test {

class LoopbackClient {
 public:
  using Clock = std::chrono::steady_clock;

  /// Connects at once; `patience` bounds every ReadUntil.
  explicit LoopbackClient(int port, std::chrono::milliseconds patience = std::chrono::seconds(5))
      : fd_(::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0)), patience_(patience) {
    sockaddr_in sa{};
    sa.sin_family = AF_INET;
    sa.sin_port = htons(static_cast<std::uint16_t>(port));
    sa.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = ::connect(fd_, reinterpret_cast<sockaddr*>(&sa), sizeof sa) == 0;
  }
  ~LoopbackClient() { ::close(fd_); }
  LoopbackClient(const LoopbackClient&) = delete;
  LoopbackClient& operator=(const LoopbackClient&) = delete;

  bool connected() const { return connected_; }
  void Send(const std::string& bytes) { ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL); }
  /// Reads until `stop` appears in what was read (at or after byte `from`), the peer closes,
  /// or the patience passes; returns everything read so far.
  std::string ReadUntil(const std::string& stop, std::size_t from = 0) {
    const auto deadline = Clock::now() + patience_;
    while (received_.find(stop, from) == std::string::npos && !closed_ && Clock::now() < deadline) {
      pollfd p = {fd_, POLLIN, 0};
      if (::poll(&p, 1, 100) <= 0) continue;
      char buffer[4096];
      const ssize_t n = ::recv(fd_, buffer, sizeof buffer, 0);
      if (n <= 0) closed_ = true;
      if (n > 0) received_.append(buffer, static_cast<std::size_t>(n));
    }
    return received_;
  }
  std::string ReadAll() { return ReadUntil(std::string(1, '\0') + "never"); }
  bool closed() const { return closed_; }

 private:
  int fd_;
  std::chrono::milliseconds patience_;
  bool connected_ = false;
  bool closed_ = false;
  std::string received_;
};

}  // namespace occlude::test
