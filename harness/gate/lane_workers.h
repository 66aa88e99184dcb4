// Each scene-and-lane render in a worker process of its own, as conformance runners run their
// tests: a worker that crashes, is killed or passes its time limit is that scene and lane's
// failure, named with where it was ("timeout after 120 s in pass bokeh (render 1 of 2)",
// "worker died: SIGSEGV (segmentation fault) in pass scene (render 2 of 2)"), and the run goes on
// with the others. Workers are also how a run uses every core: up to `jobs` run at once, and the
// results, images and their order do not depend on how many.
//
// A worker is this program again (SceneWorkers::command names how to start it, with --serve): it
// renders one lane of one scene after another as its supervisor asks on its standard input, and
// hands each result over in a folder: lane.json (the lane's result as harness/gate/result_json.h
// writes it, and what it compiled) and image.f32 (the lane's float image, exactly). Its status
// lines ("while compiling", "in pass bokeh (render 1 of 2)", then "done CODE") come on
// kChildStatusFd (base/subprocess.h). A worker lives as long as its renders end well: starting
// one costs as much as a render, and a long-lived one keeps its driver's compiled shaders; one
// that crashed or was stopped at its time limit is replaced for the next render.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "harness/gate/scene_check.h"

namespace xshade::harness {

// A render that takes longer than this is stopped and fails. The slowest fixed scene-and-lane
// takes about 6 s as a whole `xshade run` (compile, two renders, the checks, the report) on a
// 2-core machine busy with other work (ctest's scene.material_grid.gl); 120 s leaves a slower CI
// machine twenty times that, and still ends a shader stuck in a loop within two minutes. A scene
// may set its own (`timeout`, with `timeout_reason`).
inline constexpr double kDefaultTimeoutSeconds = 120.0;

struct SceneWorkers {
  // The program and arguments that start a worker; "--serve" is added.
  std::vector<std::string> command;
  // What a worker forked from this process runs instead (the same as the command runs, without
  // loading the program again); empty, or when this process has threads: the command.
  std::function<int()> serve;
  unsigned jobs = 1;
  double timeout_seconds = kDefaultTimeoutSeconds;  // unless the scene sets its own
  // Set in each worker's environment (e.g. LP_NUM_THREADS, so that llvmpipe's and lavapipe's
  // own threads do not ask for more cores than there are).
  std::vector<std::string> environment;
};

// What the workers compiled, over the whole run.
struct WorkerTotals {
  size_t renders = 0;             // scene-and-lane renders handed to workers
  size_t workers_started = 0;     // worker processes it took: one per job slot, and one after each that ended
  size_t compiled = 0;            // shader variants compiled
  size_t cached = 0;              // found in the cache
  std::string cache_write_error;  // the first one, when a worker could not write the cache
  std::string cache_damage;       // the first damaged entry a worker found (and recompiled)
};

// Workers and their results' folder, kept from one check_in_workers to the next: `xshade watch`
// renders again with workers whose drivers and compilers are warm. Destroying it kills the workers
// and removes the folder. Making it first removes the workers' folders that dead runs of this
// user left.
class LaneWorkerPool {
 public:
  explicit LaneWorkerPool(SceneWorkers workers);
  ~LaneWorkerPool();
  LaneWorkerPool(const LaneWorkerPool&) = delete;
  LaneWorkerPool& operator=(const LaneWorkerPool&) = delete;

  struct State;  // lane_workers.cpp's

 private:
  friend WorkerTotals check_in_workers(SceneChecker&, LaneWorkerPool&, const std::vector<std::filesystem::path>&,
                                       const std::vector<Lane>&, const std::function<void(CheckedScene&&)>&,
                                       const std::function<void(const std::string&)>&);
  std::unique_ptr<State> state_;
};

// Checks each scene of `files` on those of `lanes` it lists, each lane in a worker of `pool`;
// `done` gets each scene once it is concluded, in the order of `files`, with the files its lanes'
// compiles read in CheckedScene::files_read. Worker output (a driver's warnings) goes to `output`
// with its scene. When the process is asked to stop (base/interrupt.h) it returns early (the
// workers are killed with the pool); the scenes not yet given to `done` are not.
WorkerTotals check_in_workers(SceneChecker& checker, LaneWorkerPool& pool,
                              const std::vector<std::filesystem::path>& files, const std::vector<Lane>& lanes,
                              const std::function<void(CheckedScene&&)>& done,
                              const std::function<void(const std::string&)>& output);
// The same with a pool of its own, whose workers and folder are gone when it returns.
WorkerTotals check_in_workers(SceneChecker& checker, const SceneWorkers& workers,
                              const std::vector<std::filesystem::path>& files, const std::vector<Lane>& lanes,
                              const std::function<void(CheckedScene&&)>& done,
                              const std::function<void(const std::string&)>& output);

// The worker's side: one lane of one scene checked in this process, its result and image written
// to `result_dir`, its status to kChildStatusFd. The exit code is 0 when the result was written
// (whatever its verdict), 3 when it could not be.
int run_lane_worker(SceneChecker& checker, const std::filesystem::path& scene_file, Lane lane,
                    const std::filesystem::path& result_dir);

// A status line from a worker to its supervisor (on kChildStatusFd).
void report_worker_status(const std::string& line);

// The number of llvmpipe/lavapipe threads each of `jobs` workers should use on `cores` cores:
// together they use the cores once, each at least one.
unsigned driver_threads_per_worker(unsigned cores, unsigned jobs);

}  // namespace xshade::harness
