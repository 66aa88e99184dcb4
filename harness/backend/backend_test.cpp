// The rules every backend holds a texture upload and a texture binding to (backend.h), without a
// driver: what both backends refuse, they refuse with the same words.
#include "harness/backend/backend.h"

#include <optional>

#include <gtest/gtest.h>

namespace xshade::harness {
namespace {

TextureData texture(TextureDimension dimension, uint32_t width, uint32_t height, uint32_t layers,
                    TextureFormat format = TextureFormat::Rgba8Unorm, uint32_t samples = 1) {
  TextureData data;
  data.format = format;
  data.dimension = dimension;
  data.width = width;
  data.height = height;
  data.layers = layers;
  data.samples = samples;
  data.levels.emplace_back(level_bytes(data, 0));
  return data;
}

std::string refusal(const TextureData& data) {
  auto valid = validate_texture(data, 4096);
  return valid ? std::string("accepted") : valid.error().message;
}

TEST(Textures, ALevelHoldsEveryLayerOrSliceOfItsSize) {
  TextureData cube = texture(TextureDimension::Cube, 4, 4, 6, TextureFormat::Rgba32Float);
  EXPECT_EQ(level_bytes(cube, 0), 4u * 4 * 6 * 16);
  EXPECT_EQ(level_bytes(cube, 1), 2u * 2 * 6 * 16);  // layers stay
  TextureData volume = texture(TextureDimension::Tex3D, 8, 4, 4, TextureFormat::R32Float);
  EXPECT_EQ(level_bytes(volume, 1), 4u * 2 * 2 * 4);  // slices halve
  EXPECT_EQ(level_bytes(volume, 3), 1u * 1 * 1 * 4);
}

TEST(Textures, EachDimensionKeepsItsOwnRules) {
  EXPECT_EQ(refusal(texture(TextureDimension::Cube, 4, 4, 6)), "accepted");
  EXPECT_EQ(refusal(texture(TextureDimension::CubeArray, 4, 4, 12)), "accepted");
  EXPECT_EQ(refusal(texture(TextureDimension::Tex2D, 4, 4, 1, TextureFormat::Rgba32Uint, 4)), "accepted");
  EXPECT_EQ(refusal(texture(TextureDimension::Cube, 4, 4, 5)),
            "upload_texture: TextureCube: a cube has 6 faces (+X, -X, +Y, -Y, +Z, -Z), not 5 layers");
  EXPECT_EQ(refusal(texture(TextureDimension::CubeArray, 4, 4, 8)),
            "upload_texture: TextureCubeArray: a cube array has 6 layers per cube, not 8");
  EXPECT_EQ(refusal(texture(TextureDimension::Cube, 4, 2, 6)),
            "upload_texture: TextureCube: a cube's faces are square, not 4x2");
  EXPECT_EQ(refusal(texture(TextureDimension::Tex1D, 4, 2, 1)),
            "upload_texture: Texture1D: a 1D texture has height 1, not 2");
  EXPECT_EQ(refusal(texture(TextureDimension::Tex2D, 4, 4, 3)),
            "upload_texture: Texture2D: has 3 layers; only arrays, cubes and 3D textures have more than one");
  EXPECT_EQ(refusal(texture(TextureDimension::Tex3D, 4, 4, 4, TextureFormat::Rgba8Unorm, 4)),
            "upload_texture: Texture3D: only 2D textures and 2D arrays can be multisampled");
  EXPECT_EQ(refusal(texture(TextureDimension::Tex2D, 4, 4, 1, TextureFormat::Depth32Float, 4)),
            "upload_texture: Texture2DMS: a multisampled Depth32Float texture is not supported (use a linear colour or "
            "integer format)");
  EXPECT_EQ(refusal(texture(TextureDimension::Tex3D, 4, 4, 4, TextureFormat::Depth32Float)),
            "upload_texture: Texture3D: neither API has 3D depth textures");
  TextureData short_level = texture(TextureDimension::Tex2DArray, 4, 4, 3);
  short_level.levels[0].resize(4 * 4 * 4 * 2);
  EXPECT_EQ(refusal(short_level),
            "upload_texture: Texture2DArray: mip level 0 has 128 bytes, expected 192 (4x4, 3 layers, 4 bytes a texel)");
  TextureData too_many = texture(TextureDimension::Tex3D, 4, 4, 2);
  for (uint32_t level = 1; level < 4; ++level) too_many.levels.emplace_back(level_bytes(too_many, level));
  EXPECT_EQ(refusal(too_many), "upload_texture: Texture3D: 4 mip levels given but a 4x4x2 texture has at most 3");
}

TEST(Textures, ABindingMustBeWhatTheSlotDeclares) {
  TextureSlot slot{"environment", 16, std::nullopt};
  slot.shape = {TextureDimension::Cube, false};
  const SamplerDesc point{Filter::Nearest, AddressMode::ClampToEdge};
  const auto check = [&](const BoundTextureFacts& bound, const SamplerDesc& sampler) {
    auto fits = check_bound_texture(slot, bound, sampler, "draw 0");
    return fits ? std::string("accepted") : fits.error().message;
  };
  EXPECT_EQ(check({{TextureDimension::Cube, false}, TextureFormat::Rgba8Unorm, "texture 2"}, point), "accepted");
  EXPECT_EQ(check({{TextureDimension::Tex2DArray, false}, TextureFormat::Rgba8Unorm, "texture 2"}, point),
            "draw 0: texture 'environment' is declared TextureCube, but texture 2 is a Texture2DArray");
  slot.shape = {TextureDimension::Tex2D, true};
  EXPECT_EQ(check({{TextureDimension::Tex2D, false}, TextureFormat::Rgba8Unorm, "texture 2"}, point),
            "draw 0: texture 'environment' is declared Texture2DMS, but texture 2 is a Texture2D");
  slot.shape = {};
  slot.texel = TexelKind::Int;
  EXPECT_EQ(check({{}, TextureFormat::Rgba32Uint, "texture 2"}, point),
            "draw 0: texture 'environment' reads int texels, but texture 2 is Rgba32Uint (uint texels)");
  EXPECT_EQ(check({{}, TextureFormat::Rgba32Sint, "texture 2"}, {Filter::Linear, AddressMode::Repeat}),
            "draw 0: texture 'environment': texture 2 has integer texels (Rgba32Sint), which cannot be filtered "
            "linearly; use a nearest sampler");
  slot.texel = TexelKind::Float;
  slot.comparison = true;
  EXPECT_EQ(check({{}, TextureFormat::Depth32Float, "the depth of target 1"}, point), "accepted");
  EXPECT_EQ(check({{}, TextureFormat::R32Float, "texture 2"}, point),
            "draw 0: texture 'environment' is read with a comparison sampler, which needs a depth texture "
            "(Depth32Float or a target's depth), but texture 2 is R32Float");
}

namespace backend_refusal_kinds {
// The kind of a refusal; none for what is accepted.
std::optional<ErrorKind> refusal_kind(const Result<void>& result) {
  return result ? std::nullopt : std::optional<ErrorKind>(result.error().kind);
}
}  // namespace backend_refusal_kinds

// Whose fault a refusal is: what the caller gave against the contract is xshade's own bug
// (Internal), a size the device cannot hold is the device's (Backend). Both exit 3, and neither
// is ever the user's (exit 2): the renderer checks the scene before a backend sees it.
TEST(Textures, AContractRefusalIsInternalAndADeviceLimitIsTheBackends) {
  using backend_refusal_kinds::refusal_kind;
  EXPECT_EQ(refusal_kind(validate_texture(texture(TextureDimension::Tex2D, 0, 4, 1), 4096)), ErrorKind::Internal);
  EXPECT_EQ(refusal_kind(validate_texture(texture(TextureDimension::Cube, 4, 4, 5), 4096)), ErrorKind::Internal);
  EXPECT_EQ(refusal_kind(validate_texture(texture(TextureDimension::Tex2D, 8, 8, 1), 4)), ErrorKind::Backend);
  EXPECT_EQ(refusal_kind(validate_mesh({})), ErrorKind::Internal);
  TextureSlot slot{"environment", 16, std::nullopt};
  slot.shape = {TextureDimension::Cube, false};
  EXPECT_EQ(refusal_kind(check_bound_texture(slot, {{TextureDimension::Tex2D, false}, TextureFormat::Rgba8Unorm, "t"},
                                             {Filter::Nearest, AddressMode::ClampToEdge}, "draw 0")),
            ErrorKind::Internal);
}

}  // namespace
}  // namespace xshade::harness
