// The verbs of the xshade command line, one file each.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "base/result.h"
#include "cli/folders.h"

namespace CLI {
class App;
}

namespace xshade::cli {

// A verb of the command line: its subcommand, which parsing marks when it is given, and what runs
// it then, with the whole command line (which run, report merge and the studies record). Each
// verb's file registers its own options (add_*_command below, in --help's order in main.cpp).
struct Verb {
  CLI::App* command = nullptr;
  std::function<int(const std::string& command_line)> run;
};
Verb add_info_command(CLI::App& app);
Verb add_run_command(CLI::App& app);
Verb add_bless_command(CLI::App& app);
Verb add_compile_command(CLI::App& app);
Verb add_eval_command(CLI::App& app);
Verb add_worker_command(CLI::App& app);  // the workers run, bless and eval start; not in --help
Verb add_report_command(CLI::App& app);  // report merge
Verb add_diff_command(CLI::App& app);
Verb add_stability_command(CLI::App& app);
Verb add_accuracy_command(CLI::App& app);
Verb add_watch_command(CLI::App& app);

// The exit codes every verb shares (docs/cli.md).
enum ExitCode : int {
  kPass = 0,           // everything checked passed
  kTestFailed = 1,     // a check failed: images differ, a lane disagrees
  kBadInput = 2,       // bad usage, a bad shader or scene file
  kBackendError = 3,   // a driver or lane could not run, or an internal error
  kInterrupted = 128,  // plus the signal, as a shell reports it: stopped by ^C (130) or `kill` (143)
};

// The exit code of a verb that an error of `kind` stopped: whose fault it is decides.
inline int exit_code_of(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::UserInput:
    case ErrorKind::Usage: return kBadInput;
    case ErrorKind::CheckFailed: return kTestFailed;
    case ErrorKind::Backend:
    case ErrorKind::Internal: return kBackendError;
  }
  return kBackendError;
}

// Runs a verb: errors travel as values, and an exception that still escapes (an allocation that
// failed, a library that throws) is reported as a crash of xshade's (exit 3) naming the verb,
// never an abort. main runs every verb so, and a forked worker its renders.
int guarded_verb(const std::string& verb, const std::function<int()>& body);

// A ceiling on each xshade process's address space (RLIMIT_AS, which its workers inherit), so
// that a runaway allocation is a std::bad_alloc that guarded_verb reports (exit 3), not the
// kernel's OOM killer: `setting` in GiB (XSHADE_MEMORY_LIMIT; "0" for none), by default half the
// machine's memory. Never raises a lower limit already set. A `setting` that is not a number is
// the user's error.
Result<void> limit_memory(const char* setting);

struct LaneSelection {
  std::vector<std::string> lanes;  // empty = every lane
  bool validation = false;
  std::string gl_platform = "auto";  // how the gl lane gets its context: auto, osmesa or egl
};

int run_info(const LaneSelection& selection);

// How a verb's renders run: each scene-and-lane (each lane of eval) in a worker process of its
// own, up to `jobs` at once, each stopped after `timeout_seconds`.
struct WorkerLimits {
  unsigned jobs = 0;             // 0: one per core
  double timeout_seconds = 0.0;  // 0: harness::kDefaultTimeoutSeconds (a scene may set its own)
};

struct RunOptions {
  LaneSelection selection;
  std::vector<std::string> scenes;  // names in the scenes folder, or .toml paths; empty = all
  FolderOptions folders;
  std::filesystem::path report_dir = "report";
  std::filesystem::path cache_dir;  // empty: $XSHADE_CACHE_DIR, else the user's cache folder
  bool no_cache = false;
  std::string shard;                // "i/N": every N-th scene from the i-th, in name order
  std::string precision = "float";  // or "half": half emulation (gl and vk; goldens not compared)
  bool plan_only = false;
  bool pass_images = false;      // also write each pass's output (REPORT/SCENE/passes/PASS.LANE.exr)
  bool trace_nonfinite = false;  // trace every gl and vk lane, not only those with non-finite pixels
  WorkerLimits workers;
  std::string command_line;  // for the reports
};
int run_run(const RunOptions& options);

// `xshade watch`: run, then render again what each saved file reaches, serving the report.
struct WatchOptions {
  LaneSelection selection;
  std::vector<std::string> scenes;  // as RunOptions::scenes
  FolderOptions folders;
  std::filesystem::path report_dir = "watch-report";
  std::filesystem::path cache_dir;
  uint16_t port = 8123;  // on 127.0.0.1; 0: any free port
  WorkerLimits workers;
  std::string command_line;
};
int run_watch(const WatchOptions& options);

struct BlessOptions {
  std::string scene;
  std::string lane;  // empty: the common golden, from lanes that agree
  std::string reason;
  FolderOptions folders;
  std::filesystem::path cache_dir;
  std::filesystem::path report_dir = "bless-report";  // where the rendered images go
  std::string gl_platform = "auto";                   // as LaneSelection::gl_platform
  WorkerLimits workers;
};
int run_bless(const BlessOptions& options);

struct CompileOptions {
  std::filesystem::path file;
  std::vector<std::filesystem::path> include_dirs;
  std::vector<std::string> defines;  // KEYWORD, or KEY=VALUE
  std::string target = "vk";         // gl, vk, spirv, vk-hlsl
  std::string precision = "float";   // or "half": half emulation (gl, vk, spirv)
  bool trace_nonfinite = false;      // the tracing variant of the fragment stage (gl, vk, spirv)
  bool reflect = false;
  std::filesystem::path output;           // a path prefix; empty = standard output
  std::string entry;                      // a fragment function, compiled as a full-screen pass
  std::string pass;                       // a post pass by its #pragma pass name
  bool all_variants = false;              // every keyword combination the file declares, each reported
  std::string unity_platform = "glcore";  // a .shader's: glcore, d3d11 or vulkan
  bool generated = false;                 // a .shader's passes' HLSL as composed and generated, not compiled
  FolderOptions folders;                  // the project file's shader folders (only shaders, project, no_project)
};
int run_compile(const CompileOptions& options);

struct EvalOptions {
  std::vector<std::filesystem::path> files;  // each evaluated on its own, with these options
  std::vector<std::filesystem::path> include_dirs;
  std::vector<std::string> keywords;
  std::string entry;  // the fragment function; empty = #pragma fragment
  std::string size = "64x64";
  std::string precision = "float";  // or "half": half emulation on the GLSL lanes
  LaneSelection selection;          // "all" or a list
  std::filesystem::path output_dir = ".";
  std::optional<uint32_t> seed;              // inputs from this seed instead of the defaults and white
  std::vector<std::string> specializations;  // NAME=VALUE: a [[vk::constant_id]] constant's value
  bool allow_non_finite = false;             // NaN, Inf and negative output is reported, not a failure
  bool trace_nonfinite = false;              // render the tracing variant too and say where non-finite values were born
  bool write_images = true;                  // false: compare and print only; the image library is never loaded
  WorkerLimits workers;
  bool in_worker = false;  // this process is one lane's worker: render it here
};
int run_eval(const EvalOptions& options);

// `xshade worker`: one lane of one scene, for the run or bless that started it
// (harness/gate/lane_workers.h). Not for users; its options are the supervisor's resolved ones.
struct WorkerOptions {
  std::filesystem::path scene = {};
  std::string lane = {};
  std::filesystem::path result_dir = {};
  std::vector<std::filesystem::path> shader_folders = {};  // the whole search path, in order
  std::filesystem::path golden = {};                       // empty: no golden layer
  std::filesystem::path report_dir = {};
  std::filesystem::path cache_dir = {};  // empty: no cache
  std::string gl_platform = "auto";
  bool validation = false;
  bool pass_images = false;
  bool half_emulation = false;
  bool trace_nonfinite = false;
  bool serve = false;  // renders read from standard input, one a line, instead of scene and lane
};
int run_worker(const WorkerOptions& options);

// `xshade report merge`: several runs' reports (each a report folder, or a folder of them) as one.
struct ReportMergeOptions {
  std::vector<std::filesystem::path> folders;
  std::filesystem::path out;
  bool exit_code = false;   // exit with the merged verdict's code, as xshade run would
  bool cross_lane = false;  // hold the lanes of scenes whose lanes came from separate runs against each other
  std::string command_line;
};
int run_report_merge(const ReportMergeOptions& options);

// `xshade diff A B`: B held against A by the comparison model's layers.
struct DiffOptions {
  std::filesystem::path a;         // the reference (a golden)
  std::filesystem::path b;         // the image under test
  uint32_t tolerance = 1;          // channel tolerance, 8-bit sRGB steps
  double budget = 0.0;             // fraction of the pixels that may fail
  uint32_t radius = 0;             // position radius, pixels
  double float_tolerance = 0.005;  // relative, for values above 1
  std::filesystem::path heat_map;  // PNG of the difference, when asked
  std::filesystem::path mask;      // PNG, white where the per-pixel layer failed, when asked
  bool json = false;
  // --metric: the verdict is this metric's against its threshold (harness/image/metric_layers.h)
  // instead of the per-pixel layers'.
  std::string metric;
  std::optional<double> threshold;  // the metric's default when not given
  double pixel_threshold = 1.0;     // deltae: per-pixel CIEDE2000 ignored below
  double incorrect_fraction = 0.0;  // deltae: pixels above the per-pixel threshold allowed
  double pixels_per_degree = 0.0;   // flip: 0 for the reference implementation's 67.02
};
int run_diff(const DiffOptions& options);

struct StabilityOptions {
  LaneSelection selection;
  std::string precision = "all";   // float, half or all
  std::vector<std::string> cases;  // ids; empty = every case
  bool list = false;               // print the cases and run nothing
  std::filesystem::path markdown;  // write docs/stability.md's text here
  std::filesystem::path shaders_dir = own_folders().shaders;
  std::filesystem::path probes_dir = own_folders().probes;
  std::filesystem::path scenes_dir = own_folders().scenes;
  std::string command_line;
};
int run_stability(const StabilityOptions& options);

struct AccuracyOptions {
  LaneSelection selection;
  std::vector<std::string> studies;  // ids; empty = every study (or the quick ones)
  bool quick = false;                // one round, no reference check, the quick studies
  uint32_t rounds = 5;
  std::filesystem::path report_dir = "accuracy-report";
  std::filesystem::path markdown;  // also write docs/accuracy.md's text here, charts beside it
  std::filesystem::path scenes_dir = own_folders().scenes;
  std::filesystem::path shaders_dir = own_folders().shaders;
  // Shader folders searched before the library: a study of Unity shaders names theirs and
  // Unity's include files here.
  std::vector<std::filesystem::path> shader_folders;
  std::string command_line;
};
int run_accuracy(const AccuracyOptions& options);

}  // namespace xshade::cli
