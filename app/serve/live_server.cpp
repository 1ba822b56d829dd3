// The live page server (see live_server.h): one thread, one poll loop over the
// listening socket, a wake-up pipe and the connections, all non-blocking.
#include "serve/live_server.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "serve/http_head_internal.h"

namespace occlude::app {
// Named, not anonymous: LiveServer::Impl holds these (unity builds warn otherwise).
namespace live_server_internal {

using Clock = std::chrono::steady_clock;
using serve_detail::HeadStatus;
using serve_detail::HttpHead;

/// How long a connection is read (and discarded) after its response before it is closed,
/// so the client gets the response rather than a reset.
constexpr std::chrono::milliseconds kLinger{1000};

Clock::duration Seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

struct Connection {
  int fd = -1;
  std::string in;
  std::string out;
  Clock::time_point deadline;  ///< the request's, or the linger's once closing
  bool streaming = false;      ///< an open /events stream
  bool closing = false;        ///< close once `out` is sent (and the linger is over)
  bool dead = false;
};

// The IPv4 address `text` ("localhost" = 127.0.0.1), checked against the options.
in_addr CheckedAddress(const LiveServerOptions& o) {
  const std::string text = o.address == "localhost" ? "127.0.0.1" : o.address;
  in_addr addr{};
  if (::inet_pton(AF_INET, text.c_str(), &addr) != 1) {
    throw std::invalid_argument("address: '" + o.address +
                                "' is not an IPv4 address; give one such as 127.0.0.1");
  }
  const bool loopback = (ntohl(addr.s_addr) >> 24) == 127;
  if (!loopback && !o.allow_non_loopback) {
    throw std::invalid_argument("address: " + o.address +
                                " is not a loopback address (127.x.x.x); the page shows patient "
                                "data without a password, so other addresses must be allowed "
                                "explicitly");
  }
  if (!loopback && !o.warn) {
    throw std::invalid_argument("warn: serving on the non-loopback address " + o.address +
                                " needs a warning sink to tell the user");
  }
  return addr;
}

void CheckLimits(const LiveServerOptions& o) {
  if (o.port < 0 || o.port > 65535) throw std::invalid_argument("port: must be in 0..65535");
  if (!(o.read_timeout_s > 0)) throw std::invalid_argument("read_timeout_s: must be positive");
  if (o.max_request_bytes < 256) throw std::invalid_argument("max_request_bytes: at least 256");
  if (o.max_clients < 1) throw std::invalid_argument("max_clients: at least 1");
  if (!(o.keepalive_s > 0)) throw std::invalid_argument("keepalive_s: must be positive");
}

}  // namespace live_server_internal

using namespace live_server_internal;

struct LiveServer::Impl {
  LiveServerOptions options;
  std::string address;
  int port = 0;
  int listen_fd = -1;
  int wake[2] = {-1, -1};
  std::thread thread;
  std::atomic<bool> stop_requested{false};
  std::atomic<bool> finished{false};
  std::mutex stop_mutex;  ///< serializes Stop()

  mutable std::mutex mutex;  ///< guards the four below
  std::string page;
  std::vector<std::string> queue;  ///< events not yet handed to the streams
  std::string last_event;
  std::size_t streams = 0;

  std::vector<Connection> connections;  ///< the server thread's only
  Clock::time_point next_ping;

  void Listen(const in_addr& addr);
  void Run();
  int PollTimeoutMs(Clock::time_point now) const;
  void Accept(Clock::time_point now);
  void ReadFrom(Connection& c, Clock::time_point now);
  void Respond(Connection& c, const HttpHead& head, Clock::time_point now);
  void Fail(Connection& c, int status, Clock::time_point now);
  void WriteTo(Connection& c);
  void Deliver();
  void Expire(Clock::time_point now);
  void Sweep();
};

void LiveServer::Impl::Listen(const in_addr& addr) {
  listen_fd = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  const int on = 1;
  ::setsockopt(listen_fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
  sockaddr_in sa{};
  sa.sin_family = AF_INET;
  sa.sin_addr = addr;
  sa.sin_port = htons(static_cast<std::uint16_t>(options.port));
  if (listen_fd < 0 || ::bind(listen_fd, reinterpret_cast<sockaddr*>(&sa), sizeof sa) != 0 ||
      ::listen(listen_fd, 16) != 0) {
    const int error = errno;
    if (listen_fd >= 0) ::close(listen_fd);
    listen_fd = -1;
    throw std::runtime_error(address + ":" + std::to_string(options.port) + ": cannot listen (" +
                             std::strerror(error) +
                             "); choose another port, or 0 for any free one");
  }
  socklen_t len = sizeof sa;
  ::getsockname(listen_fd, reinterpret_cast<sockaddr*>(&sa), &len);
  port = ntohs(sa.sin_port);
  if (::pipe2(wake, O_NONBLOCK | O_CLOEXEC) != 0) {
    throw std::runtime_error(std::string("live server: pipe: ") + std::strerror(errno));
  }
}

void LiveServer::Impl::Run() {
  next_ping = Clock::now() + Seconds(options.keepalive_s);
  std::vector<pollfd> fds;
  while (!stop_requested.load()) {
    fds.assign({{wake[0], POLLIN, 0}, {listen_fd, POLLIN, 0}});
    for (const Connection& c : connections) {
      fds.push_back({c.fd, static_cast<short>(POLLIN | (c.out.empty() ? 0 : POLLOUT)), 0});
    }
    ::poll(fds.data(), fds.size(), PollTimeoutMs(Clock::now()));
    char drain[64];
    while (::read(wake[0], drain, sizeof drain) > 0) {
    }
    if (stop_requested.load()) break;
    const Clock::time_point now = Clock::now();
    Deliver();
    const std::size_t polled = fds.size() - 2;
    if (fds[1].revents & POLLIN) Accept(now);
    for (std::size_t i = 0; i < polled; ++i) {
      const short ev = fds[i + 2].revents;
      if (ev & (POLLIN | POLLHUP | POLLERR)) ReadFrom(connections[i], now);
      if ((ev & POLLOUT) && !connections[i].dead) WriteTo(connections[i]);
    }
    Expire(now);
    Sweep();
  }
  for (Connection& c : connections) ::close(c.fd);
  connections.clear();
  finished.store(true);
}

int LiveServer::Impl::PollTimeoutMs(Clock::time_point now) const {
  Clock::time_point next = std::min(next_ping, now + std::chrono::seconds(1));
  for (const Connection& c : connections) {
    if (!c.streaming) next = std::min(next, c.deadline);
  }
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(next - now).count();
  return static_cast<int>(std::clamp<long long>(ms + 1, 0, 1000));
}

void LiveServer::Impl::Accept(Clock::time_point now) {
  for (;;) {
    const int fd = ::accept4(listen_fd, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) return;  // EAGAIN: none left (or a transient error: poll again)
    Connection c;
    c.fd = fd;
    c.deadline = now + Seconds(options.read_timeout_s);
    if (connections.size() >= options.max_clients) Fail(c, 503, now);
    connections.push_back(std::move(c));
    WriteTo(connections.back());
  }
}

void LiveServer::Impl::ReadFrom(Connection& c, Clock::time_point now) {
  char buffer[16384];
  const ssize_t n = ::recv(c.fd, buffer, sizeof buffer, 0);
  if (n < 0 && (errno == EAGAIN || errno == EINTR)) return;
  if (n <= 0) {
    c.dead = true;  // the client closed (or the connection broke)
    return;
  }
  if (c.streaming || c.closing) return;  // nothing more is read after a request
  c.in.append(buffer, static_cast<std::size_t>(n));
  HttpHead head;
  switch (serve_detail::ParseHttpHead(c.in, options.max_request_bytes, &head)) {
    case HeadStatus::kIncomplete:
      return;
    case HeadStatus::kTooLarge:
      return Fail(c, 431, now);
    case HeadStatus::kBad:
      return Fail(c, 400, now);
    case HeadStatus::kComplete:
      break;
  }
  if (head.content_length > options.max_request_bytes - head.head_bytes) return Fail(c, 413, now);
  if (c.in.size() < head.head_bytes + head.content_length) return;  // the body is on its way
  Respond(c, head, now);
}

void LiveServer::Impl::Respond(Connection& c, const HttpHead& head, Clock::time_point now) {
  const bool head_only = head.method == "HEAD";
  if (head.method != "GET" && !head_only) return Fail(c, 405, now);
  c.in.clear();
  if (head.path == "/" || head.path == "/index.html") {
    std::lock_guard<std::mutex> lock(mutex);
    c.out = serve_detail::HttpResponse(200, "text/html; charset=utf-8", page, head_only);
  } else if (head.path == "/favicon.ico") {  // browsers ask; no icon, and no error in the console
    c.out = serve_detail::HttpResponse(204, "image/x-icon", "", head_only);
  } else if (head.path == "/events" && !head_only) {
    std::lock_guard<std::mutex> lock(mutex);
    c.out = serve_detail::EventStreamHead() + "retry: 1000\n\n" + last_event;
    c.streaming = true;
    return WriteTo(c);
  } else {
    return Fail(c, 404, now);
  }
  c.closing = true;
  c.deadline = now + kLinger;
  WriteTo(c);
}

void LiveServer::Impl::Fail(Connection& c, int status, Clock::time_point now) {
  const char* why = status == 431   ? "the request is too large\n"
                    : status == 413 ? "the request body is too large\n"
                    : status == 408 ? "the request did not arrive in time\n"
                    : status == 503 ? "too many connections\n"
                    : status == 405 ? "only GET and HEAD are served\n"
                    : status == 404 ? "not found: this server serves / and /events\n"
                                    : "bad request\n";
  c.in.clear();
  c.out = serve_detail::HttpResponse(status, "text/plain; charset=utf-8", why);
  c.closing = true;
  c.deadline = now + kLinger;
}

void LiveServer::Impl::WriteTo(Connection& c) {
  while (!c.out.empty()) {
    const ssize_t n = ::send(c.fd, c.out.data(), c.out.size(), MSG_NOSIGNAL);
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) return;
    if (n <= 0) {
      c.dead = true;
      return;
    }
    c.out.erase(0, static_cast<std::size_t>(n));
  }
  if (c.closing) ::shutdown(c.fd, SHUT_WR);  // then read until the client closes or the linger ends
}

void LiveServer::Impl::Deliver() {
  std::vector<std::string> events;
  {
    std::lock_guard<std::mutex> lock(mutex);
    events.swap(queue);
  }
  if (events.empty()) return;
  for (Connection& c : connections) {
    if (!c.streaming || c.dead) continue;
    // Unread bytes from earlier events beyond the limit: the client does not read. (Checked
    // before the new events, so one event larger than the limit still goes to a reader.)
    if (c.out.size() > options.max_stream_backlog_bytes) {
      c.dead = true;
      continue;
    }
    for (const std::string& e : events) c.out += e;
    WriteTo(c);
  }
}

void LiveServer::Impl::Expire(Clock::time_point now) {
  const bool ping = now >= next_ping;
  if (ping) next_ping = now + Seconds(options.keepalive_s);
  for (Connection& c : connections) {
    if (c.dead) continue;
    if (c.streaming) {
      if (ping && c.out.empty()) c.out = ": ping\n\n";
    } else if (c.closing) {
      if (now > c.deadline) c.dead = true;
      continue;
    } else if (now > c.deadline) {
      Fail(c, 408, now);
    }
    if (!c.out.empty()) WriteTo(c);
  }
}

void LiveServer::Impl::Sweep() {
  std::size_t open_streams = 0;
  for (Connection& c : connections) {
    if (c.dead) ::close(c.fd);
    if (!c.dead && c.streaming) ++open_streams;
  }
  connections.erase(std::remove_if(connections.begin(), connections.end(),
                                   [](const Connection& c) { return c.dead; }),
                    connections.end());
  std::lock_guard<std::mutex> lock(mutex);
  streams = open_streams;
}

LiveServer::LiveServer(const LiveServerOptions& options) : impl_(std::make_unique<Impl>()) {
  CheckLimits(options);
  const in_addr addr = CheckedAddress(options);
  impl_->options = options;
  impl_->address = options.address == "localhost" ? "127.0.0.1" : options.address;
  impl_->Listen(addr);
  if ((ntohl(addr.s_addr) >> 24) != 127) {
    options.warn("serving on " + url() +
                 ", which other machines on the network can reach: the page shows patient data "
                 "and has no password; bind 127.0.0.1 unless that is what you want");
  }
  impl_->thread = std::thread([this] { impl_->Run(); });
}

LiveServer::~LiveServer() { Stop(); }

int LiveServer::port() const { return impl_->port; }

std::string LiveServer::url() const {
  return "http://" + impl_->address + ":" + std::to_string(impl_->port) + "/";
}

void LiveServer::SetPage(std::string html) {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->page = std::move(html);
}

void LiveServer::Publish(const std::string& event, const std::string& data) {
  if (event.empty() || event.find_first_of("\r\n") != std::string::npos) {
    throw std::invalid_argument("event: a name of one line is needed, got '" + event + "'");
  }
  {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    impl_->last_event = serve_detail::EventText(event, data);
    impl_->queue.push_back(impl_->last_event);
  }
  const char one = 1;
  [[maybe_unused]] const ssize_t n = ::write(impl_->wake[1], &one, 1);  // full pipe: awake anyway
}

std::size_t LiveServer::clients() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->streams;
}

void LiveServer::RequestStopFromSignal() noexcept {
  impl_->stop_requested.store(true);
  const char one = 1;
  [[maybe_unused]] const ssize_t n = ::write(impl_->wake[1], &one, 1);
}

bool LiveServer::stopped() const { return impl_->finished.load(); }

void LiveServer::Stop() {
  std::lock_guard<std::mutex> lock(impl_->stop_mutex);
  RequestStopFromSignal();
  if (impl_->thread.joinable()) impl_->thread.join();
  for (int* fd : {&impl_->listen_fd, &impl_->wake[0], &impl_->wake[1]}) {
    if (*fd >= 0) ::close(*fd);
    *fd = -1;
  }
}

}  // namespace occlude::app
