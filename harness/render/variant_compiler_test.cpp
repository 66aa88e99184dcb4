#include "harness/render/variant_compiler.h"

#include <gtest/gtest.h>

#include <fstream>

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

const fs::path kLibrary = fs::path(XSHADE_SOURCE_DIR) / "shaders";

// A material in a folder of its own, with an include beside it, before the library.
class VariantCompilerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("xshade_variant_compiler_" + std::to_string(::getpid()));
    fs::remove_all(folder_);
    fs::create_directories(folder_ / "materials");
    write_include("0.25");
    std::ofstream(folder_ / "materials" / "flat.hlsl") << R"(#pragma vertex vert
#pragma fragment frag
#include "include/scene_inputs.hlsl"
#include "shade.hlsl"
SurfaceVaryings vert(MeshVertex input) { return surface_vertex(input); }
float4 frag(SurfaceVaryings input) : SV_Target { return float4(kShade, kShade, kShade, 1.0); }
)";
  }
  void TearDown() override { fs::remove_all(folder_); }
  void write_include(const std::string& value) {
    std::ofstream(folder_ / "materials" / "shade.hlsl") << "static const float kShade = " << value << ";\n";
  }
  VariantRequest request() const {
    VariantRequest made;
    made.source = folder_ / "materials" / "flat.hlsl";
    made.library_path = "materials/flat.hlsl";
    return made;
  }
  ShaderSearchPath shaders() const { return ShaderSearchPath(std::vector<fs::path>{folder_, kLibrary}); }
  fs::path folder_;
};

std::string fragment_of(const CompiledVariant& variant) { return variant.program.fragment.glsl; }

// A long-lived process (a worker of `xshade watch`) keeps what its front end made, but not past
// an edit of a file it read: the include's new value is in the program.
TEST_F(VariantCompilerTest, AnIncludeEditedSinceIsCompiledAgain) {
  VariantCompiler compiler(shaders(), nullptr);
  auto first = compiler.compile(request(), Lane::Gl);
  ASSERT_TRUE(first) << first.error().to_string();
  EXPECT_NE(fragment_of(*first).find("0.25"), std::string::npos) << fragment_of(*first);
  write_include("0.75");
  auto second = compiler.compile(request(), Lane::Gl);
  ASSERT_TRUE(second) << second.error().to_string();
  EXPECT_NE(fragment_of(*second).find("0.75"), std::string::npos) << fragment_of(*second);
  EXPECT_EQ(compiler.compiled(), 2u);
}

TEST_F(VariantCompilerTest, TheFilesReadAreTheSourceAndItsIncludesOnceTaken) {
  VariantCompiler compiler(shaders(), nullptr);
  ASSERT_TRUE(compiler.compile(request(), Lane::Gl));
  const std::set<fs::path> read = compiler.take_files_read();
  EXPECT_EQ(read.count(folder_ / "materials" / "flat.hlsl"), 1u);
  EXPECT_EQ(read.count(folder_ / "materials" / "shade.hlsl"), 1u);
  EXPECT_EQ(read.count(kLibrary / "include" / "scene_inputs.hlsl"), 1u);
  EXPECT_TRUE(compiler.take_files_read().empty());
}

// Found in the cache, the variant still names what it was compiled from.
TEST_F(VariantCompilerTest, AVariantFromTheCacheNamesTheFilesItWasCompiledFrom) {
  const ShaderCache cache(folder_ / "cache", "identity");
  VariantCompiler filler(shaders(), &cache);
  ASSERT_TRUE(filler.compile(request(), Lane::Gl));
  VariantCompiler warm(shaders(), &cache);
  ASSERT_TRUE(warm.compile(request(), Lane::Gl));
  EXPECT_EQ(warm.cached(), 1u);
  EXPECT_EQ(warm.take_files_read().count(fs::absolute(folder_ / "materials" / "shade.hlsl")), 1u);
}

}  // namespace
}  // namespace xshade::harness
