// A uniform block and a sampled texture give the same result on every lane, and the right one.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

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

    params_.transform =
        glm::rotate(glm::scale(glm::mat4(1.0f), glm::vec3(0.5f, 2.0f, 1.5f)), 0.7f, glm::vec3(0.3f, 0.8f, 0.1f));
    params_.transform[3] = glm::vec4(0.25f, -0.5f, 0.125f, 1.0f);
    params_.bias = {0.1f, 0.2f, -0.3f, 0.4f};
    params_.gain = 1.75f;
  }

  // Runs tests/shaders/<shader>.*.frag, which reads `values` and maybe `Params`.
  harness::FloatImage render(Lane lane, const std::string& shader, uint32_t width, uint32_t height, glm::vec4 tiling,
                             harness::SamplerDesc sampler) {
    harness::Backend& lane_backend = backend(lane);
    const bool reads_params = shader == "uniforms_texture";
    harness::ProgramLayout layout{{}, {{"values", 1, 2}}};
    if (reads_params) layout.uniform_blocks = {{"Params", 0, sizeof(Params)}};
    auto shade = program(lane, "fullscreen", shader, layout);
    auto texture = lane_backend.upload_texture(texture_);
    auto target = lane_backend.create_target({width, height, false});
    EXPECT_TRUE(texture && target);
    Params params = params_;
    params.tiling = tiling;
    harness::RenderPass pass{*target, glm::vec4(0.0f), 1.0f, {}};
    pass.draws = {{shade, {}, {}, {{"values", harness::TextureSource::texture(*texture, sampler)}}, {}}};
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
  for (Lane lane : harness::glsl_pair_lanes()) {
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

// Bilinear filtering of the test texture at uv, in double precision: the reference each lane's
// sampler is measured against. Texel centres sit at (i + 0.5) / size.
glm::dvec4 bilinear_reference(const std::vector<glm::vec4>& texels, glm::dvec2 uv, harness::AddressMode address) {
  const int size = int(kTextureSize);
  auto fetch = [&](int x, int y) {
    if (address == harness::AddressMode::Repeat) {
      x = ((x % size) + size) % size;
      y = ((y % size) + size) % size;
    } else {
      x = std::clamp(x, 0, size - 1);
      y = std::clamp(y, 0, size - 1);
    }
    return glm::dvec4(texels[size_t(y) * kTextureSize + size_t(x)]);
  };
  const glm::dvec2 position = uv * double(size) - 0.5;
  const glm::dvec2 base = glm::floor(position);
  const glm::dvec2 f = position - base;
  const int x = int(base.x), y = int(base.y);
  return glm::mix(glm::mix(fetch(x, y), fetch(x + 1, y), f.x), glm::mix(fetch(x, y + 1), fetch(x + 1, y + 1), f.x),
                  f.y);
}

TEST_F(UniformsAndTextures, FilteredSamplingMatchesAnExactBilinearReference) {
  // Off-centre coordinates, wrapping and bilinear filtering, with no arithmetic of the shader's
  // own: the interpolated uv is bit-identical on both lanes, and nearest sampling is too. Not so
  // the filtered values. Measured on Mesa 22.3.6 over this image: gl lands up to 3.4e-6 from an
  // fp64 bilinear reference and vk up to 4.2e-6, at different pixels, so the lanes differ by up
  // to 4.1e-6 with texels in [-2, 2]. Neither is wrong: both APIs only promise a few bits of
  // sub-texel precision (Vulkan's minimum subTexelPrecisionBits is 4), and the sampling code
  // llvmpipe generates for each API rounds the filter weights differently. The bound, 1e-5 for
  // each lane against the reference and for the lanes against each other, is ~2.5x the worst
  // seen: tight enough that a wrong texel, a wrong wrap or a half-texel shift (errors of 1e-2
  // and more here) fails.
  for (harness::AddressMode address : {harness::AddressMode::Repeat, harness::AddressMode::ClampToEdge}) {
    SCOPED_TRACE(address == harness::AddressMode::Repeat ? "repeat" : "clamp");
    const harness::SamplerDesc sampler{harness::Filter::Linear, address};
    const uint32_t width = 37, height = 23;
    std::map<Lane, double> worst;
    std::map<Lane, harness::FloatImage> images;
    for (Lane lane : harness::glsl_pair_lanes()) {
      harness::FloatImage image = render(lane, "filtered_sample", width, height, {}, sampler);
      ASSERT_EQ(image.width, width);
      for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
          const glm::dvec2 uv{(x + 0.5) / width, (y + 0.5) / height};
          const glm::dvec4 expected = bilinear_reference(texels_, uv, address);
          for (int c = 0; c < 4; ++c)
            worst[lane] = std::max(worst[lane], std::fabs(double(image.at(x, y)[c]) - expected[c]));
        }
      images.emplace(lane, std::move(image));
    }
    EXPECT_LE(worst[Lane::Gl], 1e-5);
    EXPECT_LE(worst[Lane::Vk], 1e-5);
    EXPECT_LE(harness::max_difference(images[Lane::Gl], images[Lane::Vk]).max, 1e-5);
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
