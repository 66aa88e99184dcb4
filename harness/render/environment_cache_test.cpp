#include "harness/render/environment_cache.h"

#include <cstring>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

EnvironmentSpec gradient() {
  EnvironmentSpec spec;
  spec.kind = EnvironmentKind::Gradient;
  spec.sky = {0.2f, 0.4f, 0.9f};
  spec.horizon = {0.8f, 0.8f, 0.7f};
  spec.ground = {0.1f, 0.1f, 0.1f};
  return spec;
}

bool same(const Environment& a, const Environment& b) {
  return a.radiance.rgba == b.radiance.rgba && std::memcmp(&a.sh, &b.sh, sizeof a.sh) == 0 &&
         a.prefiltered.levels == b.prefiltered.levels && a.prefiltered.width == b.prefiltered.width;
}

TEST(EnvironmentCache, BuildsOnceAProcessAndOnceAFolderAndNeverUsesADamagedEntry) {
  const fs::path folder = fs::temp_directory_path() / "xshade_environment_cache_test";
  fs::remove_all(folder);
  const Environment fresh = *build_environment(gradient());

  EnvironmentCache first(folder, "build A");
  auto a = first.get(gradient());
  ASSERT_TRUE(a) << a.error().to_string();
  auto again = first.get(gradient());
  ASSERT_TRUE(again);
  EXPECT_EQ(a->get(), again->get());  // the same one, not built twice
  EXPECT_EQ(first.built(), 1u);
  EXPECT_TRUE(same(**a, fresh));

  // Another process with the same folder finds it, bit for bit.
  EnvironmentCache second(folder, "build A");
  auto found = second.get(gradient());
  ASSERT_TRUE(found);
  EXPECT_EQ(second.built(), 0u);
  EXPECT_TRUE(same(**found, fresh));

  // Another spec, or another build of xshade, is built.
  EnvironmentSpec brighter = gradient();
  brighter.intensity = 2.0f;
  ASSERT_TRUE(second.get(brighter));
  EXPECT_EQ(second.built(), 1u);
  EnvironmentCache rebuilt(folder, "build B");
  ASSERT_TRUE(rebuilt.get(gradient()));
  EXPECT_EQ(rebuilt.built(), 1u);

  // A flipped byte in every entry: each is built again, and right.
  for (const auto& entry : fs::directory_iterator(folder)) {
    std::fstream file(entry.path(), std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(-5, std::ios::end);
    file.put('\x7f');
  }
  EnvironmentCache damaged(folder, "build A");
  auto repaired = damaged.get(gradient());
  ASSERT_TRUE(repaired);
  EXPECT_EQ(damaged.built(), 1u);
  EXPECT_TRUE(same(**repaired, fresh));
  fs::remove_all(folder);
}

TEST(EnvironmentCache, AnEquirectIsKeptByItsFilesBytes) {
  const fs::path folder = fs::temp_directory_path() / "xshade_environment_cache_file_test";
  fs::remove_all(folder);
  EnvironmentSpec spec;
  spec.kind = EnvironmentKind::Equirect;
  spec.file = fs::path(XSHADE_SOURCE_DIR) / "golden" / "white_furnace.png";
  EnvironmentCache cache(folder, "build A");
  ASSERT_TRUE(cache.get(spec));
  spec.file = fs::path(XSHADE_SOURCE_DIR) / "golden" / "toon_shadow_texture.png";
  ASSERT_TRUE(cache.get(spec));
  EXPECT_EQ(cache.built(), 2u);
  spec.file = fs::path(XSHADE_SOURCE_DIR) / "golden" / "missing.png";
  EXPECT_FALSE(cache.get(spec)) << "a file that cannot be read is the build's error, with its name";
  fs::remove_all(folder);
}

}  // namespace
}  // namespace xshade::harness
