#include "harness/render/shader_cache.h"

#include <filesystem>
#include <fstream>
#include <functional>

#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "harness/render/variant_compiler.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

// A library of one material that includes one file, in a fresh folder per test.
class ShaderCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("xshade_cache_test_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
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
  // Two requests of one .shader that make different programs (red for `first`, the colour
  // `second_colour` of GLSL for `second`) are two entries: both compiled, then `first` from the
  // cache, still red.
  void expect_two_entries(const VariantRequest& first, const VariantRequest& second, const std::string& second_colour) {
    ShaderCache cache(root_ / "cache", "identity");
    EXPECT_FALSE(from_cache(cache, first));
    EXPECT_FALSE(from_cache(cache, second));
    EXPECT_NE(last_.program.fragment.glsl.find(second_colour), std::string::npos) << last_.program.fragment.glsl;
    EXPECT_TRUE(from_cache(cache, first));
    EXPECT_NE(last_.program.fragment.glsl.find("vec4(1.0, 0.0, 0.0, 1.0)"), std::string::npos)
        << last_.program.fragment.glsl;
  }

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
  EXPECT_NE(last_.program.fragment.glsl.find("vec4(0.0, 1.0, 0.0, 1.0)"), std::string::npos)
      << last_.program.fragment.glsl;
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

// Each pass of a .shader is its own program: the second pass is never the first one's entry.
TEST_F(ShaderCacheTest, EachPassOfAUnityShaderIsItsOwnEntry) {
  write("materials/two.shader",
        "Shader \"Two\" { SubShader {\n"
        "  Pass { HLSLPROGRAM\n#pragma fragment frag\nfloat4 frag() : SV_Target { return float4(1, 0, 0, 1); "
        "}\nENDHLSL }\n"
        "  Pass { HLSLPROGRAM\n#pragma fragment frag\nfloat4 frag() : SV_Target { return float4(0, 0, 1, 1); "
        "}\nENDHLSL }\n"
        "} }\n");
  VariantRequest first{root_ / "materials" / "two.shader", "materials/two.shader", {}, {}};
  first.shader_pass = 0;
  VariantRequest second = first;
  second.shader_pass = 1;
  expect_two_entries(first, second, "vec4(0.0, 0.0, 1.0, 1.0)");
}

// A .shader compiled for another Unity platform is another program (its SHADER_API and what
// HLSLSupport.cginc makes of it): never the GLCore entry.
TEST_F(ShaderCacheTest, AUnityPlatformIsItsOwnEntry) {
  write("materials/api.shader",
        "Shader \"Api\" { SubShader {\n  Pass { HLSLPROGRAM\n#pragma fragment frag\n"
        "float4 frag() : SV_Target {\n#if defined(SHADER_API_D3D11)\n  return float4(0, 1, 0, 1);\n#else\n"
        "  return float4(1, 0, 0, 1);\n#endif\n}\nENDHLSL }\n} }\n");
  VariantRequest glcore{root_ / "materials" / "api.shader", "materials/api.shader", {}, {}};
  glcore.shader_pass = 0;
  VariantRequest d3d11 = glcore;
  d3d11.unity_platform = shaderlab::UnityPlatform::D3D11;
  expect_two_entries(glcore, d3d11, "vec4(0.0, 1.0, 0.0, 1.0)");
}

// Two materials, one of which reads the include: editing the include recompiles that one only.
TEST_F(ShaderCacheTest, ChangingAnIncludeRecompilesExactlyTheVariantsThatReadIt) {
  write("materials/plain.hlsl",
        "#pragma fragment frag\nfloat4 frag(float2 uv : TEXCOORD0) : SV_Target { return 1; }\n");
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

// Editing one part of a stored entry by hand, as a flipped bit on disk or a curious user would.
// The edit keeps the entry's first line (its hash), so only the hash check can tell.
class DamagedCacheEntryTest : public ShaderCacheTest {
 protected:
  // The one file of `extension` in the cache.
  fs::path entry(const std::string& extension) {
    fs::path found;
    for (const auto& item : fs::directory_iterator(root_ / "cache"))
      if (item.path().extension() == extension) {
        EXPECT_TRUE(found.empty()) << "two " << extension << " entries";
        found = item.path();
      }
    return found;
  }
  void edit(const fs::path& path, const std::function<void(nlohmann::json&)>& change) {
    std::ifstream file(path, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    const size_t newline = text.find('\n');
    ASSERT_EQ(newline, 32u) << "an entry starts with the hash of its contents";
    nlohmann::json contents = nlohmann::json::parse(text.substr(newline + 1));
    change(contents);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text.substr(0, newline + 1) << contents.dump();
  }
  // Compiles as a new run would; whether it came from the cache, and the warning it gives.
  std::pair<bool, std::optional<Error>> compile(const ShaderCache& cache, Lane lane) {
    VariantCompiler compiler(root_, &cache);
    auto compiled = compiler.compile(request(), lane);
    EXPECT_TRUE(compiled) << compiled.error().to_string();
    last_ = compiled ? *compiled : CompiledVariant{};
    return {compiler.cached() == 1, compiler.cache_damage()};
  }
  // The damaged entry is compiled again with a warning naming it, and rewritten: the next run
  // reads it from the cache, with what the compiler makes.
  void expect_recompiled_and_repaired(const ShaderCache& cache, Lane lane, const fs::path& damaged,
                                      const CompiledVariant& original) {
    auto [cached, warning] = compile(cache, lane);
    EXPECT_FALSE(cached) << "a damaged entry was used";
    ASSERT_TRUE(warning.has_value());
    EXPECT_EQ(warning->message,
              "the shader cache entry " + damaged.string() +
                  " was damaged (its contents do not match their hash), so materials/flat.hlsl [] was "
                  "compiled again and the entry rewritten");
    EXPECT_EQ(last_.program.fragment.glsl, original.program.fragment.glsl);
    auto [again, no_warning] = compile(cache, lane);
    EXPECT_TRUE(again) << "the rewritten entry is not a hit";
    EXPECT_FALSE(no_warning.has_value());
    EXPECT_EQ(last_.program.fragment.glsl, original.program.fragment.glsl);
    EXPECT_EQ(last_.program.fragment.spirv, original.program.fragment.spirv);
    EXPECT_EQ(last_.program.layout.uniform_blocks.size(), original.program.layout.uniform_blocks.size());
  }
};

TEST_F(DamagedCacheEntryTest, EditedGlslIsCompiledAgainWithAWarning) {
  ShaderCache cache(root_ / "cache", "identity");
  ASSERT_FALSE(compile(cache, Lane::Gl).first);
  const CompiledVariant original = last_;
  edit(entry(".variant"), [](nlohmann::json& j) {
    std::string glsl = j["fragment"]["glsl"];
    glsl.replace(glsl.find("vec4(1.0, 0.0, 0.0, 1.0)"), 24, "vec4(0.0, 0.0, 1.0, 1.0)");
    j["fragment"]["glsl"] = glsl;
  });
  expect_recompiled_and_repaired(cache, Lane::Gl, entry(".variant"), original);
}

TEST_F(DamagedCacheEntryTest, FlippedSpirvWordsAreCompiledAgainWithAWarning) {
  ShaderCache cache(root_ / "cache", "identity");
  ASSERT_FALSE(compile(cache, Lane::Vk).first);
  const CompiledVariant original = last_;
  ASSERT_GT(original.program.fragment.spirv.size(), 10u);
  edit(entry(".variant"),
       [](nlohmann::json& j) { j["fragment"]["spirv"][8] = j["fragment"]["spirv"][8].get<uint32_t>() ^ 0x00010000u; });
  expect_recompiled_and_repaired(cache, Lane::Vk, entry(".variant"), original);
}

TEST_F(DamagedCacheEntryTest, AnEditedLayoutIsCompiledAgainWithAWarning) {
  ShaderCache cache(root_ / "cache", "identity");
  ASSERT_FALSE(compile(cache, Lane::Gl).first);
  const CompiledVariant original = last_;
  edit(entry(".variant"), [](nlohmann::json& j) {
    j["uniform_blocks"].push_back({{"name", "Globals"}, {"binding", 3}, {"size", 4096}});
  });
  expect_recompiled_and_repaired(cache, Lane::Gl, entry(".variant"), original);
}

TEST_F(DamagedCacheEntryTest, EditedReflectionIsCompiledAgainWithAWarning) {
  ShaderCache cache(root_ / "cache", "identity");
  ASSERT_FALSE(compile(cache, Lane::Gl).first);
  const CompiledVariant original = last_;
  edit(entry(".variant"), [](nlohmann::json& j) {
    nlohmann::json interface = nlohmann::json::parse(j["interface"].get<std::string>());
    interface["textures"].push_back("_NotInTheShader");
    j["interface"] = interface.dump(1);
  });
  expect_recompiled_and_repaired(cache, Lane::Gl, entry(".variant"), original);
  EXPECT_EQ(last_.interface.textures, original.interface.textures);
}

// The manifest names the program: pointed at another, it would hand out the wrong one.
TEST_F(DamagedCacheEntryTest, AnEditedManifestIsCompiledAgainWithAWarning) {
  ShaderCache cache(root_ / "cache", "identity");
  ASSERT_FALSE(compile(cache, Lane::Gl).first);
  const CompiledVariant original = last_;
  edit(entry(".manifest"), [](nlohmann::json& j) { j["request"] = "materials/other.hlsl"; });
  expect_recompiled_and_repaired(cache, Lane::Gl, entry(".manifest"), original);
}

// Worker processes sharing one cache store the same entry at once while another reads it: every
// read is a whole entry (a hit) or none, never a damaged one.
TEST_F(ShaderCacheTest, ProcessesStoringTheSameEntryAtOnceNeverTearIt) {
  ShaderCache cache(root_ / "cache", "identity");
  EXPECT_FALSE(from_cache(cache, request()));
  const CompiledVariant variant = last_;
  const std::vector<fs::path> dependencies{root_ / "materials" / "flat.hlsl", root_ / "include" / "tint.hlsl"};
  std::vector<pid_t> writers;
  for (int i = 0; i < 4; ++i) {
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      bool ok = true;
      for (int round = 0; round < 200 && ok; ++round)
        ok = bool(cache.store(request(), Lane::Gl, variant, dependencies));
      ::_exit(ok ? 0 : 1);
    }
    writers.push_back(pid);
  }
  size_t hits = 0, damaged = 0;
  for (int round = 0; round < 400; ++round) {
    CacheLookup found = cache.look_up(request(), Lane::Gl);
    hits += found.variant.has_value();
    damaged += found.damage.has_value();
  }
  for (pid_t pid : writers) {
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  }
  EXPECT_EQ(damaged, 0u);
  EXPECT_EQ(hits, 400u);
  for (const auto& item : fs::directory_iterator(root_ / "cache"))
    EXPECT_EQ(item.path().string().find(".tmp"), std::string::npos) << item.path();
}

TEST(ContentHash, IsStableAndSensitive) {
  EXPECT_EQ(content_hash("abc"), content_hash("abc"));
  EXPECT_NE(content_hash("abc"), content_hash("abd"));
  EXPECT_EQ(content_hash("").size(), 32u);
}

}  // namespace
}  // namespace xshade::harness
