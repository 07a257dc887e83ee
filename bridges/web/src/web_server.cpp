// Implements web_server.hpp: the HTTP + WebSocket server (civetweb): static files from a directory,
// GET /api/stats and /api/model, and pages on the WebSocket /ws.
#include "hapticctrl/web_bridge/web_server.hpp"

#include <civetweb.h>

#include <array>
#include <cstring>
#include <mutex>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace hapticctrl::web_bridge {
namespace {

// RFC 6455 opcodes and the FIN bit of the first header byte, as civetweb hands it over.
constexpr int kOpcodeMask = 0x0f;
constexpr int kFin = 0x80;
constexpr int kContinuation = 0x0;
constexpr int kText = 0x1;
constexpr int kBinary = 0x2;
constexpr int kClose = 0x8;

void count(std::atomic<std::uint64_t>& counter) noexcept {
  counter.fetch_add(1, std::memory_order_relaxed);
}

int send_json(mg_connection* conn, const std::string& body) {
  mg_send_http_ok(conn, "application/json", static_cast<long long>(body.size()));
  mg_write(conn, body.data(), body.size());
  return 200;
}

bool is_get(const mg_connection* conn) {
  const mg_request_info* info = mg_get_request_info(conn);
  return info != nullptr && info->request_method != nullptr &&
         std::strcmp(info->request_method, "GET") == 0;
}

/// Whether `host` (a Host header: name or address, optional port) names this machine by an
/// IPv4 literal or as localhost.
bool names_by_address(const std::string& host) {
  const std::string name = host.substr(0, host.rfind(':'));
  if (name == "localhost") {
    return true;
  }
  return !name.empty() && name.find_first_not_of("0123456789.") == std::string::npos;
}

void init_civetweb_once() {
  static std::once_flag once;
  std::call_once(once, [] { mg_init_library(MG_FEATURES_WEBSOCKET); });
  if (mg_check_feature(MG_FEATURES_WEBSOCKET) == 0) {
    throw std::runtime_error("this civetweb library was built without WebSocket support");
  }
}

}  // namespace

bool same_origin(const char* origin, const char* host, bool loopback_only) {
  if (origin == nullptr) {
    return true;  // browsers always send Origin on a WebSocket; tools do not
  }
  if (host == nullptr || (loopback_only && !names_by_address(host))) {
    return false;
  }
  return std::string(origin) == std::string("http://") + host;
}

/// civetweb's C callbacks; `cbdata` is the WebServer.
struct WebServer::Callbacks {
  static WebServer& server(void* cbdata) { return *static_cast<WebServer*>(cbdata); }

  static int on_connect(const mg_connection* conn, void* cbdata) {
    WebServer& s = server(cbdata);
    if (!same_origin(mg_get_header(conn, "Origin"), mg_get_header(conn, "Host"),
                     s.loopback_only_)) {
      count(s.counters_.refused_origin);
      return 1;
    }
    if (s.pages() >= static_cast<std::size_t>(s.max_pages_)) {
      count(s.counters_.refused_full);
      return 1;
    }
    return 0;
  }

  static void on_ready(mg_connection* conn, void* cbdata) {
    WebServer& s = server(cbdata);
    const mg_request_info* info = mg_get_request_info(conn);
    auto page = std::make_unique<PageSession>();
    page->peer = std::string(info->remote_addr) + ":" + std::to_string(info->remote_port);
    // Greeted and registered under the pages' lock: no broadcast frame can come before the
    // greeting, and none is missed between the greeting's history and the registration.
    const std::lock_guard lock(s.pages_mutex_);
    for (const std::string& frame : s.handler_.greeting()) {
      mg_websocket_write(conn, MG_WEBSOCKET_OPCODE_TEXT, frame.data(), frame.size());
    }
    mg_set_user_connection_data(conn, page.get());
    s.pages_[conn] = Page{conn, std::move(page)};
    count(s.counters_.pages_opened);
  }

  static int on_data(mg_connection* conn, int bits, char* data, std::size_t size, void* cbdata) {
    WebServer& s = server(cbdata);
    const int opcode = bits & kOpcodeMask;
    if (opcode == kClose) {
      return 0;
    }
    if (opcode != kText && opcode != kBinary && opcode != kContinuation) {
      return 1;  // ping, pong: civetweb's business
    }
    if (opcode == kBinary) {
      count(s.counters_.dropped_binary);
      return reply(conn, reply_json("", false, "text JSON messages only"));
    }
    if (opcode == kContinuation || (bits & kFin) == 0) {
      count(s.counters_.dropped_fragmented);
      return 1;
    }
    if (size > kMaxPageMessageBytes) {
      count(s.counters_.dropped_oversized);
      return reply(conn, reply_json("", false, "message too long"));
    }
    auto* page = static_cast<PageSession*>(mg_get_user_connection_data(conn));
    if (page == nullptr) {
      return 1;  // before ready: nothing to attribute it to
    }
    count(s.counters_.messages_in);
    return reply(conn, s.handler_.on_message(*page, std::string_view(data, size)));
  }

  static void on_close(const mg_connection* conn, void* cbdata) {
    WebServer& s = server(cbdata);
    const std::lock_guard lock(s.pages_mutex_);  // waits for a broadcast writing to it
    if (s.pages_.erase(conn) > 0) {
      count(s.counters_.pages_closed);
    }
  }

  static int reply(mg_connection* conn, const std::string& text) {
    if (!text.empty()) {
      mg_websocket_write(conn, MG_WEBSOCKET_OPCODE_TEXT, text.data(), text.size());
    }
    return 1;
  }

  static int on_stats(mg_connection* conn, void* cbdata) {
    if (!is_get(conn)) {
      return mg_send_http_error(conn, 405, "%s", "GET only"), 405;
    }
    WebServer& s = server(cbdata);
    return send_json(
        conn, "{\"server\":" + s.counters_json() + ",\"bridge\":" + s.handler_.stats() + "}");
  }

  static int on_model(mg_connection* conn, void* cbdata) {
    if (!is_get(conn)) {
      return mg_send_http_error(conn, 405, "%s", "GET only"), 405;
    }
    return send_json(conn, server(cbdata).handler_.model());
  }
};

WebServer::WebServer(const ServerSettings& settings, PageHandler& handler)
    : handler_(handler), max_pages_(settings.max_pages), loopback_only_(settings.loopback_only) {
  init_civetweb_once();
  // One server thread per open page (civetweb keeps a WebSocket on its thread) plus four
  // for files and the API.
  const std::string threads = std::to_string(settings.max_pages + 4);
  const std::array<const char*, 17> options{
      "listening_ports", settings.listen.c_str(), "document_root", settings.www_dir.c_str(),
      "num_threads", threads.c_str(), "enable_directory_listing", "no", "request_timeout_ms",
      "5000",
      // A quiet page is pinged, not dropped.
      "websocket_timeout_ms", "5000", "enable_websocket_ping_pong", "yes", "additional_header",
      "X-Content-Type-Options: nosniff", nullptr};
  mg_callbacks callbacks{};
  mg_init_data init{};
  init.callbacks = &callbacks;
  init.user_data = this;
  init.configuration_options = const_cast<const char**>(options.data());
  std::array<char, 256> error_text{};
  unsigned error_code = 0;
  mg_error_data error{&error_code, error_text.data(), error_text.size()};
  context_ = mg_start2(&init, &error);
  if (context_ == nullptr) {
    throw std::runtime_error("cannot start the web server on " + settings.listen + ": " +
                             error_text.data());
  }
  mg_set_websocket_handler(context_, "/ws", Callbacks::on_connect, Callbacks::on_ready,
                           Callbacks::on_data, Callbacks::on_close, this);
  mg_set_request_handler(context_, "/api/stats", Callbacks::on_stats, this);
  mg_set_request_handler(context_, "/api/model", Callbacks::on_model, this);
  std::array<mg_server_port, 4> ports{};
  if (mg_get_server_ports(context_, static_cast<int>(ports.size()), ports.data()) > 0) {
    port_ = static_cast<std::uint16_t>(ports[0].port);
  }
}

WebServer::~WebServer() {
  mg_stop(context_);  // closes every page (their close callbacks run) and joins the threads
}

std::size_t WebServer::broadcast(const std::string& text) {
  const std::lock_guard lock(pages_mutex_);
  std::size_t sent = 0;
  for (auto& [key, page] : pages_) {
    if (mg_websocket_write(page.conn, MG_WEBSOCKET_OPCODE_TEXT, text.data(), text.size()) > 0) {
      ++sent;
    } else {
      count(counters_.push_failures);
    }
  }
  counters_.frames_pushed.fetch_add(sent, std::memory_order_relaxed);
  return sent;
}

std::size_t WebServer::pages() const {
  const std::lock_guard lock(pages_mutex_);
  return pages_.size();
}

std::string WebServer::counters_json() const {
  const auto get = [](const std::atomic<std::uint64_t>& c) {
    return c.load(std::memory_order_relaxed);
  };
  const nlohmann::json j{{"pages", pages()},
                         {"pages_opened", get(counters_.pages_opened)},
                         {"pages_closed", get(counters_.pages_closed)},
                         {"refused_full", get(counters_.refused_full)},
                         {"refused_origin", get(counters_.refused_origin)},
                         {"messages_in", get(counters_.messages_in)},
                         {"dropped_binary", get(counters_.dropped_binary)},
                         {"dropped_fragmented", get(counters_.dropped_fragmented)},
                         {"dropped_oversized", get(counters_.dropped_oversized)},
                         {"frames_pushed", get(counters_.frames_pushed)},
                         {"push_failures", get(counters_.push_failures)}};
  return j.dump();
}

}  // namespace hapticctrl::web_bridge
