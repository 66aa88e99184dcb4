// The report of `xshade watch`, served on the loopback interface only: the report folder's files
// (never cached by the browser, as they change under it), each HTML page with the live script
// (live.js) added so that an open page updates itself, and /events, a stream of server-sent
// events on which each new state of the report is announced.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "base/result.h"

namespace xshade::harness {

class LiveServer {
 public:
  // Binds 127.0.0.1:`port` (0: a free one) and serves `report_dir` in threads of its own.
  static Result<std::unique_ptr<LiveServer>> start(const std::filesystem::path& report_dir, uint16_t port);
  // Ends the event streams, stops serving and joins its threads.
  ~LiveServer();
  LiveServer(const LiveServer&) = delete;
  LiveServer& operator=(const LiveServer&) = delete;

  uint16_t port() const;
  // Sends `event` as the next event to every open page, numbered in its "event" member (from 1);
  // a page that connects later gets the last event first, so that it knows the report's state.
  void announce(nlohmann::json event);

  struct State;  // live_server.cpp's

 private:
  explicit LiveServer(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

// `html` with the live script loaded before </body> (or at its end, when it has none), told that
// the page is as of event `last_event`.
std::string with_live_script(std::string html, uint64_t last_event);

}  // namespace xshade::harness
