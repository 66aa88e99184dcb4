// A uniform block and a sampled texture give the same result on every lane, and the right one.
#include <cstring>
#include <random>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "tests/lanes/lane_fixture.h"

namespace xshade::tests {
namespace {

using harness::Lane;

// Matches `Params` in tests/shaders/uniforms_texture.*.frag (std140).
struct Params {
  glm::mat4 transform;
  glm::vec4 tiling;
  glm::vec4 bias;
  float gain;
  float padding[3];
};
static_assert(sizeof(Params) == 112);

constexpr uint32_t kTextureSize = 16;

class UniformsAndTextures : public LaneTest {
 protected:
  void SetUp() override {
    LaneTest::SetUp();
    std::mt19937 random(7);
    std::uniform_real_distribution<float> value(-2.0f, 2.0f);
    texture_.format = harness::TextureFormat::Rgba32Float;
    texture_.width = texture_.height = kTextureSize;
    texels_.resize(kTextureSize * kTextureSize);
    for (glm::vec4& texel : texels_) texel = {value(random), value(random), value(random), value(random)};
    auto& level = texture_.levels.emplace_back(texels_.size() * sizeof(glm::vec4));
    std::memcpy(level.data(), texels_.data(), level.size());

    params_.transform = glm::rotate(glm::scale(glm::mat4(1.0f), glm::vec3(0.5f, 2.0f, 1.5f)), 0.7f,
                                    glm::vec3(0.3f, 0.8f, 0.1f));
    params_.transform[3] = glm::vec4(0.25f, -0.5f, 0.125f, 1.0f);
    params_.bias = {0.1f, 0.2f, -0.3f, 0.4f};
    params_.gain = 1.75f;
  }

  // Runs tests/shaders/<shader>.*.frag, which reads `values` and maybe `Params`.
  harness::FloatImage render(Lane lane, const std::string& shader, uint32_t width, uint32_t height,
                             glm::vec4 tiling, harness::SamplerDesc sampler) {
    harness::Backend& lane_backend = backend(lane);
    const bool reads_params = shader == "uniforms_texture";
    harness::ProgramLayout layout{{}, {{"values", 1, shader == "filtered_sample" ? std::nullopt : std::optional<uint32_t>(2)}}};
    if (reads_params) layout.uniform_blocks = {{"Params", 0, sizeof(Params)}};
    auto shade = program(lane, "fullscreen", shader, layout);
    auto texture = lane_backend.upload_texture(texture_);
    auto target = lane_backend.create_target({width, height, false});
    EXPECT_TRUE(texture && target);
    Params params = params_;
    params.tiling = tiling;
    harness::RenderPass pass{*target, glm::vec4(0.0f), 1.0f, {}};
    pass.draws = {{shade, {}, {}, {{"values", harness::TextureSource::texture(*texture, sampler)}}}};
    if (reads_params) pass.draws[0].uniforms = {{"Params", harness::uniform_bytes(params)}};
    auto rendered = lane_backend.render(pass);
    EXPECT_TRUE(rendered) << rendered.error().to_string();
    auto image = lane_backend.read_color(*target);
    EXPECT_TRUE(image);
    return image ? *image : harness::FloatImage{};
  }

  harness::TextureData texture_;
  std::vector<glm::vec4> texels_;
  Params params_{};
};

TEST_F(UniformsAndTextures, TexelCentresGiveTheHostsExpression) {
  // A target the size of the texture samples every texel at its centre, where linear filtering
  // returns the texel itself, so the host can compute each pixel.
  for (Lane lane : harness::all_lanes()) {
    SCOPED_TRACE(harness::lane_name(lane));
    harness::FloatImage image = render(lane, "uniforms_texture", kTextureSize, kTextureSize, {1, 1, 0, 0}, {});
    ASSERT_EQ(image.width, kTextureSize);
    for (uint32_t y = 0; y < kTextureSize; ++y)
      for (uint32_t x = 0; x < kTextureSize; ++x) {
        const glm::vec4 expected = params_.transform * texels_[y * kTextureSize + x] * params_.gain + params_.bias;
        const glm::vec4 got = image.at(x, y);
        // fp32 evaluation order (fused multiply-add or not) moves the last bits; the values are
        // below ~20 in magnitude, so 1e-5 is a few ULP.
        for (int c = 0; c < 4; ++c) EXPECT_NEAR(got[c], expected[c], 1e-5) << x << "," << y;
      }
  }
}

TEST_F(UniformsAndTextures, FilteredSamplingIsBitIdentical) {
  // Off-centre coordinates, wrapping and bilinear filtering, with no arithmetic of the shader's
  // own: both lanes end in llvmpipe's one sampler, so they must agree bit for bit.
  for (harness::AddressMode address : {harness::AddressMode::Repeat, harness::AddressMode::ClampToEdge}) {
    const harness::SamplerDesc sampler{harness::Filter::Linear, address};
    harness::FloatImage gl = render(Lane::Gl, "filtered_sample", 37, 23, {}, sampler);
    harness::FloatImage vk = render(Lane::Vk, "filtered_sample", 37, 23, {}, sampler);
    ASSERT_EQ(gl.width, 37u);
    ASSERT_EQ(vk.width, 37u);
    const harness::ImageDifference difference = harness::max_difference(gl, vk);
    EXPECT_TRUE(harness::bitwise_equal(gl, vk))
        << "max difference " << difference.max << " at " << difference.x << "," << difference.y;
  }
}

TEST_F(UniformsAndTextures, ShaderArithmeticAgreesWithinRounding) {
  // Not bit-identical, and this is why: the lanes reach llvmpipe by two compilers (Mesa's GLSL
  // compiler for gl; glslang, SPIR-V and spirv_to_nir for vk), which round the same expression
  // differently: `uv * tiling.xy + tiling.zw` differs by one ULP (1.2e-7 near 1), and `precise`
  // does not change it. Bilinear filtering scales a coordinate error by the texture size (16)
  // and the texel step (up to 4): ~8e-6; the 4x4 transform (scale up to 2) and gain 1.75 take
  // it to ~5e-5. Measured here: 2.9e-5 with repeat addressing. The bound is 1e-4.
  const glm::vec4 tiling{1.37f, 0.71f, 0.13f, -0.29f};
  harness::FloatImage gl = render(Lane::Gl, "uniforms_texture", 37, 23, tiling, {});
  harness::FloatImage vk = render(Lane::Vk, "uniforms_texture", 37, 23, tiling, {});
  ASSERT_EQ(gl.width, 37u);
  ASSERT_EQ(vk.width, 37u);
  const harness::ImageDifference difference = harness::max_difference(gl, vk);
  EXPECT_LE(difference.max, 1e-4) << "at " << difference.x << "," << difference.y;
  EXPECT_GT(difference.max, 0.0) << "the lanes now agree exactly: make this test bit-exact";
}

}  // namespace
}  // namespace xshade::tests
