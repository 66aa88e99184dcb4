// Child processes a parent supervises, as conformance runners run their tests: each started with
// posix_spawn, its standard output and error collected together, a second pipe (file descriptor
// 3 in the child) for the status lines it reports, and a deadline after which it is killed. A
// child that crashes, hangs or is killed is then a result the parent reports, never the parent's
// own end. A child may also serve many requests: the parent writes them to its standard input,
// and takes its output and status lines request by request, with a deadline for each.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "base/result.h"

namespace xshade {

// The file descriptor a child writes its status lines to.
inline constexpr int kChildStatusFd = 3;

struct ChildExit {
  int code = -1;           // the exit code, when it exited
  int signal = 0;          // the signal that ended it; 0 when it exited
  bool timed_out = false;  // killed by its parent at its deadline
};

// "SIGSEGV (segmentation fault)".
std::string describe_signal(int signal);

class ChildProcess {
 public:
  using Clock = std::chrono::steady_clock;

  // Starts `argv[0]` (a path) with `argv`, its environment ours with each "NAME=value" of
  // `environment` set over it. It is killed at `time_limit` from now.
  static Result<ChildProcess> start(const std::vector<std::string>& argv, const std::vector<std::string>& environment,
                                    Clock::duration time_limit);
  // The same, but the child is a fork of this process that runs `body` and exits with what it
  // returns: no program is loaded again, nor the drivers and libraries it has loaded (the image
  // library's 260 take a third of a second). fork copies the calling thread alone, and a lock another thread held stays
  // held in the child, so this is only for a process running no thread of its own: it fails, and the caller starts a
  // program instead, when the process has more threads than it had when main began or than it had when it last counted
  // them (remember_startup_threads) -- those are the idle pools some libraries start as they load (log4cplus, which
  // OpenImageIO's formats bring, starts four), which xshade gives no work.
  static Result<ChildProcess> fork(const std::function<int()>& body, const std::vector<std::string>& environment,
                                   Clock::duration time_limit);

  ChildProcess(ChildProcess&& other) noexcept;
  ChildProcess& operator=(ChildProcess&& other) noexcept;
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  // A child still running is killed and reaped: none outlives the object that started it.
  ~ChildProcess();

  // Reads what the child wrote, reaps it when it has ended and kills it at its deadline; true
  // once it has ended (and then output() and last_status() are complete). Never blocks.
  bool poll();
  bool finished() const { return finished_; }
  const ChildExit& exit_status() const { return exit_; }
  // Standard output and error, interleaved as written; of a very talkative child only the first
  // and last kOutputKept bytes.
  const std::string& output() const { return output_; }
  // The last complete line the child wrote to kChildStatusFd; empty before the first.
  const std::string& last_status() const { return last_status_; }
  double seconds() const { return std::chrono::duration<double>(ended_ - started_).count(); }

  // The file descriptors still open, for waiting on.
  std::vector<int> open_fds() const;
  Clock::time_point deadline() const { return deadline_; }
  void set_deadline(Clock::time_point deadline) { deadline_ = deadline; }

  // For a child that serves requests: writes `line` (and a newline) to its standard input; false
  // when it cannot be written (the child has ended or closed it).
  bool send(const std::string& line);
  // The output written since the last take (all of it, for the first).
  std::string take_output();
  // The complete status lines written since the last take, in order; last_status() is not
  // cleared by this, but by forget_status().
  std::vector<std::string> take_status_lines();
  void forget_status() { last_status_.clear(); }

  static constexpr size_t kOutputKept = 1 << 20;

 private:
  ChildProcess() = default;
  // Either way of starting: `spawn` makes the child from its ends of the pipes (0 input, 1 and 2
  // output, kChildStatusFd status) and returns its pid, or -1 with errno's reason in `error`.
  static Result<ChildProcess> start_with(const std::function<pid_t(const int fds[4], int& error)>& spawn,
                                         const std::string& what, Clock::duration time_limit);
  void read_pipes();
  void close_pipes();
  void release();

  pid_t pid_ = -1;
  int input_fd_ = -1;
  int output_fd_ = -1;
  int status_fd_ = -1;
  bool finished_ = false;
  ChildExit exit_;
  std::string output_;
  size_t output_cut_ = 0;  // bytes left out of output_'s middle
  std::string status_partial_;
  std::string last_status_;
  std::vector<std::string> status_lines_;  // since the last take_status_lines()
  Clock::time_point started_{};
  Clock::time_point deadline_{};
  Clock::time_point ended_{};
};

// Called first thing in main, and again after loading a library that starts idle threads of its
// own: the threads the process has while none of its own code runs in a thread.
void remember_startup_threads();

// Waits until one of `children` writes, ends or reaches its deadline, or `longest` has passed.
void wait_for_any(const std::vector<ChildProcess*>& children, std::chrono::milliseconds longest);

// The cores this process may run on (its affinity mask), at least 1.
unsigned usable_cores();

}  // namespace xshade
