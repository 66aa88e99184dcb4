// The worker processes of the verbs that render: how one is started (this program again, with
// the verb's folders and options already resolved), how many at once, and their time limit.
#pragma once

#include <string>
#include <vector>

#include "cli/commands.h"
#include "harness/gate/lane_workers.h"

namespace xshade::cli {

// This program's own path, to start it again as a worker.
std::string this_program();

unsigned worker_jobs(const WorkerLimits& limits);
double worker_timeout(const WorkerLimits& limits);

// What every worker's environment gets: llvmpipe's and lavapipe's thread count
// (LP_NUM_THREADS) shared out so that `jobs` workers use the cores once, unless the user set it.
std::vector<std::string> worker_environment(unsigned jobs);

// The `xshade worker` command line for `shared` (its scene, lane and result folder are added per
// render), with `limits`.
harness::SceneWorkers scene_workers(const WorkerOptions& shared, const WorkerLimits& limits);

}  // namespace xshade::cli
