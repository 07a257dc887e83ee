// The web server against a raw WebSocket client on loopback: static files and the API, the
// greeting and broadcasts, and everything a broken or hostile page can send.
#include "hapticctrl/web_bridge/web_server.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

#include "support/websocket_client.hpp"

namespace hapticctrl::web_bridge {
namespace {

using test::http_get;
using test::WebSocketClient;

/// Records what the server hands over; replies "echo:<text>" to texts starting with "ask".
class RecordingHandler final : public PageHandler {
 public:
  std::vector<std::string> greeting() override { return {"{\"type\":\"hello\"}", "{\"g\":2}"}; }
  std::string on_message(PageSession& page, std::string_view text) override {
    const std::lock_guard lock(mutex);
    messages.emplace_back(text);
    last_peer = page.peer;
    return text.substr(0, 3) == "ask" ? "echo:" + std::string(text) : std::string();
  }
  std::string model() override { return "{\"type\":\"model\"}"; }
  std::string stats() override { return "{\"bridge_counter\":7}"; }

  std::size_t received() {
    const std::lock_guard lock(mutex);
    return messages.size();
  }

  std::mutex mutex;
  std::vector<std::string> messages;
  std::string last_peer;
};

class WebServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    www_ = std::filesystem::temp_directory_path() /
           ("hapticctrl-www-" + std::to_string(getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(www_ / "sub");
    std::ofstream(www_ / "index.html") << "<title>operator view</title>";
    std::ofstream(www_ / "sub" / "a.txt") << "a";
  }
  void TearDown() override {
    server_.reset();
    std::filesystem::remove_all(www_);
  }
  WebServer& start(int max_pages = 4) {
    ServerSettings s;
    s.listen = "127.0.0.1:0";
    s.www_dir = www_.string();
    s.max_pages = max_pages;
    server_ = std::make_unique<WebServer>(s, handler_);
    return *server_;
  }
  /// Waits (bounded) until the server counts `pages` open pages.
  bool pages_become(std::size_t pages) {
    for (int i = 0; i < 300; ++i) {
      if (server_->pages() == pages) {
        return true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }
  /// A page that has been greeted (so the server has registered it).
  std::unique_ptr<WebSocketClient> greeted_page() {
    auto page = std::make_unique<WebSocketClient>(server_->port());
    EXPECT_EQ(page->status(), 101);
    EXPECT_TRUE(page->receive_containing("\"g\":2"));
    return page;
  }

  std::filesystem::path www_;
  RecordingHandler handler_;
  std::unique_ptr<WebServer> server_;
};

TEST_F(WebServerTest, ServesThePageAndTheApi) {
  const WebServer& s = start();
  ASSERT_NE(s.port(), 0);
  EXPECT_NE(http_get(s.port(), "/").find("operator view"), std::string::npos);
  EXPECT_NE(http_get(s.port(), "/api/model").find("{\"type\":\"model\"}"), std::string::npos);
  const std::string stats = http_get(s.port(), "/api/stats");
  EXPECT_NE(stats.find("\"bridge\":{\"bridge_counter\":7}"), std::string::npos) << stats;
  EXPECT_NE(stats.find("\"pages_opened\":0"), std::string::npos) << stats;
  EXPECT_EQ(http_get(s.port(), "/api/stats", "POST").substr(9, 3), "405");
  EXPECT_EQ(http_get(s.port(), "/sub/").substr(9, 3), "403");  // no directory listing
  EXPECT_EQ(http_get(s.port(), "/missing.js").substr(9, 3), "404");
  EXPECT_EQ(http_get(s.port(), "/../../etc/passwd").find("root:"), std::string::npos);
}

TEST_F(WebServerTest, GreetsAPageThenBroadcastsToIt) {
  WebServer& s = start();
  WebSocketClient page(s.port());
  ASSERT_EQ(page.status(), 101);
  EXPECT_EQ(page.receive_text(), "{\"type\":\"hello\"}");
  EXPECT_EQ(page.receive_text(), "{\"g\":2}");
  ASSERT_TRUE(pages_become(1));
  EXPECT_EQ(s.broadcast("{\"type\":\"state\",\"n\":1}"), 1U);
  EXPECT_EQ(page.receive_text(), "{\"type\":\"state\",\"n\":1}");
  EXPECT_EQ(s.counters().frames_pushed.load(), 1U);
}

TEST_F(WebServerTest, HandsTextToTheHandlerAndRepliesWhenItAnswers) {
  WebServer& s = start();
  auto page = greeted_page();
  page->send_text("quiet");
  page->send_text("ask me");
  EXPECT_EQ(page->receive_text(), "echo:ask me");
  EXPECT_EQ(handler_.received(), 2U);
  EXPECT_EQ(handler_.last_peer.rfind("127.0.0.1:", 0), 0U) << handler_.last_peer;
  EXPECT_EQ(s.counters().messages_in.load(), 2U);
}

TEST_F(WebServerTest, DropsBinaryFragmentedAndOversizedMessagesAndKeepsThePage) {
  WebServer& s = start();
  auto page = greeted_page();
  page->send_frame(0x82, "\x01\x02\x03");  // binary
  EXPECT_TRUE(page->receive_containing("text JSON messages only"));
  page->send_frame(0x01, "{\"type\":");    // a first fragment (no FIN)
  page->send_frame(0x80, "\"command\"}");  // its continuation
  page->send_text(std::string(kMaxPageMessageBytes + 1, 'x'));
  EXPECT_TRUE(page->receive_containing("message too long"));
  page->send_text("ask still here");
  EXPECT_EQ(page->receive_text(), "echo:ask still here");
  EXPECT_EQ(handler_.received(), 1U);  // only the last one reached the handler
  EXPECT_EQ(s.counters().dropped_binary.load(), 1U);
  EXPECT_EQ(s.counters().dropped_fragmented.load(), 2U);
  EXPECT_EQ(s.counters().dropped_oversized.load(), 1U);
}

TEST_F(WebServerTest, SurvivesGarbageTruncatedFramesAndAbsurdLengths) {
  WebServer& s = start();
  {
    auto page = greeted_page();
    page->send_raw(std::string("\xff\xff\xff\xff garbage that is no frame", 29));
  }
  {
    auto page = greeted_page();
    page->send_raw(std::string("\x81\x85\x01\x02", 4));  // header, half a mask, then gone
    page->vanish();
  }
  {
    auto page = greeted_page();
    // A text frame announcing 2^40 bytes, then nothing.
    page->send_raw(std::string("\x81\xff\x00\x00\x01\x00\x00\x00\x00\x00\x01\x02\x03\x04", 14));
    page->vanish();
  }
  {
    WebSocketClient not_even_http(s.port());  // a second upgrade request on the socket
    not_even_http.send_raw("GET / HTTP/1.1\r\n\r\n");
  }
  ASSERT_TRUE(pages_become(0));
  auto page = greeted_page();
  page->send_text("ask alive");
  EXPECT_EQ(page->receive_text(), "echo:ask alive");
  EXPECT_NE(http_get(s.port(), "/").find("operator view"), std::string::npos);
}

TEST_F(WebServerTest, ForgetsClosedAndVanishedPages) {
  WebServer& s = start(8);
  std::vector<std::unique_ptr<WebSocketClient>> pages;
  pages.reserve(6);
  for (int i = 0; i < 6; ++i) {
    pages.push_back(greeted_page());
  }
  ASSERT_TRUE(pages_become(6));
  for (int i = 0; i < 3; ++i) {
    pages[static_cast<std::size_t>(i)]->send_frame(0x88, "");  // a proper close
  }
  for (int i = 3; i < 6; ++i) {
    pages[static_cast<std::size_t>(i)]->vanish();  // a killed tab
  }
  ASSERT_TRUE(pages_become(0));
  EXPECT_EQ(s.broadcast("{}"), 0U);
  EXPECT_EQ(s.counters().pages_opened.load(), 6U);
  EXPECT_EQ(s.counters().pages_closed.load(), 6U);
}

TEST_F(WebServerTest, RefusesForeignOriginsAndPagesBeyondTheLimit) {
  WebServer& s = start(2);
  WebSocketClient foreign(s.port(), "http://evil.example");
  EXPECT_NE(foreign.status(), 101);
  WebSocketClient own(s.port(), "http://127.0.0.1:" + std::to_string(s.port()));
  EXPECT_EQ(own.status(), 101);
  ASSERT_TRUE(own.receive_containing("\"g\":2"));
  auto second = greeted_page();
  ASSERT_TRUE(pages_become(2));
  WebSocketClient third(s.port());
  EXPECT_NE(third.status(), 101);
  EXPECT_EQ(s.counters().refused_origin.load(), 1U);
  EXPECT_EQ(s.counters().refused_full.load(), 1U);
}

TEST_F(WebServerTest, BroadcastsWhilePagesComeAndGo) {
  WebServer& s = start(8);
  std::atomic<bool> running{true};
  std::thread pusher([&] {
    while (running.load()) {
      s.broadcast("{\"type\":\"state\"}");
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  });
  for (int i = 0; i < 20; ++i) {
    auto page = greeted_page();
    EXPECT_TRUE(page->receive_containing("state"));
    if (i % 2 == 0) {
      page->vanish();
    }
  }
  running.store(false);
  pusher.join();
  ASSERT_TRUE(pages_become(0));
  EXPECT_EQ(s.counters().pages_closed.load(), 20U);
}

TEST(SameOrigin, OnlyPagesOfThisServer) {
  EXPECT_TRUE(same_origin(nullptr, "127.0.0.1:8080", true));  // not a browser
  EXPECT_TRUE(same_origin("http://127.0.0.1:8080", "127.0.0.1:8080", true));
  EXPECT_TRUE(same_origin("http://localhost:8080", "localhost:8080", true));
  EXPECT_FALSE(same_origin("http://evil.example", "127.0.0.1:8080", true));
  EXPECT_FALSE(same_origin("http://127.0.0.1:9999", "127.0.0.1:8080", true));
  EXPECT_FALSE(same_origin("http://127.0.0.1:8080", nullptr, true));
  // DNS rebinding: a site whose name now resolves to 127.0.0.1 has a matching Host.
  EXPECT_FALSE(same_origin("http://rebound.example:8080", "rebound.example:8080", true));
  // Serving a network (--allow-remote), machines are named.
  EXPECT_TRUE(same_origin("http://controller.lab:8080", "controller.lab:8080", false));
  EXPECT_FALSE(same_origin("http://evil.example", "controller.lab:8080", false));
}

TEST(WebServer, SaysWhyItCannotStart) {
  RecordingHandler handler;
  ServerSettings s;
  s.listen = "127.0.0.1:0";
  s.www_dir = "/";
  WebServer first(s, handler);
  s.listen = "127.0.0.1:" + std::to_string(first.port());
  try {
    WebServer second(s, handler);
    FAIL() << "a second server on the same port started";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr(s.listen)) << e.what();
  }
}

}  // namespace
}  // namespace hapticctrl::web_bridge
