// xshade eval: one fragment shader as a full-screen pass on each lane, the images written as
// EXR, and how far the lanes agree.
#include <fmt/core.h>

#include <algorithm>
#include <map>

#include "cli/commands.h"
#include "base/file_io.h"
#include "base/subprocess.h"
#include "cli/lane_selection.h"
#include "cli/workers.h"
#include "harness/render/evaluate.h"
#include "harness/render/nonfinite_origins.h"
#include "harness/image/image_compare.h"
#include "harness/image/image_io.h"

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
        fmt::print("{} vs {}: max difference {:g} at ({}, {}) channel {}: {:g} vs {:g}\n",
                   harness::lane_name(first_lane), harness::lane_name(lane), difference.max, difference.x,
                   difference.y, "rgba"[difference.channel], pixel[int(difference.channel)],
                   other[int(difference.channel)]);
    }
}

// --trace-nonfinite: the tracing variant on the same inputs, its image held to the plain one, and
// where its non-finite pixels were born.
void print_traced(const EvalOptions& options, const hlsl::Module& module, harness::Lane lane, harness::Backend& backend,
                  const harness::FloatImage& plain, uint32_t width, uint32_t height) {
  const std::string name(harness::lane_name(lane));
  harness::ProgramOptions traced_options{.half_emulation = options.precision == "half", .trace_nonfinite = true};
  auto program = harness::FullscreenProgram::create(module, lane, backend, traced_options);
  if (!program) {
    fmt::print("{}: not traced: {}\n", name, program.error().message);
    return;
  }
  harness::FloatImage record;
  auto traced = options.seed ? program->run_seeded(backend, width, height, *options.seed, &record)
                             : program->run(backend, width, height, {}, {}, &record);
  (void)backend.destroy(program->handle());  // made here, destroyed once
  if (!traced) {
    fmt::print("{}: the traced render failed: {}\n", name, traced.error().to_string());
    return;
  }
  fmt::print("{}: traced image {}\n", name,
             harness::bitwise_equal(*traced, plain) ? "bit-identical to the plain one"
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
  const auto map = options.output_dir / (options.file.stem().string() + "." + name + ".origins.png");
  if (auto written = harness::write_png(origins->map, map); written) fmt::print("{}: origins map {}\n", name, map.string());
}

// Where eval writes a lane's image, and where that lane's worker hands it over first (beside it,
// hidden, removed once read).
std::filesystem::path exr_path(const EvalOptions& options, const std::string& lane) {
  return options.output_dir / (options.file.stem().string() + "." + lane + ".exr");
}
std::filesystem::path handover_path(const EvalOptions& options, const std::string& lane) {
  return options.output_dir / ("." + options.file.stem().string() + "." + lane + ".f32");
}

// The options of `options` for one lane's worker: the same eval, of that lane alone.
std::vector<std::string> worker_command(const EvalOptions& options, harness::Lane lane) {
  std::vector<std::string> command = {this_program(), "eval", options.file.string(), "--in-worker",
                                      "--lane", std::string(harness::lane_name(lane)), "--size", options.size,
                                      "--precision", options.precision, "--gl-platform", options.selection.gl_platform,
                                      "-o", options.output_dir.string()};
  if (!options.entry.empty()) command.insert(command.end(), {"--entry", options.entry});
  for (const auto& folder : options.include_dirs) command.insert(command.end(), {"-I", folder.string()});
  for (const std::string& keyword : options.keywords) command.insert(command.end(), {"-D", keyword});
  if (options.seed) command.insert(command.end(), {"--seed", std::to_string(*options.seed)});
  if (options.allow_non_finite) command.push_back("--allow-nonfinite");
  if (options.trace_nonfinite) command.push_back("--trace-nonfinite");
  if (!options.write_images) command.push_back("--no-images");
  return command;
}

// Each lane in a worker of its own (cli/workers.h): a lane whose driver crashes or whose shader
// hangs is reported as that lane's and the others still run. Each worker writes its EXR and its
// lines; this process prints them in lane order and compares the images.
int run_eval_lanes_in_workers(const EvalOptions& options, const std::vector<harness::Lane>& lanes) {
  const unsigned jobs = worker_jobs(options.workers);
  const double timeout = worker_timeout(options.workers);
  const std::vector<std::string> environment = worker_environment(jobs);
  std::vector<std::optional<ChildProcess>> workers(lanes.size());
  int exit_code = kPass;
  std::map<harness::Lane, harness::FloatImage> images;
  size_t next_to_start = 0, next_to_report = 0;
  while (next_to_report < lanes.size()) {
    size_t running = 0;
    for (size_t i = next_to_report; i < next_to_start; ++i) running += workers[i] && !workers[i]->finished();
    while (running < jobs && next_to_start < lanes.size()) {
      std::error_code ignored;  // what an earlier eval that was stopped left
      std::filesystem::remove(handover_path(options, std::string(harness::lane_name(lanes[next_to_start]))), ignored);
      auto worker = ChildProcess::start(worker_command(options, lanes[next_to_start]), environment,
                                        std::chrono::duration_cast<ChildProcess::Clock::duration>(
                                            std::chrono::duration<double>(timeout)));
      if (worker) {
        workers[next_to_start] = std::move(*worker);
        ++running;
      } else {
        fmt::print("{}: cannot start a worker: {}\n", harness::lane_name(lanes[next_to_start]), worker.error().to_string());
        exit_code = std::max<int>(exit_code, kBackendError);
      }
      ++next_to_start;
    }
    // Reported in lane order, each once its worker has ended.
    while (next_to_report < next_to_start && (!workers[next_to_report] || workers[next_to_report]->poll())) {
      const harness::Lane lane = lanes[next_to_report];
      if (std::optional<ChildProcess>& worker = workers[next_to_report]) {
        fmt::print("{}", worker->output());
        const ChildExit& exit = worker->exit_status();
        const std::string name(harness::lane_name(lane));
        if (exit.timed_out) {
          fmt::print("{}: timeout after {:g} s; a slower shader needs --timeout SECONDS\n", name, timeout);
          exit_code = std::max<int>(exit_code, kTestFailed);
        } else if (exit.signal) {
          fmt::print("{}: worker died: {}\n", name, describe_signal(exit.signal));
          exit_code = std::max<int>(exit_code, kBackendError);
        } else {
          exit_code = std::max(exit_code, exit.code);
          const auto handover = handover_path(options, name);
          const std::optional<std::string> bytes = read_file(handover);
          std::error_code ignored;
          std::filesystem::remove(handover, ignored);
          std::optional<harness::FloatImage> image = bytes ? harness::float_image_from(*bytes) : std::nullopt;
          if (image && options.write_images) {
            if (auto written = harness::write_exr(*image, exr_path(options, name)); !written) {
              fmt::print(stderr, "xshade eval: {}\n", written.error().to_string());
              exit_code = std::max<int>(exit_code, kBackendError);
            }
          }
          if (exit.code != kBackendError && image) images.emplace(lane, std::move(*image));
        }
      }
      ++next_to_report;
    }
    std::vector<ChildProcess*> waiting;
    for (size_t i = next_to_report; i < next_to_start; ++i)
      if (workers[i] && !workers[i]->finished()) waiting.push_back(&*workers[i]);
    if (!waiting.empty()) wait_for_any(waiting, std::chrono::milliseconds(1000));
    for (ChildProcess* worker : waiting) worker->poll();
  }
  print_lane_differences(images);
  return exit_code;
}

}  // namespace

int run_eval(const EvalOptions& options) {
  uint32_t width = 0, height = 0;
  if (std::sscanf(options.size.c_str(), "%ux%u", &width, &height) != 2 || width == 0 || height == 0 ||
      width > 8192 || height > 8192) {
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

  hlsl::CompileOptions front_end;
  front_end.include_dirs = include_folders(options.include_dirs);
  front_end.keywords = options.keywords;
  front_end.fragment_only_entry = options.entry;
  if (options.precision == "half") front_end.defines.push_back({harness::kHalfEmulationMacro, "1"});
  auto module = hlsl::compile_file(options.file, front_end);
  if (!module->diagnostics.diagnostics().empty()) fmt::print(stderr, "{}", module->diagnostics.render_all());
  if (!module->ok()) return kBadInput;
  if (!module->entry_points.fragment) {
    fmt::print(stderr, "xshade eval: {} has no fragment entry point; name one with --entry or #pragma fragment\n",
               options.file.string());
    return kBadInput;
  }

  // A shader that writes only SV_Depth leaves the colour undefined: nothing to compare.
  const auto& outputs = module->reflection.fragment_outputs;
  if (std::none_of(outputs.begin(), outputs.end(), [](const hlsl::StageVariable& output) {
        return output.semantic.starts_with("SV_Target");
      })) {
    fmt::print(stderr, "xshade eval: {} writes no colour (SV_Target); eval renders and compares colour only\n",
               options.file.string());
    return kBadInput;
  }

  std::error_code error;
  std::filesystem::create_directories(options.output_dir, error);
  if (!options.in_worker) return run_eval_lanes_in_workers(options, *lanes);
  int exit_code = kPass;
  std::map<harness::Lane, harness::FloatImage> images;
  for (harness::Lane lane : *lanes) {
    const std::string name(harness::lane_name(lane));
    auto backend = harness::create_backend(lane, backend_options(selection));
    if (!backend) {
      fmt::print("{}: unavailable: {}\n", name, backend.error().to_string());
      exit_code = kBackendError;
      continue;
    }
    const harness::ProgramOptions program_options{.half_emulation = options.precision == "half"};
    auto image = options.seed ? [&]() -> Result<harness::FloatImage> {
      auto program = harness::FullscreenProgram::create(*module, lane, **backend, program_options);
      if (!program) return fail(program.error());
      return program->run_seeded(**backend, width, height, *options.seed);
    }()
                              : harness::evaluate(*module, lane, **backend, width, height, {}, program_options);
    if (image && options.trace_nonfinite) print_traced(options, *module, lane, **backend, *image, width, height);
    if (!image) {
      fmt::print("{}: failed: {}\n", name, image.error().to_string());
      exit_code = kBackendError;
      continue;
    }
    for (const std::string& message : (*backend)->take_driver_messages()) fmt::print("{}: driver message: {}\n", name, message);
    // The image goes to the process that started this worker, which writes the EXR: a worker then
    // never loads the image library (harness/image/image_codec.h), a third of a second a lane.
    if (auto handed = write_file_atomically(handover_path(options, name), harness::float_image_bytes(*image)); !handed) {
      fmt::print(stderr, "xshade eval: {}\n", handed.error().to_string());
      exit_code = kBackendError;
    } else if (options.write_images) {
      fmt::print("{}: {}\n", name, exr_path(options, name).string());
    }
    // A NaN, an Inf or a negative colour is a failure unless the shader is a test of such a hazard.
    if (const harness::NonFiniteCount bad = harness::count_non_finite(*image); bad.total()) {
      fmt::print("{}: {}{}\n", name, harness::describe_non_finite(bad),
                 options.allow_non_finite ? " (allowed by --allow-nonfinite)" : "");
      if (!options.allow_non_finite) exit_code = std::max<int>(exit_code, kTestFailed);
    }
    images.emplace(lane, std::move(*image));
  }
  print_lane_differences(images);
  return exit_code;
}

}  // namespace xshade::cli
