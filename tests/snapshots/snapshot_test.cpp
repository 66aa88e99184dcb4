// Snapshots of the GLSL the emitter writes for the shader library, both flavours: a review aid
// that shows, in a change's diff, exactly what a compiler change does to real shaders. The
// semantics are tested elsewhere (conformance on the lanes, the scenes); a snapshot only says
// "this changed".
//
// After a deliberate change, rewrite the snapshots and review the diff before committing:
//   cmake --build build --target update_snapshots
// That target builds this file as a separate program that writes (XSHADE_WRITE_SNAPSHOTS); the
// test CTest runs only ever compares, whatever the environment says.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "glsl/glsl_emitter.h"
#include "hlsl_like/compiler.h"

namespace xshade::tests {
namespace {

namespace fs = std::filesystem;

const fs::path kLibrary = XSHADE_SHADER_LIBRARY;
const fs::path kSnapshots = XSHADE_SNAPSHOT_DIR;

struct Variant {
  std::string name;  // the snapshot files' stem
  std::string source;
  std::vector<std::string> keywords;
  std::string entry;  // a post pass's fragment function
};

// The library's variants worth reading: each material's seed forms and its alternatives with
// the guards on, and every depth-of-field pass.
std::vector<Variant> variants() {
  std::vector<Variant> list{
      {"standard_pbr", "materials/standard_pbr.hlsl", {}, {}},
      {"standard_pbr.alternatives_guarded",
       "materials/standard_pbr.hlsl",
       {"_D_GGX_LAGRANGE", "_G_SMITH_CORRELATED", "_F_SPHERICAL_GAUSSIAN", "_GUARDED"},
       {}},
      {"toon", "materials/toon.hlsl", {}, {}},
      {"toon.shadow_tex_guarded", "materials/toon.hlsl", {"_SHADOW_TEX", "_GUARDED"}, {}},
  };
  for (const char* pass : {"coc", "prefilter", "bokeh", "postfilter", "combine"})
    list.push_back({std::string("depth_of_field.") + pass,
                    "post/depth_of_field.hlsl",
                    {"_KERNEL_LARGE"},
                    std::string("frag_") + pass});
  return list;
}

std::string read(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// The emitted text names its source files by path; the library's location is the machine's.
std::string without_library_root(std::string text) {
  const std::string root = kLibrary.string() + "/";
  for (size_t at = text.find(root); at != std::string::npos; at = text.find(root, at)) text.erase(at, root.size());
  return text;
}

// The line where two texts first differ, for a failure message that points at the change.
std::string first_difference(const std::string& expected, const std::string& actual) {
  std::istringstream a(expected), b(actual);
  std::string la, lb;
  for (int line = 1;; ++line) {
    const bool more_a = bool(std::getline(a, la)), more_b = bool(std::getline(b, lb));
    if (!more_a && !more_b) return "identical";
    if (la != lb || more_a != more_b)
      return "line " + std::to_string(line) + ":\n  snapshot: " + (more_a ? la : "<end>") +
             "\n  emitted:  " + (more_b ? lb : "<end>");
  }
}

class Snapshot : public ::testing::TestWithParam<Variant> {};

TEST_P(Snapshot, EmittedGlslMatches) {
  const Variant& variant = GetParam();
  hlsl::CompileOptions options;
  options.include_dirs = {kLibrary};
  options.keywords = variant.keywords;
  options.fragment_only_entry = variant.entry;
  auto module = hlsl::compile_file(kLibrary / variant.source, options);
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
#ifdef XSHADE_WRITE_SNAPSHOTS
  constexpr bool update = true;
#else
  constexpr bool update = false;
#endif
  for (glsl::Flavour flavour : {glsl::Flavour::Gl, glsl::Flavour::Vk}) {
    auto emitted = glsl::emit(*module, {flavour});
    ASSERT_TRUE(emitted) << emitted.error().to_string();
    const std::string flavour_name = flavour == glsl::Flavour::Gl ? "gl" : "vk";
    for (const auto& [stage, suffix] : {std::pair{&emitted->vertex, "vert"}, std::pair{&emitted->fragment, "frag"}}) {
      const fs::path file = kSnapshots / (variant.name + "." + flavour_name + "." + suffix);
      if (!*stage) {
        // A stage the emitter stopped producing is a change too, not a snapshot to skip.
        if (update) fs::remove(file);
        EXPECT_TRUE(update || !fs::exists(file))
            << file.filename().string() << " is a snapshot of a stage the emitter no "
            << "longer produces";
        continue;
      }
      const std::string text = without_library_root((*stage)->text);
      if (update) {
        std::ofstream(file, std::ios::binary) << text;
        continue;
      }
      ASSERT_TRUE(fs::exists(file)) << file
                                    << " is missing; write it with cmake --build build --target update_snapshots";
      const std::string expected = read(file);
      EXPECT_TRUE(expected == text)
          << file.filename().string() << " differs at " << first_difference(expected, text)
          << "\nIf the change is meant, rewrite with cmake --build build --target update_snapshots and "
             "review the diff.";
    }
  }
}

std::string test_name(const ::testing::TestParamInfo<Variant>& param) {
  std::string name = param.param.name;
  for (char& c : name)
    if (c == '.') c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Library, Snapshot, ::testing::ValuesIn(variants()), test_name);

}  // namespace
}  // namespace xshade::tests
