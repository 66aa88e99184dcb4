#include "base/subprocess.h"

#include <fcntl.h>
#include <poll.h>
#include <sched.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iterator>

#include "base/file_io.h"

extern char** environ;

namespace xshade {
namespace {

// A pipe whose ends are above the descriptors the child's file actions write (0 to 3), so that
// dup2 onto 1, 2 or 3 never meets one of them, and close-on-exec, so that no other child inherits
// them.
bool make_pipe(int ends[2]) {
  int raw[2];
  if (pipe2(raw, O_CLOEXEC) != 0) return false;
  for (int i = 0; i < 2; ++i) {
    ends[i] = fcntl(raw[i], F_DUPFD_CLOEXEC, 10);
    close(raw[i]);
  }
  if (ends[0] < 0 || ends[1] < 0) {
    for (int i = 0; i < 2; ++i)
      if (ends[i] >= 0) close(ends[i]);
    return false;
  }
  fcntl(ends[0], F_SETFL, O_NONBLOCK);
  return true;
}

// Our environment with each "NAME=value" of `overrides` in place of ours.
std::vector<std::string> child_environment(const std::vector<std::string>& overrides) {
  std::vector<std::string> entries;
  auto name_of = [](const std::string& entry) { return entry.substr(0, entry.find('=')); };
  for (char** entry = environ; *entry; ++entry) {
    const std::string text = *entry;
    if (std::none_of(overrides.begin(), overrides.end(),
                     [&](const std::string& over) { return name_of(over) == name_of(text); }))
      entries.push_back(text);
  }
  entries.insert(entries.end(), overrides.begin(), overrides.end());
  return entries;
}

std::vector<char*> pointers(std::vector<std::string>& strings) {
  std::vector<char*> result;
  for (std::string& text : strings) result.push_back(text.data());
  result.push_back(nullptr);
  return result;
}

}  // namespace

std::string describe_signal(int signal) {
  const char* name = sigabbrev_np(signal);
  const char* what = sigdescr_np(signal);
  std::string text = name ? std::string("SIG") + name : "signal " + std::to_string(signal);
  if (what) {
    std::string lower = what;
    if (!lower.empty()) lower[0] = char(std::tolower(static_cast<unsigned char>(lower[0])));
    text += " (" + lower + ")";
  }
  return text;
}

Result<ChildProcess> ChildProcess::start_with(const std::function<pid_t(const int fds[4], int& error)>& spawn,
                                              const std::string& what, Clock::duration time_limit) {
  int output[2], status[2], input[2];
  if (!make_pipe(output)) return fail(ErrorKind::Backend, std::string("cannot make a pipe: ") + std::strerror(errno));
  if (!make_pipe(status)) {
    close(output[0]);
    close(output[1]);
    return fail(ErrorKind::Backend, std::string("cannot make a pipe: ") + std::strerror(errno));
  }
  if (!make_pipe(input)) {
    for (int fd : {output[0], output[1], status[0], status[1]}) close(fd);
    return fail(ErrorKind::Backend, std::string("cannot make a pipe: ") + std::strerror(errno));
  }
  // Our end of the child's input blocks (a request is a line, written whole); make_pipe left
  // the reading end, which is the child's, non-blocking, and the child must block on it.
  fcntl(input[0], F_SETFL, 0);
  const int child_ends[4] = {input[0], output[1], output[1], status[1]};
  int error = 0;
  const pid_t pid = spawn(child_ends, error);
  close(output[1]);
  close(status[1]);
  close(input[0]);
  if (pid < 0) {
    close(output[0]);
    close(status[0]);
    close(input[1]);
    return fail(ErrorKind::Backend, "cannot start " + what + ": " + std::strerror(error));
  }
  ChildProcess child;
  child.pid_ = pid;
  child.input_fd_ = input[1];
  child.output_fd_ = output[0];
  child.status_fd_ = status[0];
  child.started_ = Clock::now();
  child.deadline_ = child.started_ + time_limit;
  return child;
}

Result<ChildProcess> ChildProcess::start(const std::vector<std::string>& argv,
                                         const std::vector<std::string>& environment, Clock::duration time_limit) {
  if (argv.empty()) return fail(ErrorKind::Internal, "a child process needs a program to run");
  return start_with(
      [&](const int fds[4], int& error) -> pid_t {
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        for (int target = 0; target < 4; ++target) posix_spawn_file_actions_adddup2(&actions, fds[target], target);
        std::vector<std::string> arguments = argv;
        std::vector<std::string> variables = child_environment(environment);
        std::vector<char*> argument_pointers = pointers(arguments);
        std::vector<char*> variable_pointers = pointers(variables);
        pid_t pid = -1;
        error =
            posix_spawn(&pid, argv[0].c_str(), &actions, nullptr, argument_pointers.data(), variable_pointers.data());
        posix_spawn_file_actions_destroy(&actions);
        return error == 0 ? pid : -1;
      },
      argv[0], time_limit);
}

namespace {

long thread_count() {
  std::error_code error;
  const long count = std::distance(std::filesystem::directory_iterator("/proc/self/task", error),
                                   std::filesystem::directory_iterator());
  return error ? -1 : count;
}

long startup_threads = 1;

}  // namespace

void remember_startup_threads() { startup_threads = std::max(1L, thread_count()); }

Result<ChildProcess> ChildProcess::fork(const std::function<int()>& body, const std::vector<std::string>& environment,
                                        Clock::duration time_limit) {
  const long threads = thread_count();
  if (threads < 1 || threads > startup_threads)
    return fail(ErrorKind::Internal, "cannot fork a child: this process runs " + std::to_string(threads) +
                                         " threads, more than the " + std::to_string(startup_threads) +
                                         " it started with");
  // What the C library still holds for our own output would be written twice, by us and by it.
  std::fflush(nullptr);
  return start_with(
      [&](const int fds[4], int& failure) -> pid_t {
        const pid_t pid = ::fork();
        if (pid < 0) failure = errno;
        if (pid != 0) return pid;
        // The child: its ends of the pipes as 0 to 3, nothing else of ours open.
        for (int target = 0; target < 4; ++target)
          if (dup2(fds[target], target) < 0) _exit(3);
        close_range(4, ~0u, 0);
        for (const std::string& entry : environment) {
          const size_t equals = entry.find('=');
          setenv(entry.substr(0, equals).c_str(), equals == std::string::npos ? "" : entry.c_str() + equals + 1, 1);
        }
        // Nothing may leave `body` but its exit: an exception unwinding into the parent's frames
        // would go on as a second parent.
        int code = 3;
        try {
          code = body();
        } catch (...) {
        }
        std::fflush(nullptr);
        _exit(code);  // our own exit handlers and destructors are the parent's to run
      },
      "a worker", time_limit);
}

ChildProcess::ChildProcess(ChildProcess&& other) noexcept { *this = std::move(other); }

ChildProcess& ChildProcess::operator=(ChildProcess&& other) noexcept {
  if (this == &other) return *this;
  release();
  pid_ = std::exchange(other.pid_, -1);
  input_fd_ = std::exchange(other.input_fd_, -1);
  output_fd_ = std::exchange(other.output_fd_, -1);
  status_fd_ = std::exchange(other.status_fd_, -1);
  finished_ = other.finished_;
  exit_ = other.exit_;
  output_ = std::move(other.output_);
  output_cut_ = other.output_cut_;
  status_partial_ = std::move(other.status_partial_);
  last_status_ = std::move(other.last_status_);
  status_lines_ = std::move(other.status_lines_);
  started_ = other.started_;
  deadline_ = other.deadline_;
  ended_ = other.ended_;
  return *this;
}

ChildProcess::~ChildProcess() { release(); }

void ChildProcess::release() {
  if (pid_ > 0 && !finished_) {
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
  pid_ = -1;
  close_pipes();
}

void ChildProcess::close_pipes() {
  for (int* fd : {&input_fd_, &output_fd_, &status_fd_})
    if (*fd >= 0) {
      close(*fd);
      *fd = -1;
    }
}

std::vector<int> ChildProcess::open_fds() const {
  std::vector<int> fds;
  for (int fd : {output_fd_, status_fd_})
    if (fd >= 0) fds.push_back(fd);
  return fds;
}

void ChildProcess::read_pipes() {
  char buffer[65536];
  for (int* fd : {&output_fd_, &status_fd_}) {
    while (*fd >= 0) {
      const ssize_t got = read(*fd, buffer, sizeof buffer);
      if (got < 0 && errno == EINTR) continue;
      if (got < 0) break;  // EAGAIN: nothing more now
      if (got == 0) {      // the child (and anything it started) closed its end
        close(*fd);
        *fd = -1;
        break;
      }
      if (fd == &output_fd_) {
        output_.append(buffer, size_t(got));
        // Keep the start (how it began) and the end (how it ended) of a flood of output.
        if (output_.size() > kOutputKept) {
          const size_t half = kOutputKept / 2, cut = output_.size() - kOutputKept;
          output_.erase(half, cut);
          output_cut_ += cut;
        }
      } else {
        status_partial_.append(buffer, size_t(got));
        for (size_t end; (end = status_partial_.find('\n')) != std::string::npos;) {
          last_status_ = status_partial_.substr(0, end);
          status_lines_.push_back(last_status_);
          status_partial_.erase(0, end + 1);
        }
        if (status_partial_.size() > 65536) status_partial_.clear();  // not a status line
      }
    }
  }
}

bool ChildProcess::poll() {
  if (finished_) return true;
  read_pipes();
  int status = 0;
  pid_t reaped = waitpid(pid_, &status, WNOHANG);
  if (reaped == 0 && Clock::now() >= deadline_) {
    kill(pid_, SIGKILL);
    reaped = waitpid(pid_, &status, 0);
    exit_.timed_out = true;
  }
  if (reaped != pid_) return false;
  finished_ = true;
  ended_ = Clock::now();
  if (WIFEXITED(status)) exit_.code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) exit_.signal = WTERMSIG(status);
  // What it wrote before it ended is still in the pipes: read it all (the descriptors are
  // non-blocking, so a grandchild holding a pipe open cannot stall us).
  read_pipes();
  close_pipes();
  if (output_cut_)
    output_.insert(kOutputKept / 2, "\n[... " + std::to_string(output_cut_) + " bytes of output left out ...]\n");
  return true;
}

bool ChildProcess::send(const std::string& line) {
  if (input_fd_ < 0 || finished_) return false;
  const std::string text = line + "\n";
  // A child that has ended makes the write fail with EPIPE rather than end us with SIGPIPE.
  struct sigaction ignore {
  }, previous{};
  ignore.sa_handler = SIG_IGN;
  sigaction(SIGPIPE, &ignore, &previous);
  const bool written = write_all(input_fd_, text);
  sigaction(SIGPIPE, &previous, nullptr);
  return written;
}

std::string ChildProcess::take_output() {
  read_pipes();
  output_cut_ = 0;
  return std::exchange(output_, {});
}

std::vector<std::string> ChildProcess::take_status_lines() {
  read_pipes();
  return std::exchange(status_lines_, {});
}

void wait_for_any(const std::vector<ChildProcess*>& children, std::chrono::milliseconds longest) {
  std::vector<pollfd> fds;
  auto wait = longest;
  const auto now = ChildProcess::Clock::now();
  for (const ChildProcess* child : children) {
    if (child->finished()) return;
    for (int fd : child->open_fds()) fds.push_back({fd, POLLIN, 0});
    const auto until_deadline =
        std::chrono::duration_cast<std::chrono::milliseconds>(child->deadline() - now) + std::chrono::milliseconds(1);
    wait = std::max(std::chrono::milliseconds(0), std::min(wait, until_deadline));
  }
  // A child that has closed both pipes is only seen ending by waitpid: wake up soon to look.
  if (fds.size() < 2 * children.size()) wait = std::min(wait, std::chrono::milliseconds(10));
  ::poll(fds.data(), fds.size(), int(wait.count()));
}

unsigned usable_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  const long online = sysconf(_SC_NPROCESSORS_ONLN);
  return online > 0 ? unsigned(online) : 1u;
}

}  // namespace xshade
