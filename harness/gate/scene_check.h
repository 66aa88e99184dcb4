// Checking one scene: plan it, compile what it needs, render it on each lane (twice, to prove the
// lane deterministic), and hold each lane's image against its golden and against the other
// lanes. Writes the images a report shows into the report folder and returns the verdicts.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "harness/gate/golden_store.h"
#include "harness/render/lanes.h"
#include "harness/gate/run_results.h"
#include "harness/scene/scene.h"
#include "harness/render/variant_compiler.h"

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
};

// A checked scene: the verdicts, and the images each lane rendered (for blessing).
struct CheckedScene {
  SceneResult result;
  std::optional<Scene> scene;
  std::map<Lane, FloatImage> images;
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

// Why a checked scene must not become a golden: a lane that did not pass (with its verdict) or
// two lanes that disagree (Fail); nullopt when it may.
struct BlessRefusal {
  Verdict verdict = Verdict::Fail;
  std::string message;
};
std::optional<BlessRefusal> bless_refusal(const SceneResult& result);

class SceneChecker {
 public:
  using Progress = std::function<void(const std::string& line)>;

  SceneChecker(VariantCompiler& compiler, SceneCheckOptions options, Progress progress);

  // `lanes`: the lanes asked for; a scene runs those of them it lists.
  CheckedScene check(const std::filesystem::path& scene_file, const std::vector<Lane>& lanes);

 private:
  void check_lane(const Scene& scene, const struct Plan& plan, const struct Environment& environment, Lane lane,
                  CheckedScene& checked);
  void compare_lanes(const Scene& scene, CheckedScene& checked);
  std::string write_image(const FloatImage& image, const std::string& scene, const std::string& file, bool exr = false);

  VariantCompiler& compiler_;
  SceneCheckOptions options_;
  Progress progress_;
};

}  // namespace xshade::harness
