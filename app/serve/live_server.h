// A minimal local HTTP server for the live pages (`refine --watch --serve`): it
// serves one HTML page at "/" and pushes events to every open page as
// server-sent events at "/events" (EventSource in the page). Nothing else (an
// empty answer for /favicon.ico, 404 for any other path): GET and HEAD only, one
// response per connection except the event streams.
//
// Safety: binds 127.0.0.1 by default and refuses any address outside 127.0.0.0/8
// unless the caller allows it explicitly and gives a warning sink (the page shows
// patient data and has no authentication); a request must arrive whole within
// the read timeout and within the size limit (else 408, 431 or 413, and the
// connection is closed); at most `max_clients` connections; a client that does not
// read its event stream is dropped rather than buffered without bound.
//
// Threads: the server runs on a thread of its own (one poll loop, no thread per
// connection); SetPage, Publish and Stop may be called from any thread, and
// RequestStopFromSignal from a signal handler (Ctrl-C).
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>

namespace occlude::app {

struct LiveServerOptions {
  std::string address = "127.0.0.1";  ///< IPv4 address to bind ("localhost" = 127.0.0.1)
  int port = 0;                       ///< 0..65535; 0 = any free port (see LiveServer::port)
  /// An address outside 127.0.0.0/8 is refused unless this is true and `warn` is set.
  bool allow_non_loopback = false;
  /// Told, once, when the server listens on a non-loopback address.
  std::function<void(const std::string&)> warn;
  double read_timeout_s = 5.0;           ///< a request (head and body) must arrive within this
  std::size_t max_request_bytes = 8192;  ///< request line, headers and body at most
  std::size_t max_clients = 32;          ///< open connections at most; more get 503
  double keepalive_s = 15.0;             ///< a comment line on idle event streams this often
  /// Unread event bytes on a stream beyond which it is dropped at the next Publish.
  std::size_t max_stream_backlog_bytes = 1 << 20;
};

class LiveServer {
 public:
  /// Binds and starts serving. Throws std::invalid_argument naming the option (an
  /// address that is not IPv4, a non-loopback address not allowed, allowed without
  /// `warn`, a port or limit out of range) and std::runtime_error when the address
  /// and port cannot be bound (naming them and the reason, e.g. in use).
  explicit LiveServer(const LiveServerOptions& options);
  ~LiveServer();  ///< Stop()
  LiveServer(const LiveServer&) = delete;
  LiveServer& operator=(const LiveServer&) = delete;

  int port() const;         ///< the bound port
  std::string url() const;  ///< "http://ADDRESS:PORT/"

  /// Replaces the page served at "/" (UTF-8 HTML).
  void SetPage(std::string html);
  /// Sends `event` with `data` (any text; each line becomes one "data:" line) to every
  /// open event stream, and keeps it: a stream opened later receives the last event
  /// first. Throws std::invalid_argument when `event` is empty or holds a line break.
  void Publish(const std::string& event, const std::string& data);
  /// Open event streams.
  std::size_t clients() const;

  /// Closes the listening socket and every connection and joins the server's thread;
  /// returns promptly (it waits for no client). Idempotent; any thread but the server's.
  void Stop();
  /// Async-signal-safe: asks the server's thread to finish (Stop() still joins it).
  void RequestStopFromSignal() noexcept;
  /// True once the server's thread has finished (after a stop request).
  bool stopped() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace occlude::app
