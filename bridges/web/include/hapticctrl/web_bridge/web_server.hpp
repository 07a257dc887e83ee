#pragma once
/// @file web_server.hpp
/// The HTTP + WebSocket server (civetweb): static files from a directory, GET /api/stats and
/// /api/model, and pages on the WebSocket /ws. It refuses WebSocket connections whose Origin is
/// another site (so that a page elsewhere cannot drive the arm through a browser on this
/// network) and beyond `max_pages`; it drops binary, fragmented and oversized messages, counted.
/// Closed or vanished browsers are removed when civetweb closes their connection.
///
/// Real-time contract: soft-RT; every method may allocate and lock. The constructor throws
/// std::runtime_error (with the address) when the server cannot start.
#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "hapticctrl/web_bridge/page_gateway.hpp"

struct mg_context;
struct mg_connection;

namespace hapticctrl::web_bridge {

/// What the server asks of the bridge.
class PageHandler {
 public:
  virtual ~PageHandler() = default;
  /// Frames for a page that just connected (the model, the recent events, ...).
  virtual std::vector<std::string> greeting() = 0;
  /// One text message of `page`; returns the reply, or nothing.
  virtual std::string on_message(PageSession& page, std::string_view text) = 0;
  /// The body of GET /api/model.
  virtual std::string model() = 0;
  /// The bridge's part of GET /api/stats (a JSON object).
  virtual std::string stats() = 0;
};

struct ServerSettings {
  std::string listen = "127.0.0.1:8080";  ///< "ADDRESS:PORT"; port 0: any free one
  std::string www_dir;
  int max_pages = 8;
  /// Serving this host only: a page must name the server by an IPv4 address or "localhost"
  /// (its Host header), so that a site re-resolving its name to 127.0.0.1 (DNS rebinding)
  /// cannot pass for a page of this server.
  bool loopback_only = true;
};

/// Whether a WebSocket upgrade comes from a page of this server: no Origin (not a browser), or
/// an Origin equal to "http://" + `host`, where, for a loopback-only server, `host` names it by
/// an IPv4 address or "localhost". Pure function (no I/O); `origin`/`host` may be null.
[[nodiscard]] bool same_origin(const char* origin, const char* host, bool loopback_only);

struct ServerCounters {
  std::atomic<std::uint64_t> pages_opened{0};
  std::atomic<std::uint64_t> pages_closed{0};
  std::atomic<std::uint64_t> refused_full{0};    ///< beyond max_pages
  std::atomic<std::uint64_t> refused_origin{0};  ///< Origin not this server
  std::atomic<std::uint64_t> messages_in{0};     ///< text messages handled
  std::atomic<std::uint64_t> dropped_binary{0};
  std::atomic<std::uint64_t> dropped_fragmented{0};
  std::atomic<std::uint64_t> dropped_oversized{0};
  std::atomic<std::uint64_t> frames_pushed{0};
  std::atomic<std::uint64_t> push_failures{0};
};

class WebServer {
 public:
  WebServer(const ServerSettings& settings, PageHandler& handler);
  ~WebServer();
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  /// The port it listens on (the chosen one when asked for port 0).
  [[nodiscard]] std::uint16_t port() const noexcept { return port_; }
  /// Sends `text` to every open page; a page whose write fails is counted, and civetweb closes
  /// it. Returns how many pages got it.
  std::size_t broadcast(const std::string& text);
  [[nodiscard]] std::size_t pages() const;
  [[nodiscard]] const ServerCounters& counters() const noexcept { return counters_; }
  /// {"pages":n,"pages_opened":...}: the server's counters.
  [[nodiscard]] std::string counters_json() const;

 private:
  struct Callbacks;  // civetweb's C callbacks, friends of this class

  PageHandler& handler_;
  int max_pages_;
  bool loopback_only_;
  std::uint16_t port_ = 0;
  mutable std::mutex pages_mutex_;  // held while writing to pages: a close waits for it
  struct Page {
    mg_connection* conn = nullptr;
    std::unique_ptr<PageSession> session;
  };
  std::map<const mg_connection*, Page> pages_;
  ServerCounters counters_;
  mg_context* context_ = nullptr;
};

}  // namespace hapticctrl::web_bridge
