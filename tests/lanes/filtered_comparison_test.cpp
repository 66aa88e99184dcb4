// A comparison sampler that filters linearly (a soft shadow's map): the 2x2 texels a bilinear
// read of the coordinate weights, each compared with the reference, then weighted. gl filters in
// the driver, vk in the shader (lavapipe filters no depth texture; glsl::EmitOptions::
// filter_comparisons), and both must give what the host computes; vk-hlsl cannot, and says so.
#include <algorithm>
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include "harness/render/evaluate.h"
#include "harness/render/shader_program.h"
#include "hlsl_like/compiler.h"
#include "tests/lanes/lane_fixture.h"

namespace xshade::tests {
namespace {

using harness::Lane;

constexpr uint32_t kComparedMapSize = 4;     // texels a side of the depth texture
constexpr uint32_t kComparedImageSize = 16;  // pixels a side: four per texel, none at a texel centre

// Texel (x, y) holds (y * 4 + x + 0.5) / 16. Each pixel reads the map at its own coordinate
// (offset by one texel in the right half, with SampleCmp's offset) with a reference that varies
// from pixel to pixel, so that every mix of lit and shadowed corners occurs.
constexpr const char* kFilteredComparisonSource = R"(
#pragma fragment frag
Texture2D<float> shadow;
SamplerComparisonState compare_sampler;
float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  int2 p = int2(pos.xy);
  float2 st = (float2(p) + 0.5) / 16.0;
  float reference = ((p.x * 7 + p.y * 3) % 16 + 0.25) / 16.0;
  float level_zero = shadow.SampleCmpLevelZero(compare_sampler, st, reference);
  float sampled = p.x < 8 ? shadow.SampleCmp(compare_sampler, st, reference)
                          : shadow.SampleCmp(compare_sampler, st, reference, int2(1, 0));
  return float4(level_zero, sampled, reference, 1);
}
)";

harness::TextureData compared_depth_map() {
  harness::TextureData texture;
  texture.format = harness::TextureFormat::Depth32Float;
  texture.width = texture.height = kComparedMapSize;
  std::vector<std::byte>& bytes = texture.levels.emplace_back(kComparedMapSize * kComparedMapSize * sizeof(float));
  for (uint32_t i = 0; i < kComparedMapSize * kComparedMapSize; ++i) {
    const float depth = (float(i) + 0.5f) / float(kComparedMapSize * kComparedMapSize);
    std::memcpy(bytes.data() + i * sizeof(float), &depth, sizeof depth);
  }
  return texture;
}

// Direct3D's linear comparison filter at texel coordinate (u, v) * size, clamped to the edge.
float filtered_on_host(float u, float v, float reference) {
  const float tu = u * kComparedMapSize - 0.5f, tv = v * kComparedMapSize - 0.5f;
  const float fu = tu - std::floor(tu), fv = tv - std::floor(tv);
  const auto compared = [&](int x, int y) {
    x = std::clamp(x, 0, int(kComparedMapSize) - 1);
    y = std::clamp(y, 0, int(kComparedMapSize) - 1);
    const float depth = (float(y * int(kComparedMapSize) + x) + 0.5f) / float(kComparedMapSize * kComparedMapSize);
    return reference <= depth ? 1.0f : 0.0f;
  };
  const int x0 = int(std::floor(tu)), y0 = int(std::floor(tv));
  const float top = glm::mix(compared(x0, y0), compared(x0 + 1, y0), fu);
  const float bottom = glm::mix(compared(x0, y0 + 1), compared(x0 + 1, y0 + 1), fu);
  return glm::mix(top, bottom, fv);
}

class FilteredComparison : public LaneTest {
 protected:
  Result<harness::FloatImage> run(Lane lane) {
    auto module = hlsl::compile_text("filtered_comparison.hlsl", kFilteredComparisonSource, {});
    EXPECT_TRUE(module->ok());
    auto map = backend(lane).upload_texture(compared_depth_map());
    if (!map) return fail(map.error());
    const harness::SamplerDesc linear{harness::Filter::Linear, harness::AddressMode::ClampToEdge,
                                      harness::CompareOp::LessEqual};
    return harness::evaluate(*module, lane, backend(lane), kComparedImageSize, kComparedImageSize, {},
                             {.filter_comparisons = true}, {{"shadow", harness::TextureSource::texture(*map, linear)}});
  }
};

TEST_F(FilteredComparison, WeighsTheFourNearestComparisonsBilinearlyOnGlAndVk) {
  for (Lane lane : {Lane::Gl, Lane::Vk}) {
    SCOPED_TRACE(harness::lane_name(lane));
    auto image = run(lane);
    ASSERT_TRUE(image) << image.error().to_string();
    int reported = 0;
    for (uint32_t y = 0; y < kComparedImageSize; ++y)
      for (uint32_t x = 0; x < kComparedImageSize; ++x) {
        const float u = (float(x) + 0.5f) / kComparedImageSize, v = (float(y) + 0.5f) / kComparedImageSize;
        const float reference = (float((x * 7 + y * 3) % 16) + 0.25f) / 16.0f;
        const float offset_u = x < 8 ? u : u + 1.0f / kComparedMapSize;
        const glm::vec4 got = image->at(x, y);
        // The weights are multiples of 1/8 (the coordinates fall on eighths of a texel), which
        // the hardware's 8-bit filter weights hold exactly; the rest is one rounding of a sum.
        constexpr float kTolerance = 1e-6f;
        const bool same = std::fabs(got.x - filtered_on_host(u, v, reference)) <= kTolerance &&
                          std::fabs(got.y - filtered_on_host(offset_u, v, reference)) <= kTolerance;
        if (!same && reported++ < 6)
          ADD_FAILURE() << "pixel " << x << "," << y << ": got " << got.x << ", " << got.y << ", expected "
                        << filtered_on_host(u, v, reference) << ", " << filtered_on_host(offset_u, v, reference);
      }
    EXPECT_EQ(reported, 0) << reported << " pixels differ";
  }
}

// glslang's SPIR-V of the source leaves the filtering to the driver, which lavapipe refuses.
TEST_F(FilteredComparison, TheVkHlslLaneRefusesTheLinearComparisonSampler) {
  auto image = run(Lane::VkHlsl);
  ASSERT_FALSE(image);
  EXPECT_NE(image.error().to_string().find("cannot be filtered linearly on this device"), std::string::npos)
      << image.error().to_string();
}

}  // namespace
}  // namespace xshade::tests
