// Checking one scene: plan it, compile what it needs, render it on each lane (twice, to prove the
// lane deterministic), and hold each lane's image against its golden and against the other
// lanes. Writes the images a report shows into the report folder and returns the verdicts. The
// three steps are apart so that each lane can be rendered in a process of its own
// (harness/gate/lane_workers.h).
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "harness/gate/golden_store.h"
#include "harness/gate/run_results.h"
#include "harness/render/environment_cache.h"
#include "harness/render/lanes.h"
#include "harness/render/variant_compiler.h"
#include "harness/scene/scene.h"

namespace xshade::harness {

struct SceneCheckOptions {
  std::filesystem::path report_dir;
  const GoldenStore* goldens = nullptr;  // null: no golden layer (e.g. while blessing)
  BackendOptions backend;                // how each lane's backend is made
  bool pass_images = false;              // also write each pass's output
  bool plan_only = false;                // plan, render nothing
  // Every half result rounded to fp16 on the GLSL lanes (vk-hlsl cannot, and is skipped). The
  // goldens are fp32 renders, so the golden layer is skipped; finiteness, determinism and the
  // lanes against each other still gate.
  bool half_emulation = false;
  // Where environments come from, built once per process (and kept between runs with a folder);
  // null: each scene builds its own.
  EnvironmentCache* environments = nullptr;
  // Render every lane again with the tracing variant (gl and vk) and report where its non-finite
  // values were born; without it, only a lane whose image has NaN, Inf or negative values is.
  bool trace_nonfinite = false;
};

struct Plan;
struct Environment;

// A checked scene: the verdicts, and the images each lane rendered (for blessing).
struct CheckedScene {
  SceneResult result;
  std::optional<Scene> scene;
  std::map<Lane, FloatImage> images;
  // What SceneChecker::prepare found: the plan and the lanes to render (those asked for that the
  // scene lists; none when the result is already decided).
  std::shared_ptr<const Plan> plan;
  std::vector<Lane> lanes;
  std::shared_ptr<const Environment> environment;  // made by the first lane rendered here
  // The shader sources and includes read: by the plan (prepare), and by its lanes' compiles
  // (VariantCompiler::take_files_read), as check_in_workers collects them from its workers.
  std::set<std::filesystem::path> files_read;
};

// The gate's decisions, apart from rendering so that each can be fed what must fail it.

// Two renders of one scene on one driver must be bit-identical.
LayerResult determinism_layer(const FloatImage& first, const FloatImage& second);

// Every lane after the first (in lane order) against the first lane's image.
struct LanePairComparison {
  Lane first;
  Lane second;
  Comparison comparison;
};
std::vector<LanePairComparison> compare_lane_images(const std::map<Lane, FloatImage>& images,
                                                    const CompareSettings& settings);

// Writes a heat map as FILE of the scene's report folder; its path in the report, or empty.
using HeatMapWriter = std::function<std::string(const FloatImage& heat_map, const std::string& file)>;
// compare_lane_images as the report's pairs: each pair's verdict and metrics, its heat map
// written (none for bit-identical images), and `said` told of each with its deciding detail.
std::vector<CrossLaneResult> cross_lane_results(
    const std::map<Lane, FloatImage>& images, const CompareSettings& settings, const HeatMapWriter& write,
    const std::function<void(const CrossLaneResult&, const std::string&)>& said = {});

// Why a checked scene must not become a golden: a lane that did not pass (with its verdict) or
// two lanes that disagree (Fail); nullopt when it may.
struct BlessRefusal {
  Verdict verdict = Verdict::Fail;
  std::string message;
};
std::optional<BlessRefusal> bless_refusal(const SceneResult& result);

// "toon_ramp on gl: fail - per_pixel: ...": a lane's line in a run's progress.
std::string lane_progress_line(const std::string& scene, const LaneResult& lane);

class SceneChecker {
 public:
  using Progress = std::function<void(const std::string& line)>;
  // Where a lane's check is: "while compiling", "in pass bokeh (render 1 of 2)".
  using Status = std::function<void(const std::string& where)>;

  SceneChecker(VariantCompiler& compiler, SceneCheckOptions options, Progress progress);

  // Loads and plans the scene; `lanes` are the lanes asked for, of which the scene runs those it
  // lists (checked.lanes). A scene that does not load or plan, lists none of them, or is only to
  // be planned, is decided here and has no lanes.
  CheckedScene prepare(const std::filesystem::path& scene_file, const std::vector<Lane>& lanes);
  // Compiles, renders and checks one lane of a prepared scene in this process: its result is
  // appended to checked.result.lanes and its image to checked.images.
  void check_lane(Lane lane, CheckedScene& checked, const Status& status = {});
  // Each lane's progress line, the lanes against each other, and the scene's verdict from its
  // lanes and theirs.
  void conclude(CheckedScene& checked);

  VariantCompiler& compiler() const { return compiler_; }

 private:
  // check_lane's steps, in its order.
  Result<void> build_scene_environment(CheckedScene& checked);
  void write_lane_images(const Scene& scene, const FloatImage& image, LaneResult& result);
  void add_reference_layers(const Scene& scene, const FloatImage& image, LaneResult& result);
  void compare_lanes(const Scene& scene, CheckedScene& checked);
  // The lane rendered again with the tracing variant, into result.trace; `plain` is its image.
  void trace_lane(Lane lane, const Scene& scene, const Plan& plan, const Environment& environment, Backend& backend,
                  const FloatImage& plain, LaneResult& result);
  // REPORT/SCENE/FILE, written or copied; its path relative to the report, or empty (said on
  // the progress line) when it could not be.
  std::string write_image(const FloatImage& image, const std::string& scene, const std::string& file, bool exr = false);
  std::string copy_file(const std::filesystem::path& from, const std::string& scene, const std::string& file);

  VariantCompiler& compiler_;
  SceneCheckOptions options_;
  Progress progress_;
};

}  // namespace xshade::harness
