// The tracing variant on the gl and vk lanes: for each kind of site, a shader whose first NaN is
// born there, rendered traced; the record must name that site (its kind, file, line and function,
// and the calls that led to it), the origins' NaN counts must add up to the image's, and the
// traced image must be the plain one bit for bit. Then every fixed scene, traced and plain.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "harness/assets/environment.h"
#include "harness/backend/resource_set.h"
#include "harness/image/image_compare.h"
#include "harness/render/evaluate.h"
#include "harness/render/nonfinite_origins.h"
#include "harness/render/planner.h"
#include "harness/render/scene_renderer.h"
#include "harness/render/variant_compiler.h"
#include "harness/scene/scene.h"
#include "hlsl_like/compiler.h"

namespace xshade::tests {
namespace {

namespace fs = std::filesystem;
using glsl::TraceSite;

// A folder of its own with `files` in it (name, text).
fs::path write_files(const std::string& test, const std::vector<std::pair<std::string, std::string>>& files) {
  const fs::path folder = fs::temp_directory_path() / ("xshade_trace_" + test + "_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  for (const auto& [name, text] : files) std::ofstream(folder / name) << text;
  return folder;
}

struct Traced {
  harness::FloatImage plain;
  harness::FloatImage traced;
  harness::NonfiniteOrigins origins;
};

// `main` (in `folder`) as a full-screen pass, 8x8, plain and traced.
Traced trace_fullscreen(harness::Lane lane, const fs::path& folder, const std::string& main) {
  hlsl::CompileOptions options;
  options.include_dirs = {folder};
  auto module = hlsl::compile_file(folder / main, options);
  EXPECT_TRUE(module->ok()) << module->diagnostics.render_all();
  auto backend = harness::create_backend(lane);
  EXPECT_TRUE(backend) << backend.error().to_string();
  Traced out;
  if (!backend || !module->ok()) return out;
  auto plain = harness::evaluate(*module, lane, **backend, 8, 8);
  EXPECT_TRUE(plain) << plain.error().to_string();
  auto program = harness::FullscreenProgram::create(*module, lane, **backend, {.trace_nonfinite = true});
  EXPECT_TRUE(program) << program.error().to_string();
  if (!plain || !program) return out;
  harness::FloatImage record;
  auto traced = program->run(**backend, 8, 8, {}, &record);
  EXPECT_TRUE(traced) << traced.error().to_string();
  if (!traced) return out;
  harness::CompiledVariant variant;
  variant.program.name = main;
  variant.trace = program->trace();
  auto origins = harness::find_nonfinite_origins(*traced, {"eval", record}, {variant});
  EXPECT_TRUE(origins) << origins.error().to_string();
  EXPECT_EQ((*backend)->take_driver_messages(), std::vector<std::string>{});
  out.plain = std::move(*plain);
  out.traced = std::move(*traced);
  if (origins) out.origins = std::move(*origins);
  return out;
}

// What every traced render must show: the same bits as the plain render, and origins whose NaN,
// Inf and negative counts are the image's.
void expect_accounted(const Traced& traced) {
  EXPECT_TRUE(harness::bitwise_equal(traced.plain, traced.traced)) << "the tracing variant changed a value";
  const harness::NonFiniteCount counted = harness::count_non_finite(traced.plain);
  size_t nan = 0, inf = 0, negative = 0;
  for (const harness::NonfiniteOrigin& origin : traced.origins.origins) {
    nan += origin.nan;
    inf += origin.inf;
    negative += origin.negative;
  }
  EXPECT_EQ(nan, counted.nan);
  EXPECT_EQ(inf, counted.inf);
  EXPECT_EQ(negative, counted.negative);
  EXPECT_EQ(traced.origins.unattributed_pixels, 0u);
  EXPECT_GT(counted.nan, 0u) << "the shader was meant to make NaN";
}

// The one origin the shader has; its site's kind, line and function.
void expect_single_origin(const Traced& traced, TraceSite::Kind kind, const std::string& file, uint32_t line,
                          const std::string& function) {
  ASSERT_EQ(traced.origins.origins.size(), 1u) << harness::describe_origins(traced.origins);
  const harness::NonfiniteOrigin& origin = traced.origins.origins[0];
  EXPECT_EQ(origin.site.kind, kind) << glsl::describe_site(origin.site);
  EXPECT_EQ(fs::path(origin.site.file).filename().string(), file);
  EXPECT_EQ(origin.site.line, line);
  EXPECT_EQ(origin.site.function, function);
  EXPECT_FALSE(origin.site.source_line.empty());
}

class NonfiniteTrace : public ::testing::TestWithParam<harness::Lane> {};

// Column 0 of every row: 0/0. The other columns stay finite.
constexpr const char* kZeroOverZero = "float zero = uv.x < 0.125 ? 0.0 : 1.0;\n";

TEST_P(NonfiniteTrace, AnAssignmentIsNamed) {
  const fs::path folder =
      write_files("assignment", {{"main.hlsl", std::string("#pragma fragment frag\n"
                                                           "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n  ") +
                                                   kZeroOverZero +
                                                   "  float x = 1.0;\n"
                                                   "  x = zero / zero;\n"  // line 5
                                                   "  return float4(x, 0.5, 0.5, 1.0);\n}\n"}});
  const Traced traced = trace_fullscreen(GetParam(), folder, "main.hlsl");
  expect_accounted(traced);
  expect_single_origin(traced, TraceSite::Kind::Assignment, "main.hlsl", 5, "frag");
  EXPECT_EQ(traced.origins.origins[0].pixels, 8u);  // column 0
  EXPECT_EQ(traced.origins.origins[0].first_x, 0u);
}

TEST_P(NonfiniteTrace, ACompoundAssignmentIsNamed) {
  const fs::path folder =
      write_files("compound", {{"main.hlsl", std::string("#pragma fragment frag\n"
                                                         "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n  ") +
                                                 kZeroOverZero +
                                                 "  float x = zero;\n"
                                                 "  x /= zero;\n"  // line 5
                                                 "  return float4(0.5, x, 0.5, 1.0);\n}\n"}});
  const Traced traced = trace_fullscreen(GetParam(), folder, "main.hlsl");
  expect_accounted(traced);
  expect_single_origin(traced, TraceSite::Kind::CompoundAssignment, "main.hlsl", 5, "frag");
}

TEST_P(NonfiniteTrace, AReturnValueIsNamedWithTheCallThatMadeIt) {
  const fs::path folder = write_files(
      "return",
      {{"main.hlsl", std::string("#pragma fragment frag\n"
                                 "float ratio(float a, float b) {\n"
                                 "  return a / b;\n"  // line 3
                                 "}\n"
                                 "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n  ") +
                         kZeroOverZero + "  return float4(ratio(zero, zero), 0.5, 0.5, 1.0);\n}\n"}});  // line 7
  const Traced traced = trace_fullscreen(GetParam(), folder, "main.hlsl");
  expect_accounted(traced);
  expect_single_origin(traced, TraceSite::Kind::Return, "main.hlsl", 3, "ratio");
  const auto& calls = traced.origins.origins[0].calls;
  ASSERT_EQ(calls.size(), 1u);
  EXPECT_EQ(calls[0].callee, "ratio");
  EXPECT_EQ(calls[0].caller, "frag");
  EXPECT_EQ(calls[0].line, 7u);
}

TEST_P(NonfiniteTrace, ALibraryCallFromAnIncludeIsNamedInTheIncludeWithItsCallers) {
  const fs::path folder = write_files("include", {{"lib.hlsl",
                                                   "float soft_root(float x) {\n"
                                                   "  float r = sqrt(x);\n"  // line 2: the intrinsic's result
                                                   "  return r;\n"
                                                   "}\n"
                                                   "float shade(float x) { return soft_root(x) * 2.0; }\n"},
                                                  {"main.hlsl",
                                                   "#include \"lib.hlsl\"\n"
                                                   "#pragma fragment frag\n"
                                                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                                                   "  float x = uv.y < 0.25 ? -1.0 : 1.0;\n"
                                                   "  return float4(0.5, 0.5, shade(x), 1.0);\n}\n"}});  // line 5
  const Traced traced = trace_fullscreen(GetParam(), folder, "main.hlsl");
  expect_accounted(traced);
  expect_single_origin(traced, TraceSite::Kind::Call, "lib.hlsl", 2, "soft_root");
  const harness::NonfiniteOrigin& origin = traced.origins.origins[0];
  EXPECT_EQ(origin.site.what, "sqrt");
  EXPECT_EQ(origin.pixels, 16u);       // rows 0 and 1
  ASSERT_EQ(origin.calls.size(), 2u);  // soft_root from shade, shade from frag
  EXPECT_EQ(origin.calls[0].caller, "shade");
  EXPECT_EQ(fs::path(origin.calls[0].file).filename().string(), "lib.hlsl");
  EXPECT_EQ(origin.calls[1].caller, "frag");
  EXPECT_EQ(origin.calls[1].line, 5u);
}

TEST_P(NonfiniteTrace, ANegativeColourIsNamedAtTheOutput) {
  const fs::path folder = write_files("negative", {{"main.hlsl",
                                                    "#pragma fragment frag\n"
                                                    "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                                                    "  return float4(uv.x - 0.5, 0.5, 0.5, 1.0);\n}\n"}});
  const Traced traced = trace_fullscreen(GetParam(), folder, "main.hlsl");
  EXPECT_TRUE(harness::bitwise_equal(traced.plain, traced.traced));
  ASSERT_EQ(traced.origins.origins.size(), 1u) << harness::describe_origins(traced.origins);
  EXPECT_EQ(traced.origins.origins[0].site.kind, TraceSite::Kind::NegativeOutput);
  EXPECT_EQ(traced.origins.origins[0].negative, harness::count_non_finite(traced.plain).negative);
}

// A value born in the vertex stage arrives at the fragment stage non-finite: the fragment input
// is named, with its semantic (the vertex stage itself is not traced).
TEST_P(NonfiniteTrace, AValueBornInTheVertexStageIsNamedAsItArrives) {
  const harness::Lane lane = GetParam();
  const char* source =
      "#pragma vertex vert\n#pragma fragment frag\n"
      "struct V { float4 position : SV_Position; float weight : TEXCOORD3; };\n"
      "float _Zero = 0.0;\n"
      "V vert(float3 position : POSITION) {\n"
      "  V o; o.position = float4(position, 1.0); o.weight = _Zero / _Zero; return o;\n}\n"
      "float4 frag(V input) : SV_Target { return float4(input.weight, 0.5, 0.5, 1.0); }\n";  // line 8
  auto module = hlsl::compile_text("vertex.hlsl", source, {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  glsl::NonfiniteTrace trace;
  auto desc = harness::program_for_lane(*module, lane, {.trace_nonfinite = true}, &trace);
  ASSERT_TRUE(desc) << desc.error().to_string();
  auto backend = harness::create_backend(lane);
  ASSERT_TRUE(backend) << backend.error().to_string();
  harness::ResourceSet resources(**backend);
  auto target = resources.create_target({4, 4, false, /*second_color=*/true});
  auto program = resources.create_program(*desc);
  harness::MeshData triangle;  // covers the whole target
  for (glm::vec3 p : {glm::vec3(-1, -1, 0), glm::vec3(3, -1, 0), glm::vec3(-1, 3, 0)}) {
    harness::Vertex vertex;
    vertex.position = p;
    triangle.vertices.push_back(vertex);
  }
  triangle.indices = {0, 1, 2};
  auto mesh = resources.upload_mesh(triangle);
  ASSERT_TRUE(target && program && mesh) << (program ? "" : program.error().to_string());
  std::vector<std::byte> zero(desc->layout.uniform_blocks.at(0).size, std::byte{0});
  ASSERT_TRUE((*backend)->render(
      {*target, glm::vec4(0.0f), 1.0f, {{*program, *mesh, {{desc->layout.uniform_blocks[0].name, zero}}, {}, {}}}}));
  auto image = (*backend)->read_color(*target);
  auto record = (*backend)->read_second_color(*target);
  ASSERT_TRUE(image && record);
  harness::CompiledVariant variant;
  variant.trace = trace;
  auto origins = harness::find_nonfinite_origins(*image, {"scene", *record}, {variant});
  ASSERT_TRUE(origins) << origins.error().to_string();
  ASSERT_EQ(origins->origins.size(), 1u) << harness::describe_origins(*origins);
  const harness::NonfiniteOrigin& origin = origins->origins[0];
  EXPECT_EQ(origin.site.kind, TraceSite::Kind::Input);
  EXPECT_EQ(origin.site.what, "TEXCOORD3");
  EXPECT_EQ(origin.pixels, 16u);
  EXPECT_EQ(origin.nan, harness::count_non_finite(*image).nan);
}

INSTANTIATE_TEST_SUITE_P(Lanes, NonfiniteTrace, ::testing::Values(harness::Lane::Gl, harness::Lane::Vk),
                         [](const auto& lane) { return std::string(harness::lane_name(lane.param)); });

// Every fixed scene, plain and traced, on gl and vk: the same bits. The traced copy's
// instructions must never be shared with the plain copy's (glsl/emit_trace.cpp says why).
class TracedFixedScene : public ::testing::TestWithParam<harness::Lane> {};

TEST_P(TracedFixedScene, EveryFixedSceneRendersTheSameBitsTraced) {
  const harness::Lane lane = GetParam();
  auto backend = harness::create_backend(lane);
  ASSERT_TRUE(backend) << backend.error().to_string();
  harness::VariantCompiler compiler(harness::ShaderSearchPath(fs::path(XSHADE_SHADERS_DIR)), nullptr);
  size_t scenes = 0;
  for (const auto& entry : fs::directory_iterator(XSHADE_SCENES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().filename().string());
    auto scene = harness::load_scene(entry.path());
    ASSERT_TRUE(scene) << scene.error().to_string();
    auto plan = harness::plan_scene(*scene, compiler.shaders());
    ASSERT_TRUE(plan) << plan.error().to_string();
    auto environment = harness::build_environment(scene->environment);
    ASSERT_TRUE(environment);
    auto plain_variants = compiler.compile_plan(*plan, lane, false);
    auto traced_variants = compiler.compile_plan(*plan, lane, false, /*trace_nonfinite=*/true);
    ASSERT_TRUE(plain_variants && traced_variants);
    auto plain = harness::render_scene(**backend, *scene, *plan, *plain_variants, *environment);
    auto traced =
        harness::render_scene(**backend, *scene, *plan, *traced_variants, *environment, {.trace_nonfinite = true});
    ASSERT_TRUE(plain && traced) << (traced ? "" : traced.error().to_string());
    EXPECT_TRUE(harness::bitwise_equal(plain->image, traced->image));
    EXPECT_EQ(traced->traces.size(), plan->passes.size());
    ++scenes;
  }
  EXPECT_GE(scenes, 10u);
  EXPECT_EQ((*backend)->take_driver_messages(), std::vector<std::string>{});
}

// SHADERS.md hazard 8 on the fixed material grid with the seed's forms, no guards, in fp16: the
// smoothest row's D overflows and meets a zero. The tracer names D's division as where it began,
// and the NaN it accounts for are the image's.
TEST_P(TracedFixedScene, TheSeedsDIsWhereTheMaterialGridsFp16NanIsBorn) {
  const harness::Lane lane = GetParam();
  auto backend = harness::create_backend(lane);
  ASSERT_TRUE(backend) << backend.error().to_string();
  harness::VariantCompiler compiler(harness::ShaderSearchPath(fs::path(XSHADE_SHADERS_DIR)), nullptr);
  auto scene = harness::load_scene(fs::path(XSHADE_SCENES_DIR) / "material_grid.toml");
  ASSERT_TRUE(scene) << scene.error().to_string();
  auto plan = harness::plan_scene(*scene, compiler.shaders());
  auto environment = harness::build_environment(scene->environment);
  ASSERT_TRUE(plan && environment);
  auto variants = compiler.compile_plan(*plan, lane, /*half_emulation=*/true, /*trace_nonfinite=*/true);
  ASSERT_TRUE(variants) << variants.error().to_string();
  auto traced = harness::render_scene(**backend, *scene, *plan, *variants, *environment, {.trace_nonfinite = true});
  ASSERT_TRUE(traced) << traced.error().to_string();
  ASSERT_EQ(traced->traces.size(), 1u);
  auto origins = harness::find_nonfinite_origins(traced->image, traced->traces[0], *variants);
  ASSERT_TRUE(origins) << origins.error().to_string();
  const harness::NonFiniteCount counted = harness::count_non_finite(traced->image);
  ASSERT_GT(counted.nan, 0u) << "the seed's fp16 D no longer overflows on the smoothest row";
  ASSERT_FALSE(origins->origins.empty());
  size_t nan = 0;
  for (const harness::NonfiniteOrigin& origin : origins->origins) {
    nan += origin.nan;
    EXPECT_EQ(origin.site.function, "D_GGX_seed") << harness::describe_origins(*origins);
    EXPECT_EQ(origin.site.kind, TraceSite::Kind::Return);
    EXPECT_EQ(fs::path(origin.site.file).filename().string(), "brdf.hlsl");
    EXPECT_NE(origin.site.source_line.find("a2 / (kPi * d * d)"), std::string::npos) << origin.site.source_line;
  }
  EXPECT_EQ(nan, counted.nan);
}

INSTANTIATE_TEST_SUITE_P(Lanes, TracedFixedScene, ::testing::Values(harness::Lane::Gl, harness::Lane::Vk),
                         [](const auto& lane) { return std::string(harness::lane_name(lane.param)); });

}  // namespace
}  // namespace xshade::tests
