#include "harness/gate/lane_workers.h"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>  // renameat2
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "base/file_io.h"
#include "base/interrupt.h"
#include "base/subprocess.h"
#include "harness/gate/result_json.h"

namespace xshade::harness {
namespace fs = std::filesystem;

// The pool's parts, named rather than anonymous: LaneWorkerPool::State, a type of the header's,
// holds them.
namespace lane_workers_internal {
using namespace std::chrono_literals;

constexpr std::string_view kScratchPrefix = "xshade-workers-";

// A private folder for the workers' results, removed with everything in it at the end. The run
// holds a lock on it while it lives (flock on the folder, closed on exec so no worker keeps it):
// a folder whose lock can be taken is a dead run's (killed with SIGKILL, or a machine that went
// down), and the next run removes it. It is made under a hidden name, locked, and only then
// given its name, so that no run finds it unlocked.
class ScratchFolder {
 public:
  static Result<ScratchFolder> make() {
    std::error_code error;
    const fs::path temp = fs::temp_directory_path(error);
    std::string hidden = (temp / ("." + std::string(kScratchPrefix) + "XXXXXX")).string();
    if (!mkdtemp(hidden.data()))
      return fail(ErrorKind::Backend,
                  "cannot make a folder for the workers in " + temp.string() + ": " + std::strerror(errno));
    const fs::path named = temp / fs::path(hidden).filename().string().substr(1);
    const int fd = open(hidden.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0 || flock(fd, LOCK_EX | LOCK_NB) != 0 ||
        renameat2(AT_FDCWD, hidden.c_str(), AT_FDCWD, named.c_str(), RENAME_NOREPLACE) != 0) {
      const int cause = errno;
      if (fd >= 0) close(fd);
      fs::remove_all(hidden, error);
      return fail(ErrorKind::Backend,
                  "cannot make the workers' folder " + named.string() + ": " + std::strerror(cause));
    }
    return ScratchFolder(named, fd);
  }
  // Removes the folders that dead runs of this user left.
  static void remove_dead_runs() {
    std::error_code error;
    const fs::path temp = fs::temp_directory_path(error);
    if (error) return;
    for (const fs::directory_entry& entry : fs::directory_iterator(temp, error)) {
      if (!entry.path().filename().string().starts_with(kScratchPrefix)) continue;
      const int fd = open(entry.path().c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
      if (fd < 0) continue;
      struct stat status {};
      std::error_code ignored;
      if (fstat(fd, &status) == 0 && status.st_uid == geteuid() && flock(fd, LOCK_EX | LOCK_NB) == 0)
        fs::remove_all(entry.path(), ignored);
      close(fd);
    }
  }
  ScratchFolder(ScratchFolder&& other) noexcept
      : path_(std::exchange(other.path_, {})), lock_(std::exchange(other.lock_, -1)) {}
  ScratchFolder& operator=(ScratchFolder&&) = delete;
  ~ScratchFolder() {
    std::error_code ignored;
    if (!path_.empty()) fs::remove_all(path_, ignored);
    if (lock_ >= 0) close(lock_);
  }
  const fs::path& path() const { return path_; }

 private:
  ScratchFolder(fs::path path, int lock) : path_(std::move(path)), lock_(lock) {}
  fs::path path_;
  int lock_ = -1;
};

// The last `count` lines of a worker's output, for a message about how it ended.
std::string last_lines(const std::string& output, size_t count) {
  size_t begin = output.size() - (output.ends_with('\n') ? 1 : 0);
  for (size_t lines = 0; lines < count; ++lines) {
    const size_t newline = begin ? output.rfind('\n', begin - 1) : std::string::npos;
    if (newline == std::string::npos) return output;
    begin = newline;
  }
  return output.substr(begin + 1);
}

// A lane that could not be rendered for a reason of the machine's or xshade's own.
LaneResult crashed(Lane lane, std::string message) {
  LaneResult result;
  result.lane = std::string(lane_name(lane));
  result.verdict = Verdict::Crash;
  result.message = std::move(message);
  return result;
}

// The result of a render whose worker gave none: timed out, killed, crashed or exited early.
// `output` is what the worker wrote during the render.
LaneResult ended_without_result(Lane lane, const ChildProcess& worker, double timeout_seconds, double seconds,
                                const std::string& output) {
  LaneResult result;
  result.lane = std::string(lane_name(lane));
  result.seconds = seconds;
  const std::string where = worker.last_status().empty() ? "while starting" : worker.last_status();
  const ChildExit& exit = worker.exit_status();
  std::string layer = "worker";
  if (exit.timed_out) {
    // Too slow is a check the scene failed, not a broken driver: exit 1, like any other check.
    result.verdict = Verdict::Fail;
    layer = "timeout";
    result.message = fmt::format("timeout after {:g} s {}", timeout_seconds, where);
  } else if (exit.signal) {
    result.verdict = Verdict::Crash;
    result.message = fmt::format("worker died: {} {}", describe_signal(exit.signal), where);
    if (exit.signal == SIGKILL) result.message += " (killed from outside: the out-of-memory killer, or a user)";
  } else {
    result.verdict = Verdict::Crash;
    result.message = fmt::format("worker exited with code {} {} and gave no result", exit.code, where);
  }
  result.layers.push_back({layer, result.verdict, result.message});
  if (exit.timed_out)
    result.message +=
        "; a scene that needs longer says so with `timeout = SECONDS` and `timeout_reason`, a run with --timeout";
  if (const std::string tail = last_lines(output, 20); !tail.empty()) result.message += "\nits last output:\n" + tail;
  return result;
}

struct SceneInWork {
  CheckedScene checked;
  std::map<Lane, LaneResult> results;
  size_t waiting = 0;  // lanes started or queued and not yet finished
  std::string output;  // what its workers wrote
};

struct Job {
  size_t scene = 0;
  Lane lane = Lane::Gl;
};

// A worker process and the render it is doing. A worker serves renders one after another (its
// start, loading some 260 shared libraries, costs a third of a second, as much as a render), and
// is started again only after one it was doing ended it.
struct WorkerSlot {
  std::optional<ChildProcess> process;
  std::optional<Job> job;
  fs::path folder;
  double timeout_seconds = 0.0;
  ChildProcess::Clock::time_point job_started{};
};

}  // namespace lane_workers_internal

// The workers and their folder, between rounds.
struct LaneWorkerPool::State {
  SceneWorkers workers;
  Result<lane_workers_internal::ScratchFolder> scratch;  // the workers' result folders, removed with the pool
  std::vector<lane_workers_internal::WorkerSlot> slots;
};

LaneWorkerPool::LaneWorkerPool(SceneWorkers workers) {
  using lane_workers_internal::ScratchFolder;
  ScratchFolder::remove_dead_runs();
  const size_t jobs = std::max(1u, workers.jobs);
  state_ = std::make_unique<State>(
      State{std::move(workers), ScratchFolder::make(), std::vector<lane_workers_internal::WorkerSlot>(jobs)});
}

// The workers first (each ChildProcess kills and reaps its own), then the folder they wrote into.
LaneWorkerPool::~LaneWorkerPool() {
  if (state_) state_->slots.clear();
}

namespace lane_workers_internal {

// check_in_workers' state and its steps: scenes prepared as far as there is work to queue, jobs
// (a scene's lane) given to free workers, ended renders collected, finished scenes reported in order.
class LaneRenderPool {
 public:
  LaneRenderPool(SceneChecker& checker, LaneWorkerPool::State& pool, const std::vector<fs::path>& files,
                 const std::vector<Lane>& lanes, const std::function<void(CheckedScene&&)>& done,
                 const std::function<void(const std::string&)>& output)
      : checker_(checker),
        workers_(pool.workers),
        files_(files),
        lanes_(lanes),
        done_(done),
        output_(output),
        scenes_(files.size()),
        scratch_(pool.scratch),
        slots_(pool.slots) {}

  WorkerTotals run() {
    // Asked to stop (interrupt.h): it returns at once; the workers are killed and their folder
    // removed with the pool.
    while (next_to_report_ < files_.size() && !interrupt_signal()) {
      prepare_scenes();
      start_queued();
      report_ready();
      if (busy_ == 0) continue;
      wait_and_collect();
      report_ready();
    }
    return totals_;
  }

 private:
  // Prepare scenes only as far as there is work to queue: the first workers start at once.
  void prepare_scenes() {
    while (busy_ + queued_.size() < slots_.size() && next_to_prepare_ < files_.size()) {
      SceneInWork& scene = scenes_[next_to_prepare_];
      scene.checked = checker_.prepare(files_[next_to_prepare_], lanes_);
      scene.waiting = scene.checked.lanes.size();
      for (Lane lane : scene.checked.lanes) queued_.push_back({next_to_prepare_, lane});
      ++next_to_prepare_;
    }
  }

  void start_queued() {
    for (WorkerSlot& slot : slots_) {
      if (slot.job || queued_.empty()) continue;
      const Job job = queued_.front();
      queued_.pop_front();
      start(slot, job);
    }
  }

  // Waits up to a second for a worker to say something, then collects every render that ended.
  void wait_and_collect() {
    std::vector<ChildProcess*> children;
    for (WorkerSlot& slot : slots_)
      if (slot.job) children.push_back(&*slot.process);
    wait_for_any(children, 1000ms);
    for (WorkerSlot& slot : slots_) {
      if (!slot.job) continue;
      const bool ended = slot.process->poll();  // reads its pipes; kills it at its deadline
      const std::vector<std::string> lines = slot.process->take_status_lines();
      const bool rendered =
          std::any_of(lines.begin(), lines.end(), [](const std::string& line) { return line.starts_with("done "); });
      if (rendered || ended) collect(slot, rendered);
    }
  }

  // Gives `job` to the slot's worker, starting one if it has none (or it ended).
  void start(WorkerSlot& slot, const Job& job) {
    SceneInWork& scene = scenes_[job.scene];
    const double timeout = scene.checked.scene && scene.checked.scene->timeout_seconds
                               ? *scene.checked.scene->timeout_seconds
                               : workers_.timeout_seconds;
    if (!scratch_) return finish_lane(job, crashed(job.lane, scratch_.error().to_string()));
    const auto limit =
        std::chrono::duration_cast<ChildProcess::Clock::duration>(std::chrono::duration<double>(timeout));
    if (!slot.process || slot.process->finished()) {
      std::vector<std::string> command = workers_.command;
      command.push_back("--serve");
      auto process = workers_.serve ? ChildProcess::fork(workers_.serve, workers_.environment, limit)
                                    : ChildProcess::start(command, workers_.environment, limit);
      if (!process && workers_.serve) process = ChildProcess::start(command, workers_.environment, limit);
      if (!process) return finish_lane(job, crashed(job.lane, "cannot start a worker: " + process.error().to_string()));
      slot.process.emplace(std::move(*process));
      ++totals_.workers_started;
    }
    slot.folder = scratch_->path() / fmt::format("{}-{}", job.scene, lane_name(job.lane));
    std::error_code error;
    fs::create_directories(slot.folder, error);
    const nlohmann::json request = {
        {"scene", files_[job.scene].string()}, {"lane", lane_name(job.lane)}, {"result", slot.folder.string()}};
    slot.process->forget_status();
    slot.job_started = ChildProcess::Clock::now();
    slot.process->set_deadline(slot.job_started + limit);
    slot.timeout_seconds = timeout;
    slot.job = job;
    ++busy_;
    ++totals_.renders;
    // A worker that ended between renders has not read this one: its poll says so at once.
    slot.process->send(request.dump());
  }

  // The render `slot` was doing has ended, done or not; its worker stays for the next when done.
  void collect(WorkerSlot& slot, bool rendered) {
    const Job job = *slot.job;
    SceneInWork& scene = scenes_[job.scene];
    ChildProcess& worker = *slot.process;
    const std::string written = worker.take_output();
    scene.output += written;
    std::optional<LaneResult> result;
    if (rendered) {
      const auto text = read_file(slot.folder / "lane.json");
      const nlohmann::json lane_file = text ? nlohmann::json::parse(*text, nullptr, false) : nlohmann::json();
      auto parsed = lane_from_json(lane_file.is_object() ? lane_file.value("result", nlohmann::json()) : lane_file);
      if (lane_file.is_object()) {
        totals_.compiled += lane_file.value("compiled", size_t(0));
        totals_.cached += lane_file.value("cached", size_t(0));
        if (totals_.cache_write_error.empty()) totals_.cache_write_error = lane_file.value("cache_write_error", "");
        if (totals_.cache_damage.empty()) totals_.cache_damage = lane_file.value("cache_damage", "");
        for (const nlohmann::json& file : lane_file.value("read", nlohmann::json::array()))
          if (file.is_string()) scene.checked.files_read.insert(file.get<std::string>());
      }
      if (parsed) {
        result = std::move(*parsed);
      } else {
        result = crashed(job.lane, "the worker's result cannot be read: " + parsed.error().to_string());
      }
      if (const auto bytes = read_file(slot.folder / "image.f32"))
        if (auto image = float_image_from(*bytes)) scene.checked.images.emplace(job.lane, std::move(*image));
    } else {
      const double seconds = std::chrono::duration<double>(ChildProcess::Clock::now() - slot.job_started).count();
      result = ended_without_result(job.lane, worker, slot.timeout_seconds, seconds, written);
      slot.process.reset();
    }
    std::error_code ignored;
    fs::remove_all(slot.folder, ignored);
    slot.job.reset();
    --busy_;
    finish_lane(job, std::move(*result));
  }

  // Concludes and reports, in the order of `files`, every scene whose lanes are all in.
  void report_ready() {
    while (next_to_report_ < next_to_prepare_ && scenes_[next_to_report_].waiting == 0) {
      SceneInWork& scene = scenes_[next_to_report_++];
      for (Lane lane : scene.checked.lanes) scene.checked.result.lanes.push_back(std::move(scene.results[lane]));
      if (!scene.output.empty()) output_(scene.output);
      checker_.conclude(scene.checked);
      done_(std::move(scene.checked));
    }
  }

  void finish_lane(const Job& job, LaneResult result) {
    SceneInWork& scene = scenes_[job.scene];
    scene.results[job.lane] = std::move(result);
    --scene.waiting;
  }

  SceneChecker& checker_;
  const SceneWorkers& workers_;
  const std::vector<fs::path>& files_;
  const std::vector<Lane>& lanes_;
  const std::function<void(CheckedScene&&)>& done_;
  const std::function<void(const std::string&)>& output_;
  WorkerTotals totals_;
  std::vector<SceneInWork> scenes_;
  const Result<ScratchFolder>& scratch_;
  std::deque<Job> queued_;
  std::vector<WorkerSlot>& slots_;
  size_t busy_ = 0;
  size_t next_to_prepare_ = 0, next_to_report_ = 0;
};

}  // namespace lane_workers_internal

unsigned driver_threads_per_worker(unsigned cores, unsigned jobs) { return std::max(1u, cores / std::max(1u, jobs)); }

WorkerTotals check_in_workers(SceneChecker& checker, LaneWorkerPool& pool, const std::vector<fs::path>& files,
                              const std::vector<Lane>& lanes, const std::function<void(CheckedScene&&)>& done,
                              const std::function<void(const std::string&)>& output) {
  return lane_workers_internal::LaneRenderPool(checker, *pool.state_, files, lanes, done, output).run();
}

WorkerTotals check_in_workers(SceneChecker& checker, const SceneWorkers& workers, const std::vector<fs::path>& files,
                              const std::vector<Lane>& lanes, const std::function<void(CheckedScene&&)>& done,
                              const std::function<void(const std::string&)>& output) {
  LaneWorkerPool pool(workers);
  return check_in_workers(checker, pool, files, lanes, done, output);
}

void report_worker_status(const std::string& line) {
  const std::string text = line + "\n";
  // Nobody listening (a worker started by hand) is no reason to stop.
  [[maybe_unused]] const ssize_t written = ::write(kChildStatusFd, text.data(), text.size());
}

int run_lane_worker(SceneChecker& checker, const fs::path& scene_file, Lane lane, const fs::path& result_dir) {
  const auto status = report_worker_status;
  status("while loading the scene");
  // A worker may serve many renders: what it compiled for this one is the counters' growth.
  VariantCompiler& compiler = checker.compiler();
  const size_t compiled_before = compiler.compiled(), cached_before = compiler.cached();
  (void)compiler.take_files_read();  // an earlier render's
  CheckedScene checked = checker.prepare(scene_file, {lane});
  LaneResult result;
  if (checked.lanes.empty()) {
    // Its supervisor prepared this scene and found the lane in it: the file changed since.
    result.lane = std::string(lane_name(lane));
    result.verdict = checked.result.verdict == Verdict::Pass ? Verdict::Error : checked.result.verdict;
    result.message =
        checked.result.message.empty() ? "the scene no longer runs on " + result.lane : checked.result.message;
  } else {
    checker.check_lane(lane, checked, status);
    result = std::move(checked.result.lanes.back());
  }
  if (auto image = checked.images.find(lane); image != checked.images.end())
    if (!write_file_atomically(result_dir / "image.f32", float_image_bytes(image->second))) return 3;
  nlohmann::json read = nlohmann::json::array();
  for (const fs::path& file : compiler.take_files_read()) read.push_back(file.string());
  const nlohmann::json handover = {
      {"result", lane_to_json(result)},
      {"read", std::move(read)},
      {"compiled", compiler.compiled() - compiled_before},
      {"cached", compiler.cached() - cached_before},
      {"cache_write_error", compiler.cache_write_error() ? compiler.cache_write_error()->to_string() : ""},
      {"cache_damage", compiler.cache_damage() ? compiler.cache_damage()->to_string() : ""}};
  if (!write_file_atomically(result_dir / "lane.json", handover.dump())) return 3;
  return 0;
}

}  // namespace xshade::harness
