// xshade eval: fragment shaders, each as a full-screen pass on each lane, the images written as
// EXR, and how far the lanes agree.
#include <fmt/core.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "base/file_io.h"
#include "base/subprocess.h"
#include "cli/command_options.h"
#include "cli/commands.h"
#include "cli/lane_selection.h"
#include "cli/workers.h"
#include "harness/image/image_compare.h"
#include "harness/image/image_io.h"
#include "harness/render/evaluate.h"
#include "harness/render/nonfinite_origins.h"

namespace xshade::cli {

namespace {

// How far each lane's image is from the first lane's.
void print_lane_differences(const std::map<harness::Lane, harness::FloatImage>& images) {
  if (images.size() < 2) return;
  const auto& [first_lane, first] = *images.begin();
  for (const auto& [lane, image] : images) {
    if (lane == first_lane) continue;
    const harness::ImageDifference difference = harness::max_difference(first, image);
    const auto pixel = first.at(difference.x, difference.y);
    const auto other = image.at(difference.x, difference.y);
    if (harness::bitwise_equal(first, image))
      fmt::print("{} vs {}: bit-identical\n", harness::lane_name(first_lane), harness::lane_name(lane));
    else
      fmt::print("{} vs {}: max difference {:g} at ({}, {}) channel {}: {:g} vs {:g}\n", harness::lane_name(first_lane),
                 harness::lane_name(lane), difference.max, difference.x, difference.y, "rgba"[difference.channel],
                 pixel[int(difference.channel)], other[int(difference.channel)]);
  }
}

// --trace-nonfinite: the tracing variant on the same inputs, its image held to the plain one, and
// where its non-finite pixels were born.
void print_traced(const EvalOptions& options, const std::filesystem::path& file, const hlsl::Module& module,
                  harness::Lane lane, harness::Backend& backend, const harness::FloatImage& plain, uint32_t width,
                  uint32_t height) {
  const std::string name(harness::lane_name(lane));
  harness::ProgramOptions traced_options{.half_emulation = options.precision == "half", .trace_nonfinite = true};
  auto program = harness::FullscreenProgram::create(module, lane, backend, traced_options);
  if (!program) {
    fmt::print("{}: not traced: {}\n", name, program.error().message);
    return;
  }
  harness::FloatImage record;
  auto traced = options.seed ? program->run_seeded(backend, width, height, *options.seed, &record)
                             : program->run(backend, width, height, {}, &record);
  (void)backend.destroy(program->handle());  // made here, destroyed once
  if (!traced) {
    fmt::print("{}: the traced render failed: {}\n", name, traced.error().to_string());
    return;
  }
  fmt::print("{}: traced image {}\n", name,
             harness::bitwise_equal(*traced, plain)
                 ? "bit-identical to the plain one"
                 : "DIFFERS from the plain one (the tracing variant changed a value)");
  harness::CompiledVariant variant;
  variant.program.name = module.sources.name(module.main_file);
  variant.trace = program->trace();
  auto origins = harness::find_nonfinite_origins(*traced, {"eval", std::move(record)}, {variant});
  if (!origins) {
    fmt::print("{}: {}\n", name, origins.error().to_string());
    return;
  }
  if (origins->origins.empty() && !origins->unattributed_pixels) {
    fmt::print("{}: no pixel's output is NaN, Inf or negative\n", name);
    return;
  }
  fmt::print("{}: where the non-finite values were born:\n{}", name, harness::describe_origins(*origins));
  if (!options.write_images) return;
  const auto map = options.output_dir / (file.stem().string() + "." + name + ".origins.png");
  if (auto written = harness::write_png(origins->map, map); written)
    fmt::print("{}: origins map {}\n", name, map.string());
}

// Where eval writes a lane's image, and where that lane's worker hands it over first (beside it,
// hidden, removed once read).
std::filesystem::path exr_path(const EvalOptions& options, const std::filesystem::path& file, const std::string& lane) {
  return options.output_dir / (file.stem().string() + "." + lane + ".exr");
}
std::filesystem::path handover_path(const EvalOptions& options, const std::filesystem::path& file,
                                    const std::string& lane) {
  return options.output_dir / ("." + file.stem().string() + "." + lane + ".f32");
}

// The options of `options` for one lane's worker: the same eval of `files`, that lane alone.
std::vector<std::string> worker_command(const EvalOptions& options, harness::Lane lane,
                                        const std::vector<std::filesystem::path>& files) {
  std::vector<std::string> command = {this_program(), "eval"};
  for (const auto& file : files) command.push_back(file.string());
  command.insert(command.end(), {"--in-worker", "--lane", std::string(harness::lane_name(lane)), "--size", options.size,
                                 "--precision", options.precision, "--gl-platform", options.selection.gl_platform, "-o",
                                 options.output_dir.string()});
  if (!options.entry.empty()) command.insert(command.end(), {"--entry", options.entry});
  for (const auto& folder : options.include_dirs) command.insert(command.end(), {"-I", folder.string()});
  for (const std::string& keyword : options.keywords) command.insert(command.end(), {"-D", keyword});
  if (options.seed) command.insert(command.end(), {"--seed", std::to_string(*options.seed)});
  for (const std::string& given : options.specializations) command.insert(command.end(), {"--specialize", given});
  if (options.allow_non_finite) command.push_back("--allow-nonfinite");
  if (options.trace_nonfinite) command.push_back("--trace-nonfinite");
  if (!options.write_images) command.push_back("--no-images");
  return command;
}

// One file of an eval: what its front end said, then each lane's lines and image.
struct FileEval {
  std::filesystem::path file;
  std::unique_ptr<hlsl::Module> module = {};       // null when the front end refused it
  std::map<uint32_t, double> specialization = {};  // --specialize, resolved against the module
  std::string front_end_output = {};
  int exit_code = kPass;
  std::map<harness::Lane, std::string> lane_output = {};
  std::map<harness::Lane, harness::FloatImage> images = {};
  size_t lanes_done = 0;
};

// The front end for `file`: the module when it can be evaluated, else its exit code with why.
void compile_for_eval(const EvalOptions& options, FileEval& eval) {
  hlsl::CompileOptions front_end;
  front_end.include_dirs = include_folders(options.include_dirs);
  front_end.keywords = options.keywords;
  front_end.fragment_only_entry = options.entry;
  front_end.fragment_only = true;  // eval draws it full-screen: a vertex function is not its to compile
  if (options.precision == "half") front_end.defines.push_back({harness::kHalfEmulationMacro, "1"});
  std::unique_ptr<hlsl::Module> module = hlsl::compile_file(eval.file, front_end);
  if (!module->diagnostics.diagnostics().empty()) eval.front_end_output += module->diagnostics.render_all();
  eval.exit_code = kBadInput;
  if (!module->ok()) return;
  if (!module->entry_points.fragment) {
    eval.front_end_output += fmt::format(
        "xshade eval: {} has no fragment entry point; name one with --entry or #pragma fragment\n", eval.file.string());
    return;
  }
  // A shader that writes only SV_Depth leaves the colour undefined: nothing to compare.
  const auto& outputs = module->reflection.fragment_outputs;
  if (std::none_of(outputs.begin(), outputs.end(),
                   [](const hlsl::StageVariable& output) { return output.semantic.starts_with("SV_Target"); })) {
    eval.front_end_output += fmt::format(
        "xshade eval: {} writes no colour (SV_Target); eval renders and compares colour only\n", eval.file.string());
    return;
  }
  auto specialization = harness::resolve_specialization(options.specializations, module->reflection);
  if (!specialization) {
    eval.front_end_output += fmt::format("xshade eval: {}: {}\n", eval.file.string(), specialization.error().message);
    return;
  }
  eval.specialization = std::move(*specialization);
  eval.exit_code = kPass;
  eval.module = std::move(module);
}

// One lane's worker and the files it has still to do (cli/workers.h): it evaluates them in
// order, ending each file's lines with kFileEnd and then reporting "done INDEX CODE" on its status
// pipe, and has the run's time limit for each file. One that dies or passes the limit is that
// file's failure on that lane; the files after it go to a new worker.
struct LaneJob {
  harness::Lane lane;
  std::vector<size_t> todo;  // indices into the evals, in order
  size_t next = 0;           // the first of `todo` not concluded
  std::optional<ChildProcess> worker = {};
  size_t first_given = 0;  // the worker's file 0 is todo[first_given]
  // What the worker printed that is not yet a concluded file's: its output and its status come
  // through two pipes, so a read may already hold the next file's lines.
  std::string output = {};
  bool finished() const { return next == todo.size(); }

  // The lines of the file the worker has just reported done: up to its kFileEnd.
  std::string take_file_output();
};

// The line a worker prints after each file's lines (an ASCII record separator, which no message
// holds).
constexpr std::string_view kFileEnd = "\x1e\n";

std::string LaneJob::take_file_output() {
  const size_t end = output.find(kFileEnd);
  if (end == std::string::npos) return std::exchange(output, {});
  std::string file = output.substr(0, end);
  output.erase(0, end + kFileEnd.size());
  return file;
}

// The lane's result for `eval`, from its worker's output, exit code and handed-over image.
void conclude_lane(const EvalOptions& options, harness::Lane lane, FileEval& eval, std::string output,
                   const ChildExit& exit, double timeout) {
  const std::string name(harness::lane_name(lane));
  if (exit.timed_out) {
    output += fmt::format("{}: timeout after {:g} s; a slower shader needs --timeout SECONDS\n", name, timeout);
    eval.exit_code = std::max<int>(eval.exit_code, kTestFailed);
  } else if (exit.signal) {
    output += fmt::format("{}: worker died: {}\n", name, describe_signal(exit.signal));
    eval.exit_code = std::max<int>(eval.exit_code, kBackendError);
  } else {
    eval.exit_code = std::max(eval.exit_code, exit.code);
    const auto handover = handover_path(options, eval.file, name);
    const std::optional<std::string> bytes = read_file(handover);
    std::error_code ignored;
    std::filesystem::remove(handover, ignored);
    std::optional<harness::FloatImage> image = bytes ? harness::float_image_from(*bytes) : std::nullopt;
    if (image && options.write_images) {
      if (auto written = harness::write_exr(*image, exr_path(options, eval.file, name)); !written) {
        output += fmt::format("xshade eval: {}\n", written.error().to_string());
        eval.exit_code = std::max<int>(eval.exit_code, kBackendError);
      }
    }
    if (exit.code != kBackendError && image) eval.images.emplace(lane, std::move(*image));
  }
  eval.lane_output[lane] = std::move(output);
  ++eval.lanes_done;
}

// A status line "done INDEX CODE" from an eval worker: the index and exit code.
std::optional<std::pair<size_t, int>> parse_done(const std::string& line) {
  size_t index = 0;
  int code = 0;
  if (std::sscanf(line.c_str(), "done %zu %d", &index, &code) != 2) return std::nullopt;
  return std::pair{index, code};
}

// Each lane in a worker of its own (cli/workers.h): a lane whose driver crashes or whose shader
// hangs is reported as that lane's and the others still run. A worker evaluates every file of
// its lane with one driver (starting one costs more than a small render). Each worker writes its
// images and its lines; this process prints them file by file in lane order and compares the
// images, a file as soon as every lane has done it.
int run_eval_lanes_in_workers(const EvalOptions& options, const std::vector<harness::Lane>& lanes,
                              std::vector<FileEval>& evals) {
  const unsigned jobs = worker_jobs(options.workers);
  const double timeout = worker_timeout(options.workers);
  const auto time_limit =
      std::chrono::duration_cast<ChildProcess::Clock::duration>(std::chrono::duration<double>(timeout));
  const std::vector<std::string> environment = worker_environment(jobs);
  const bool several = evals.size() > 1;
  std::vector<size_t> runnable;
  for (size_t i = 0; i < evals.size(); ++i)
    if (evals[i].module) runnable.push_back(i);
  std::vector<LaneJob> lane_jobs;
  for (harness::Lane lane : lanes) lane_jobs.push_back({.lane = lane, .todo = runnable});

  int exit_code = kPass;
  size_t next_to_print = 0;
  const auto print_ready = [&] {
    for (; next_to_print < evals.size(); ++next_to_print) {
      FileEval& eval = evals[next_to_print];
      if (eval.module && eval.lanes_done < lanes.size()) return;
      if (several) fmt::print("== {}\n", eval.file.string());
      std::fflush(stdout);
      fmt::print(stderr, "{}", eval.front_end_output);
      std::fflush(stderr);
      for (harness::Lane lane : lanes) fmt::print("{}", eval.lane_output[lane]);
      print_lane_differences(eval.images);
      if (several) fmt::print("== {}: exit {}\n", eval.file.string(), eval.exit_code);
      std::fflush(stdout);
      exit_code = std::max(exit_code, eval.exit_code);
      eval.images.clear();  // printed: a long batch keeps no image or module it is done with
      eval.module.reset();
    }
  };
  print_ready();  // the files the front end refused, before the first that renders
  size_t next_to_start = 0;
  while (std::any_of(lane_jobs.begin(), lane_jobs.end(), [](const LaneJob& job) { return !job.finished(); })) {
    // Lanes start in order, up to `jobs` at once; a lane keeps its slot until its files are done.
    size_t running = 0;
    for (size_t i = 0; i < next_to_start; ++i) running += !lane_jobs[i].finished();
    for (; running < jobs && next_to_start < lane_jobs.size(); ++next_to_start)
      running += !lane_jobs[next_to_start].finished();
    std::vector<ChildProcess*> waiting;
    for (size_t j = 0; j < next_to_start; ++j) {
      LaneJob& job = lane_jobs[j];
      const std::string name(harness::lane_name(job.lane));
      if (job.finished()) continue;
      if (!job.worker) {
        std::vector<std::filesystem::path> files;
        for (size_t k = job.next; k < job.todo.size(); ++k) {
          files.push_back(evals[job.todo[k]].file);
          std::error_code ignored;  // what an earlier eval that was stopped left
          std::filesystem::remove(handover_path(options, files.back(), name), ignored);
        }
        auto worker = ChildProcess::start(worker_command(options, job.lane, files), environment, time_limit);
        if (!worker) {
          for (; job.next < job.todo.size(); ++job.next) {
            FileEval& eval = evals[job.todo[job.next]];
            eval.lane_output[job.lane] =
                fmt::format("{}: cannot start a worker: {}\n", name, worker.error().to_string());
            eval.exit_code = std::max<int>(eval.exit_code, kBackendError);
            ++eval.lanes_done;
          }
          continue;
        }
        job.worker = std::move(*worker);
        job.first_given = job.next;
      }
      ChildProcess& worker = *job.worker;
      const bool ended = worker.poll();
      for (const std::string& line : worker.take_status_lines()) {
        const auto done = parse_done(line);
        if (!done || job.first_given + done->first != job.next) continue;
        worker.poll();  // what it printed before the status line
        job.output += worker.take_output();
        conclude_lane(options, job.lane, evals[job.todo[job.next]], job.take_file_output(), ChildExit{done->second},
                      timeout);
        ++job.next;
        worker.set_deadline(ChildProcess::Clock::now() + time_limit);  // the limit is each file's
      }
      if (ended) {
        if (!job.finished()) {
          // It ended before concluding this file: a crash, a timeout, or an exit with no status.
          ChildExit exit = worker.exit_status();
          std::string output = std::exchange(job.output, {}) + worker.take_output();
          if (!exit.timed_out && !exit.signal) {
            output += fmt::format("{}: the worker ended (exit {}) before it finished this file\n", name, exit.code);
            exit.code = std::max<int>(exit.code, kBackendError);
          }
          conclude_lane(options, job.lane, evals[job.todo[job.next]], std::move(output), exit, timeout);
          ++job.next;
        }
        job.worker.reset();
        continue;
      }
      waiting.push_back(&worker);
    }
    print_ready();
    if (!waiting.empty()) wait_for_any(waiting, std::chrono::milliseconds(1000));
  }
  print_ready();
  return exit_code;
}

// A worker: `lane` for each file in order, with one backend.
int evaluate_lane_in_worker(const EvalOptions& options, harness::Lane lane, std::vector<FileEval>& evals,
                            uint32_t width, uint32_t height) {
  const std::string name(harness::lane_name(lane));
  auto backend = harness::create_backend(lane, backend_options(options.selection));
  int exit_code = kPass;
  for (size_t index = 0; index < evals.size(); ++index) {
    FileEval& eval = evals[index];
    const int code = [&]() -> int {
      if (!eval.module) return eval.exit_code;  // its supervisor says why
      if (!backend) {
        fmt::print("{}: unavailable: {}\n", name, backend.error().to_string());
        return kBackendError;
      }
      const hlsl::Module& module = *eval.module;
      const harness::ProgramOptions program_options{.half_emulation = options.precision == "half",
                                                    .specialization = eval.specialization};
      auto image = options.seed ? [&]() -> Result<harness::FloatImage> {
        auto program = harness::FullscreenProgram::create(module, lane, **backend, program_options);
        if (!program) return fail(program.error());
        auto seeded = program->run_seeded(**backend, width, height, *options.seed);
        (void)(*backend)->destroy(program->handle());  // made here, destroyed once
        return seeded;
      }()
          : harness::evaluate(module, lane, **backend, width, height, {}, program_options);
      if (image && options.trace_nonfinite)
        print_traced(options, eval.file, module, lane, **backend, *image, width, height);
      if (!image) {
        fmt::print("{}: failed: {}\n", name, image.error().to_string());
        return kBackendError;
      }
      int result = kPass;
      for (const std::string& message : (*backend)->take_driver_messages())
        fmt::print("{}: driver message: {}\n", name, message);
      // The image goes to the process that started this worker, which writes the EXR: a worker
      // then never loads the image library (harness/image/image_codec.h), a third of a second a lane.
      if (auto handed =
              write_file_atomically(handover_path(options, eval.file, name), harness::float_image_bytes(*image));
          !handed) {
        fmt::print(stderr, "xshade eval: {}\n", handed.error().to_string());
        result = kBackendError;
      } else if (options.write_images) {
        fmt::print("{}: {}\n", name, exr_path(options, eval.file, name).string());
      }
      // A NaN, an Inf or a negative colour is a failure unless the shader is a test of such a hazard.
      if (const harness::NonFiniteCount bad = harness::count_non_finite(*image); bad.total()) {
        fmt::print("{}: {}{}\n", name, harness::describe_non_finite(bad),
                   options.allow_non_finite ? " (allowed by --allow-nonfinite)" : "");
        if (!options.allow_non_finite) result = std::max<int>(result, kTestFailed);
      }
      return result;
    }();
    std::fflush(stderr);
    fmt::print("{}", kFileEnd);
    std::fflush(stdout);
    harness::report_worker_status(fmt::format("done {} {}", index, code));
    exit_code = std::max(exit_code, code);
  }
  return exit_code;
}

}  // namespace

int run_eval(const EvalOptions& options) {
  uint32_t width = 0, height = 0;
  if (std::sscanf(options.size.c_str(), "%ux%u", &width, &height) != 2 || width == 0 || height == 0 || width > 8192 ||
      height > 8192) {
    fmt::print(stderr, "xshade eval: --size wants WxH with each side 1 to 8192, not '{}'\n", options.size);
    return kBadInput;
  }
  LaneSelection selection = options.selection;
  if (selection.lanes.size() == 1 && selection.lanes[0] == "all") selection.lanes.clear();
  auto lanes = resolve_lanes(selection);
  if (!lanes) {
    fmt::print(stderr, "xshade eval: {}\n", lanes.error().to_string());
    return kBadInput;
  }
  // Each file's images are named by its stem in -o DIR.
  std::map<std::string, std::filesystem::path> stems;
  for (const auto& file : options.files) {
    auto [named, added] = stems.emplace(file.stem().string(), file);
    if (!added) {
      fmt::print(stderr, "xshade eval: {} and {} would write images of one name ({}.LANE.exr) in {}; eval them apart\n",
                 named->second.string(), file.string(), file.stem().string(), options.output_dir.string());
      return kBadInput;
    }
  }

  std::vector<FileEval> evals;
  for (const auto& file : options.files) {
    evals.push_back({.file = file});
    compile_for_eval(options, evals.back());
  }
  std::error_code error;
  std::filesystem::create_directories(options.output_dir, error);
  if (options.in_worker) return evaluate_lane_in_worker(options, lanes->front(), evals, width, height);
  if (evals.size() == 1 && !evals.front().module) {  // one file the front end refused: as the compiler says it
    fmt::print(stderr, "{}", evals.front().front_end_output);
    return evals.front().exit_code;
  }
  return run_eval_lanes_in_workers(options, *lanes, evals);
}

Verb add_eval_command(CLI::App& app) {
  auto options = std::make_shared<EvalOptions>();
  CLI::App* eval = app.add_subcommand(
      "eval", "Run fragment shaders as full-screen passes on each lane, write EXR images, compare the lanes");
  eval->add_option("file", options->files,
                   "The hlsl_like sources, each evaluated on its own with these options (with several, each one's "
                   "lines come between `== FILE` and `== FILE: exit CODE`, and the exit code is the worst)")
      ->required()
      ->type_name("FILE");
  eval->add_option("--entry", options->entry, "The fragment function (default: #pragma fragment)")->type_name("NAME");
  eval->add_option("--size", options->size, "Image size")->type_name("WxH")->capture_default_str();
  eval->add_option("--precision", options->precision,
                   "half: round every half/min16float/fixed result to fp16 (gl and vk lanes; vk-hlsl cannot)")
      ->check(CLI::IsMember({"float", "half"}))
      ->capture_default_str();
  add_gl_platform_option(*eval, options->selection.gl_platform);
  eval->add_option("--lane", options->selection.lanes, "gl, vk, vk-hlsl or all (default: all); --lane gl,vk for two")
      ->type_name("LANE")
      ->allow_extra_args(false)
      ->delimiter(',');
  eval->add_option("-I", options->include_dirs, "Search DIR for #include files")
      ->type_name("DIR")
      ->allow_extra_args(false);
  eval->add_option("-D", options->keywords, "Enable KEYWORD")->type_name("KEYWORD")->allow_extra_args(false);
  eval->add_option("-o", options->output_dir, "Folder for the EXR images")->type_name("DIR")->capture_default_str();
  eval->add_option(
          "--seed", options->seed,
          "Fill every constant buffer, texture and read-only buffer from seed N (values in ranges shaders mean, "
          "noise of each texture's declared shape) instead of the defaults and a white texel; a shader that "
          "reads a buffer needs it")
      ->type_name("N");
  eval->add_option(
          "--specialize", options->specializations,
          "Give the [[vk::constant_id]] constant NAME the value VALUE (a specialization constant on the Vulkan "
          "lanes, the constant's value in the GLSL on gl); repeat for more")
      ->type_name("NAME=VALUE")
      ->allow_extra_args(false);
  eval->add_flag("--trace-nonfinite", options->trace_nonfinite,
                 "Render the tracing variant too (gl, vk) and print the source line where each pixel's first NaN, Inf "
                 "(or negative output) was born, with a map of them as <file>.<lane>.origins.png");
  eval->add_flag(
      "--allow-nonfinite", options->allow_non_finite,
      "NaN, Inf and negative output values are expected (a test of a hazard): print their counts, do not fail");
  eval->add_flag("--no-images{false}", options->write_images,
                 "Compare the lanes and print, write no image (for scripts that read the comparisons: the image "
                 "library is then never loaded, a third of a second saved)");
  add_worker_options(*eval, options->workers, "lanes");
  eval->add_flag("--in-worker", options->in_worker)->group("");  // eval's own workers (cli/workers.h)
  return {eval, [options](const std::string&) { return run_eval(*options); }};
}

}  // namespace xshade::cli
