#include "harness/render/shader_cache.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "harness/render/variant_compiler.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

// A library of one material that includes one file, in a fresh folder per test.
class ShaderCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("xshade_cache_test_" + std::string(
        ::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "materials");
    fs::create_directories(root_ / "include");
    write("include/tint.hlsl", "float4 tint() { return float4(1, 0, 0, 1); }\n");
    write("materials/flat.hlsl",
          "#pragma fragment frag\n#pragma multi_compile _ BRIGHT\n#include \"include/tint.hlsl\"\n"
          "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n#ifdef BRIGHT\n  return 2 * tint();\n#else\n"
          "  return tint();\n#endif\n}\n");
  }
  void TearDown() override { fs::remove_all(root_); }

  void write(const std::string& name, const std::string& text) { std::ofstream(root_ / name) << text; }

  VariantRequest request(std::vector<std::string> keywords = {}) const {
    return {root_ / "materials" / "flat.hlsl", "materials/flat.hlsl", std::move(keywords), {}};
  }

  // Compiles the request once with a fresh compiler (as a new run would) and says whether the
  // program came from the cache.
  bool from_cache(const ShaderCache& cache, const VariantRequest& r) {
    VariantCompiler compiler(root_, &cache);
    auto compiled = compiler.compile(r, Lane::Gl);
    EXPECT_TRUE(compiled) << compiled.error().to_string();
    last_ = compiled ? *compiled : CompiledVariant{};
    return compiler.cached() == 1;
  }

  fs::path root_;
  CompiledVariant last_;
};

TEST_F(ShaderCacheTest, AnUnchangedVariantIsCompiledOnce) {
  ShaderCache cache(root_ / "cache", "identity");
  EXPECT_FALSE(from_cache(cache, request()));
  const std::string first = last_.program.fragment.glsl;
  EXPECT_TRUE(from_cache(cache, request()));
  EXPECT_EQ(last_.program.fragment.glsl, first);
  EXPECT_EQ(last_.program.layout.uniform_blocks.size(), 0u);
  EXPECT_TRUE(last_.program.fullscreen);
}

TEST_F(ShaderCacheTest, ChangingAnIncludeKeywordsLaneOrCompilerMisses) {
  ShaderCache cache(root_ / "cache", "identity");
  EXPECT_FALSE(from_cache(cache, request()));
  EXPECT_FALSE(from_cache(cache, request({"BRIGHT"})));
  EXPECT_TRUE(from_cache(cache, request({"BRIGHT"})));

  write("include/tint.hlsl", "float4 tint() { return float4(0, 1, 0, 1); }\n");
  EXPECT_FALSE(from_cache(cache, request()));
  EXPECT_NE(last_.program.fragment.glsl.find("vec4(0.0, 1.0, 0.0, 1.0)"), std::string::npos) << last_.program.fragment.glsl;
  EXPECT_TRUE(from_cache(cache, request()));

  EXPECT_FALSE(cache.find(request(), Lane::Vk).has_value());
  VariantRequest half = request();
  half.half_emulation = true;
  EXPECT_FALSE(from_cache(cache, half));
  EXPECT_TRUE(from_cache(cache, half));
  ShaderCache other_compiler(root_ / "cache", "another identity");
  EXPECT_FALSE(other_compiler.find(request(), Lane::Gl).has_value());
}

TEST_F(ShaderCacheTest, EditingTheMaterialsOwnFileMisses) {
  ShaderCache cache(root_ / "cache", "identity");
  EXPECT_FALSE(from_cache(cache, request()));
  EXPECT_TRUE(from_cache(cache, request()));
  write("materials/flat.hlsl",
        "#pragma fragment frag\n#pragma multi_compile _ BRIGHT\n#include \"include/tint.hlsl\"\n"
        "float4 frag(float2 uv : TEXCOORD0) : SV_Target { return 0.5 * tint(); }\n");
  EXPECT_FALSE(from_cache(cache, request()));
  EXPECT_NE(last_.program.fragment.glsl.find("0.5"), std::string::npos) << last_.program.fragment.glsl;
}

// Two materials, one of which reads the include: editing the include recompiles that one only.
TEST_F(ShaderCacheTest, ChangingAnIncludeRecompilesExactlyTheVariantsThatReadIt) {
  write("materials/plain.hlsl", "#pragma fragment frag\nfloat4 frag(float2 uv : TEXCOORD0) : SV_Target { return 1; }\n");
  const VariantRequest plain{root_ / "materials" / "plain.hlsl", "materials/plain.hlsl", {}, {}};
  ShaderCache cache(root_ / "cache", "identity");
  EXPECT_FALSE(from_cache(cache, request()));
  EXPECT_FALSE(from_cache(cache, request({"BRIGHT"})));
  EXPECT_FALSE(from_cache(cache, plain));

  write("include/tint.hlsl", "float4 tint() { return float4(0, 0, 1, 1); }\n");
  EXPECT_FALSE(from_cache(cache, request()));
  EXPECT_FALSE(from_cache(cache, request({"BRIGHT"})));
  EXPECT_TRUE(from_cache(cache, plain));
}

TEST_F(ShaderCacheTest, ADamagedEntryIsCompiledAgain) {
  ShaderCache cache(root_ / "cache", "identity");
  EXPECT_FALSE(from_cache(cache, request()));
  for (const auto& entry : fs::directory_iterator(root_ / "cache"))
    if (entry.path().extension() == ".variant") std::ofstream(entry.path()) << "{ not json";
  EXPECT_FALSE(from_cache(cache, request()));
  EXPECT_TRUE(from_cache(cache, request()));
}

TEST_F(ShaderCacheTest, AnUnwritableCacheCostsTimeNotTheCompile) {
  write("not_a_folder", "a file where the cache folder should be");
  ShaderCache cache(root_ / "not_a_folder", "identity");
  VariantCompiler compiler(root_, &cache);
  EXPECT_TRUE(compiler.compile(request(), Lane::Gl));
  ASSERT_TRUE(compiler.cache_write_error().has_value());
  EXPECT_NE(compiler.cache_write_error()->message.find("cannot create the shader cache"), std::string::npos);
}

TEST(ContentHash, IsStableAndSensitive) {
  EXPECT_EQ(content_hash("abc"), content_hash("abc"));
  EXPECT_NE(content_hash("abc"), content_hash("abd"));
  EXPECT_EQ(content_hash("").size(), 32u);
}

}  // namespace
}  // namespace xshade::harness
