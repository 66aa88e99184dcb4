#include "harness/live/live_server.h"

#include <gtest/gtest.h>
#include <httplib.h>

#include <cstdlib>
#include <fstream>
#include <future>
#include <sstream>

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

class LiveServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "xshade-live-server-XXXXXX").string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    root_ = pattern;
    report_ = root_ / "report";
    fs::create_directories(report_ / "toon");
    std::ofstream(report_ / "index.html") << "<html><body><p>index</p></body></html>";
    std::ofstream(report_ / "toon" / "gl.png") << "png bytes";
    std::ofstream(root_ / "secret.txt") << "outside the report";
  }
  void TearDown() override { fs::remove_all(root_); }
  fs::path root_, report_;
};

TEST_F(LiveServerTest, ServesTheReportsPagesWithTheLiveScriptAndNoCaching) {
  auto server = LiveServer::start(report_, 0);
  ASSERT_TRUE(server) << server.error().to_string();
  httplib::Client client("127.0.0.1", (*server)->port());
  auto page = client.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_EQ(page->body,
            "<html><body><p>index</p><script src=\"/xshade-live.js\" data-event=\"0\"></script>\n</body></html>");
  EXPECT_EQ(page->get_header_value("Cache-Control"), "no-store");
  auto image = client.Get("/toon/gl.png");
  ASSERT_TRUE(image);
  EXPECT_EQ(image->body, "png bytes");
  EXPECT_EQ(image->get_header_value("Content-Type"), "image/png");
  auto script = client.Get("/xshade-live.js");
  ASSERT_TRUE(script);
  EXPECT_NE(script->body.find("new EventSource(\"/events\")"), std::string::npos);
}

TEST_F(LiveServerTest, NothingOutsideTheReportFolder) {
  auto server = LiveServer::start(report_, 0);
  ASSERT_TRUE(server);
  httplib::Client client("127.0.0.1", (*server)->port());
  for (const char* path : {"/../secret.txt", "/toon/../../secret.txt", "/%2e%2e/secret.txt", "/missing.html"}) {
    auto response = client.Get(path);
    ASSERT_TRUE(response) << path;
    EXPECT_EQ(response->status, 404) << path;
    EXPECT_EQ(response->body.find("outside the report"), std::string::npos) << path;
  }
}

// Listening on 127.0.0.1 alone: /proc/net/tcp lists the socket with local address 0100007F
// (127.0.0.1, in the kernel's byte order) and the state 0A (listening).
TEST_F(LiveServerTest, ListensOnTheLoopbackInterfaceOnly) {
  auto server = LiveServer::start(report_, 0);
  ASSERT_TRUE(server);
  char port[8];
  std::snprintf(port, sizeof port, "%04X", (*server)->port());
  std::ifstream table("/proc/net/tcp");
  std::string line, listening;
  while (std::getline(table, line))
    if (line.find(std::string(":") + port + " ") != std::string::npos && line.find(" 0A ") != std::string::npos)
      listening += line + "\n";
  EXPECT_NE(listening.find("0100007F:" + std::string(port)), std::string::npos) << listening;
  EXPECT_EQ(listening.find("00000000:" + std::string(port)), std::string::npos) << listening;
}

TEST_F(LiveServerTest, APortTakenIsTheCommandLinesMistake) {
  auto first = LiveServer::start(report_, 0);
  ASSERT_TRUE(first);
  auto second = LiveServer::start(report_, (*first)->port());
  ASSERT_FALSE(second);
  EXPECT_EQ(second.error().kind, ErrorKind::Usage);
  EXPECT_NE(second.error().message.find("--port"), std::string::npos) << second.error().message;
}

// What an open page's EventSource reads: the last state at once, then each new one.
TEST_F(LiveServerTest, AnnouncedEventsReachAnOpenStream) {
  auto server = LiveServer::start(report_, 0);
  ASSERT_TRUE(server);
  (*server)->announce({{"round", 1}});
  std::promise<void> first_arrived;
  std::promise<std::string> received;
  std::thread reader([&, port = (*server)->port()] {
    httplib::Client client("127.0.0.1", port);
    client.set_read_timeout(20, 0);
    std::string text;
    bool first = false, told = false;
    client.Get("/events", [&](const char* data, size_t length) {
      text.append(data, length);
      if (!first && text.find(R"({"event":1,"round":1})") != std::string::npos) {
        first = true;
        first_arrived.set_value();
      }
      if (text.find(R"({"event":2,"round":2})") == std::string::npos) return true;
      received.set_value(text);
      told = true;
      return false;
    });
    if (!first) first_arrived.set_value();
    if (!told) received.set_value(text);
  });
  // The second event once the stream has the first: then it is open, whatever the machine's load.
  ASSERT_EQ(first_arrived.get_future().wait_for(std::chrono::seconds(15)), std::future_status::ready);
  (*server)->announce({{"round", 2}});
  auto future = received.get_future();
  ASSERT_EQ(future.wait_for(std::chrono::seconds(15)), std::future_status::ready);
  const std::string text = future.get();
  reader.join();
  EXPECT_NE(text.find("id: 1\ndata: {\"event\":1,\"round\":1}\n\n"), std::string::npos) << text;
  EXPECT_NE(text.find("id: 2\ndata: {\"event\":2,\"round\":2}\n\n"), std::string::npos) << text;
  // A page served now is told it is as of event 2.
  httplib::Client client("127.0.0.1", (*server)->port());
  auto page = client.Get("/index.html");
  ASSERT_TRUE(page);
  EXPECT_NE(page->body.find("data-event=\"2\""), std::string::npos);
}

TEST(LiveScript, GoesBeforeTheBodysEndOrAtTheEnd) {
  EXPECT_EQ(with_live_script("<body>a</body>", 7),
            "<body>a<script src=\"/xshade-live.js\" data-event=\"7\"></script>\n</body>");
  EXPECT_EQ(with_live_script("a", 0), "a<script src=\"/xshade-live.js\" data-event=\"0\"></script>\n");
}

}  // namespace
}  // namespace xshade::harness
