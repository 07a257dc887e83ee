#pragma once
/// @file websocket_client.hpp
/// A deliberately raw WebSocket client for tests (RFC 6455 over a blocking TCP socket): it can
/// send what a browser never would (binary, fragmented, oversized, truncated frames, or bytes
/// that are no frame at all) and vanish without a close handshake.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace hapticctrl::test {

class WebSocketClient {
 public:
  /// Connects to 127.0.0.1:`port` and upgrades on `path`; `origin` empty sends no Origin header.
  /// status() is the HTTP status of the upgrade (101 when accepted).
  WebSocketClient(std::uint16_t port, const std::string& origin = "",
                  const std::string& path = "/ws") {
    fd_ = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(port);
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (fd_ < 0 || connect(fd_, reinterpret_cast<const sockaddr*>(&to), sizeof to) != 0) {
      throw std::runtime_error("cannot connect to 127.0.0.1:" + std::to_string(port));
    }
    std::string request = "GET " + path + " HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) +
                          "\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
                          "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n"
                          "Sec-WebSocket-Version: 13\r\n";
    if (!origin.empty()) {
      request += "Origin: " + origin + "\r\n";
    }
    request += "\r\n";
    send_raw(request);
    std::string head;
    char c = 0;
    while (head.find("\r\n\r\n") == std::string::npos && wait_readable(2000) &&
           recv(fd_, &c, 1, 0) == 1) {
      head += c;
    }
    status_ = head.size() > 12 ? std::stoi(head.substr(9, 3)) : 0;
  }
  ~WebSocketClient() {
    if (fd_ >= 0) {
      close(fd_);
    }
  }
  WebSocketClient(const WebSocketClient&) = delete;
  WebSocketClient& operator=(const WebSocketClient&) = delete;

  [[nodiscard]] int status() const { return status_; }

  /// Sends one masked frame; `first_byte` is FIN|RSV|opcode (0x81: a whole text message).
  void send_frame(std::uint8_t first_byte, const std::string& payload) {
    std::string frame(1, static_cast<char>(first_byte));
    const std::size_t n = payload.size();
    if (n < 126) {
      frame += static_cast<char>(0x80 | n);
    } else if (n < 65536) {
      frame += static_cast<char>(0x80 | 126);
      frame += static_cast<char>(n >> 8U);
      frame += static_cast<char>(n & 0xffU);
    } else {
      frame += static_cast<char>(0x80 | 127);
      for (int shift = 56; shift >= 0; shift -= 8) {
        frame += static_cast<char>((n >> static_cast<unsigned>(shift)) & 0xffU);
      }
    }
    const char mask[4] = {0x12, 0x34, 0x56, 0x78};  // NOLINT(*-avoid-c-arrays)
    frame.append(mask, 4);
    for (std::size_t i = 0; i < n; ++i) {
      frame += static_cast<char>(payload[i] ^ mask[i % 4]);
    }
    send_raw(frame);
  }
  void send_text(const std::string& text) { send_frame(0x81, text); }

  /// Sends bytes as they are (a broken frame, garbage).
  void send_raw(const std::string& bytes) {
    std::size_t sent = 0;
    while (sent < bytes.size()) {
      const ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
      if (n <= 0) {
        return;  // the server closed: the caller checks with receive_text()
      }
      sent += static_cast<std::size_t>(n);
    }
  }

  /// The next text message within `timeout_ms`, skipping other frames; nothing if none came or
  /// the connection closed.
  std::optional<std::string> receive_text(int timeout_ms = 2000) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (std::chrono::steady_clock::now() < end) {
      std::uint8_t head[2];  // NOLINT(*-avoid-c-arrays)
      if (!read_exact(head, 2, end)) {
        return std::nullopt;
      }
      std::uint64_t n = head[1] & 0x7fU;
      if (n == 126 || n == 127) {
        std::uint8_t ext[8];  // NOLINT(*-avoid-c-arrays)
        const std::size_t bytes = n == 126 ? 2 : 8;
        if (!read_exact(ext, bytes, end)) {
          return std::nullopt;
        }
        n = 0;
        for (std::size_t i = 0; i < bytes; ++i) {
          n = (n << 8U) | ext[i];
        }
      }
      std::string payload(n, '\0');
      if (n > 0 && !read_exact(reinterpret_cast<std::uint8_t*>(payload.data()), n, end)) {
        return std::nullopt;
      }
      const int opcode = head[0] & 0x0f;
      if (opcode == 0x8) {
        return std::nullopt;  // closed by the server
      }
      if (opcode == 0x1) {
        return payload;
      }
    }
    return std::nullopt;
  }

  /// The next text message containing `needle`, within `timeout_ms`.
  std::optional<std::string> receive_containing(const std::string& needle, int timeout_ms = 3000) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (std::chrono::steady_clock::now() < end) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
          end - std::chrono::steady_clock::now());
      auto text = receive_text(static_cast<int>(left.count()) + 1);
      if (!text) {
        return std::nullopt;
      }
      if (text->find(needle) != std::string::npos) {
        return text;
      }
    }
    return std::nullopt;
  }

  /// Closes the socket at once, without a close frame (a browser tab killed).
  void vanish() {
    if (fd_ >= 0) {
      close(fd_);
      fd_ = -1;
    }
  }

 private:
  bool wait_readable(int timeout_ms) const {
    pollfd p{fd_, POLLIN, 0};
    return poll(&p, 1, timeout_ms) == 1;
  }

  bool read_exact(std::uint8_t* out, std::size_t n, std::chrono::steady_clock::time_point end) {
    std::size_t got = 0;
    while (got < n) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
          end - std::chrono::steady_clock::now());
      if (left.count() <= 0 || !wait_readable(static_cast<int>(left.count()))) {
        return false;
      }
      const ssize_t r = recv(fd_, out + got, n - got, 0);
      if (r <= 0) {
        return false;
      }
      got += static_cast<std::size_t>(r);
    }
    return true;
  }

  int fd_ = -1;
  int status_ = 0;
};

/// GET `path` from 127.0.0.1:`port`; returns the whole response (status line, headers, body).
inline std::string http_get(std::uint16_t port, const std::string& path,
                            const std::string& method = "GET") {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(port);
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (fd < 0 || connect(fd, reinterpret_cast<const sockaddr*>(&to), sizeof to) != 0) {
    if (fd >= 0) {
      close(fd);
    }
    return {};
  }
  const std::string request =
      method + " " + path + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n";
  (void)::send(fd, request.data(), request.size(), MSG_NOSIGNAL);
  std::string response;
  char buffer[4096];  // NOLINT(*-avoid-c-arrays)
  pollfd p{fd, POLLIN, 0};
  while (poll(&p, 1, 3000) == 1) {
    const ssize_t n = recv(fd, buffer, sizeof buffer, 0);
    if (n <= 0) {
      break;
    }
    response.append(buffer, static_cast<std::size_t>(n));
  }
  close(fd);
  return response;
}

}  // namespace hapticctrl::test
