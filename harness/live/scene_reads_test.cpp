#include "harness/live/scene_reads.h"

#include <gtest/gtest.h>

#include "harness/live/file_watcher.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

TEST(SceneReads, TheSceneItsProjectItsAssetsAndWhatItsCompilesRead) {
  CheckedScene checked;
  checked.files_read = {"/shaders/toon.hlsl", "/shaders/include/brdf.hlsl"};
  Scene scene;
  SceneObject object;
  object.mesh.file = "/scenes/bunny.obj";
  object.textures["_MainTex"].file = "/scenes/albedo.png";
  object.textures["_Sky"].faces = {"/scenes/px.png", "/scenes/nx.png"};
  object.buffers["_Weights"].file = "/scenes/weights.bin";
  scene.objects.push_back(object);
  PostEffect effect;
  effect.textures["_Lut"].file = "/scenes/lut.png";
  scene.post.push_back(effect);
  scene.environment.file = "/scenes/sky.exr";
  checked.scene = scene;
  EXPECT_EQ(
      scene_reads("/scenes/toon.toml", checked, "/project/xshade.toml"),
      (std::set<fs::path>{"/scenes/toon.toml", "/project/xshade.toml", "/shaders/toon.hlsl",
                          "/shaders/include/brdf.hlsl", "/scenes/bunny.obj", "/scenes/albedo.png", "/scenes/px.png",
                          "/scenes/nx.png", "/scenes/weights.bin", "/scenes/lut.png", "/scenes/sky.exr"}));
}

// A bless in another terminal is seen: the lane's golden images are watched, where their folder is.
TEST(SceneReads, EachLanesGoldenImagesInAFolderThatExists) {
  const fs::path golden = fs::temp_directory_path() / "xshade_scene_reads_golden";
  fs::create_directories(golden);
  CheckedScene checked;
  checked.result.scene = "toon";
  checked.result.lanes.push_back(LaneResult{});
  checked.result.lanes.back().lane = "vk";
  const GoldenStore goldens(golden);
  const std::set<fs::path> reads = scene_reads("/s/toon.toml", checked, {}, &goldens);
  EXPECT_EQ(reads, (std::set<fs::path>{"/s/toon.toml", golden / "toon.png", golden / "toon.exr"}));
  fs::remove_all(golden);
}

TEST(SceneReads, ASceneThatDidNotLoadReadItsFileAlone) {
  EXPECT_EQ(scene_reads("scenes/broken.toml", CheckedScene{}, {}),
            std::set<fs::path>{normal_file_path("scenes/broken.toml")});
}

TEST(SceneReadIndex, AFileReachesTheScenesThatReadItInTheirOrder) {
  SceneReadIndex index;
  index.set("/s/a.toml", {"/s/a.toml", "/shaders/toon.hlsl", "/shaders/brdf.hlsl"});
  index.set("/s/b.toml", {"/s/b.toml", "/shaders/pbr.hlsl", "/shaders/brdf.hlsl"});
  const std::vector<fs::path> scenes = {"/s/b.toml", "/s/a.toml", "/s/c.toml"};
  EXPECT_EQ(index.reached({"/shaders/brdf.hlsl"}, scenes), (std::vector<fs::path>{"/s/b.toml", "/s/a.toml"}));
  EXPECT_EQ(index.reached({"/shaders/toon.hlsl"}, scenes), std::vector<fs::path>{"/s/a.toml"});
  EXPECT_TRUE(index.reached({"/shaders/unused.hlsl"}, scenes).empty());
  // A scene not rendered yet is reached by its own file.
  EXPECT_EQ(index.reached({"/s/c.toml"}, scenes), std::vector<fs::path>{"/s/c.toml"});
  EXPECT_EQ(index.all_files().size(), 5u);
}

TEST(SceneReadIndex, ANewRenderReplacesWhatTheSceneRead) {
  SceneReadIndex index;
  index.set("/s/a.toml", {"/s/a.toml", "/shaders/old.hlsl"});
  index.set("/s/a.toml", {"/s/a.toml", "/shaders/new.hlsl"});
  EXPECT_TRUE(index.reached({"/shaders/old.hlsl"}, {"/s/a.toml"}).empty());
  EXPECT_EQ(index.reached({"/shaders/new.hlsl"}, {"/s/a.toml"}).size(), 1u);
  index.forget("/s/a.toml");
  EXPECT_TRUE(index.all_files().empty());
}

}  // namespace
}  // namespace xshade::harness
