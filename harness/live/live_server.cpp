#include "harness/live/live_server.h"

#include <httplib.h>

#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>
#include <utility>

#include "base/file_io.h"
#include "base/paths.h"
#include "live_assets.h"

namespace xshade::harness {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kLiveScriptPath = "/xshade-live.js";
// An open event stream is sent a comment this often, so that a page whose server went away
// learns it (its EventSource reconnects) and a stream whose page went away ends.
constexpr auto kKeepAlive = std::chrono::seconds(10);
// Events kept for streams that have not sent them yet: a round announces one, and a page is
// never this many rounds behind.
constexpr size_t kEventsKept = 64;

std::string_view content_type(const fs::path& file) {
  const std::string extension = file.extension().string();
  if (extension == ".html") return "text/html; charset=utf-8";
  if (extension == ".js") return "text/javascript; charset=utf-8";
  if (extension == ".css") return "text/css; charset=utf-8";
  if (extension == ".png") return "image/png";
  if (extension == ".json") return "application/json";
  if (extension == ".xml") return "application/xml";
  if (extension == ".txt" || extension == ".md") return "text/plain; charset=utf-8";
  return "application/octet-stream";
}

}  // namespace

struct LiveServer::State {
  fs::path report_dir;
  httplib::Server server;
  std::thread listening;
  uint16_t port = 0;

  std::mutex mutex;
  std::condition_variable changed;
  std::deque<std::pair<uint64_t, std::string>> events;  // (number, json), the last kEventsKept
  uint64_t last_event = 0;
  bool stopping = false;

  // The events after `seen`, waiting up to kKeepAlive for one; nullopt once the server stops.
  std::optional<std::vector<std::pair<uint64_t, std::string>>> events_after(uint64_t seen) {
    std::unique_lock lock(mutex);
    changed.wait_for(lock, kKeepAlive, [&] { return stopping || last_event > seen; });
    if (stopping) return std::nullopt;
    std::vector<std::pair<uint64_t, std::string>> newer;
    for (const auto& event : events)
      if (event.first > seen) newer.push_back(event);
    return newer;
  }

  void serve_events(httplib::Response& response) {
    uint64_t seen = 0;
    {
      std::lock_guard lock(mutex);
      // A page that connects gets the last state first.
      seen = last_event == 0 ? 0 : last_event - 1;
    }
    response.set_header("Cache-Control", "no-store");
    response.set_chunked_content_provider("text/event-stream", [this, seen](size_t, httplib::DataSink& sink) mutable {
      const auto newer = events_after(seen);
      if (!newer) {
        sink.done();
        return false;
      }
      std::string text;
      for (const auto& [number, json] : *newer) {
        text += "id: " + std::to_string(number) + "\ndata: " + json + "\n\n";
        seen = number;
      }
      if (text.empty()) text = ": still here\n\n";
      return sink.write(text.data(), text.size());
    });
  }

  void serve_file(const httplib::Request& request, httplib::Response& response) {
    response.set_header("Cache-Control", "no-store");
    if (request.path == "/favicon.ico") {
      response.status = 204;  // the report has no icon, and a 404 would be a console error on every page
      return;
    }
    if (request.path == kLiveScriptPath) {
      response.set_content(std::string(kLiveScript), "text/javascript; charset=utf-8");
      return;
    }
    // The event the page is as of, taken before the file is read: a round writes its files before
    // it announces them, so a page read after this is at least as new (and one that is newer is
    // only updated again).
    uint64_t as_of = 0;
    {
      std::lock_guard lock(mutex);
      as_of = last_event;
    }
    std::string relative = request.path.substr(1);
    if (relative.empty() || relative.ends_with('/')) relative += "index.html";
    const fs::path file = report_dir / fs::path(relative).lexically_normal();
    std::optional<std::string> contents;
    if (!fs::path(relative).is_absolute() && resolved_path_is_inside(file, report_dir)) contents = read_file(file);
    if (!contents) {
      response.status = 404;
      response.set_content("not in the report: " + request.path + "\n", "text/plain; charset=utf-8");
      return;
    }
    if (file.extension() == ".html") *contents = with_live_script(std::move(*contents), as_of);
    response.set_content(std::move(*contents), std::string(content_type(file)));
  }
};

std::string with_live_script(std::string html, uint64_t last_event) {
  const std::string script = "<script src=\"" + std::string(kLiveScriptPath) + "\" data-event=\"" +
                             std::to_string(last_event) + "\"></script>\n";
  const size_t body_end = html.rfind("</body>");
  html.insert(body_end == std::string::npos ? html.size() : body_end, script);
  return html;
}

LiveServer::LiveServer(std::unique_ptr<State> state) : state_(std::move(state)) {}

Result<std::unique_ptr<LiveServer>> LiveServer::start(const fs::path& report_dir, uint16_t port) {
  auto state = std::make_unique<State>();
  state->report_dir = report_dir;
  State* serving = state.get();
  state->server.Get(
      "/events", [serving](const httplib::Request&, httplib::Response& response) { serving->serve_events(response); });
  state->server.Get(R"(/.*)", [serving](const httplib::Request& request, httplib::Response& response) {
    serving->serve_file(request, response);
  });
  // SO_REUSEADDR alone: a port held by another server must be refused, not shared with it (the
  // library's default adds SO_REUSEPORT).
  state->server.set_socket_options([](int socket) {
    const int yes = 1;
    setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  // The loopback interface only: the report shows a user's shaders and files to whoever asks.
  constexpr const char* kLoopback = "127.0.0.1";
  int bound = -1;
  if (port == 0)
    bound = state->server.bind_to_any_port(kLoopback);
  else if (state->server.bind_to_port(kLoopback, port))
    bound = port;
  if (bound <= 0)
    return fail(ErrorKind::Usage, "cannot serve the report on " + std::string(kLoopback) + ":" + std::to_string(port) +
                                      ": the port is taken or not ours to use; --port N chooses another, --port 0 "
                                      "any free one");
  state->port = uint16_t(bound);
  state->listening = std::thread([serving] { serving->server.listen_after_bind(); });
  // Serving before returning: a stop() that came before the listening began would be lost, and
  // the thread would listen on for ever.
  for (int waited = 0; !state->server.is_running() && waited < 5000; ++waited)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  return std::unique_ptr<LiveServer>(new LiveServer(std::move(state)));
}

LiveServer::~LiveServer() {
  {
    std::lock_guard lock(state_->mutex);
    state_->stopping = true;
  }
  state_->changed.notify_all();
  state_->server.stop();
  if (state_->listening.joinable()) state_->listening.join();
}

uint16_t LiveServer::port() const { return state_->port; }

void LiveServer::announce(nlohmann::json event) {
  {
    std::lock_guard lock(state_->mutex);
    event["event"] = ++state_->last_event;
    state_->events.emplace_back(state_->last_event, event.dump());
    if (state_->events.size() > kEventsKept) state_->events.pop_front();
  }
  state_->changed.notify_all();
}

}  // namespace xshade::harness
