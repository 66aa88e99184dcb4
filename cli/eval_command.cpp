// xshade eval: one fragment shader as a full-screen pass on each lane, the images written as
// EXR, and how far the lanes agree.
#include <fmt/core.h>

#include <algorithm>
#include <map>

#include "cli/commands.h"
#include "cli/lane_selection.h"
#include "harness/render/evaluate.h"
#include "harness/image/image_compare.h"
#include "harness/image/image_io.h"

namespace xshade::cli {

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
    if (!image) {
      fmt::print("{}: failed: {}\n", name, image.error().to_string());
      exit_code = kBackendError;
      continue;
    }
    for (const std::string& message : (*backend)->take_driver_messages()) fmt::print("{}: driver message: {}\n", name, message);
    const auto path = options.output_dir / (options.file.stem().string() + "." + name + ".exr");
    if (auto written = harness::write_exr(*image, path); !written) {
      fmt::print(stderr, "xshade eval: {}\n", written.error().to_string());
      exit_code = kBackendError;
    } else {
      fmt::print("{}: {}\n", name, path.string());
    }
    // A NaN, an Inf or a negative colour is a failure unless the shader is a test of such a hazard.
    if (const harness::NonFiniteCount bad = harness::count_non_finite(*image); bad.total()) {
      fmt::print("{}: {}{}\n", name, harness::describe_non_finite(bad),
                 options.allow_non_finite ? " (allowed by --allow-nonfinite)" : "");
      if (!options.allow_non_finite) exit_code = std::max<int>(exit_code, kTestFailed);
    }
    images.emplace(lane, std::move(*image));
  }
  if (images.size() > 1) {
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
  return exit_code;
}

}  // namespace xshade::cli
