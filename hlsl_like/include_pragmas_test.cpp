// Unity's #include_with_pragmas: an #include whose file's Unity pragmas apply to the program, where
// a plain #include's are ignored (Unity's manual, "pragma directives in HLSL", Limitations).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "hlsl_like/compiler.h"

namespace xshade::hlsl {
namespace {

namespace fs = std::filesystem;

// A fresh folder of shader files, removed with everything in it.
class PragmaFolder {
 public:
  PragmaFolder() {
    std::random_device random;
    for (;;) {
      const fs::path candidate = fs::temp_directory_path() / ("xshade_include_pragmas_" + std::to_string(random()) +
                                                              "_" + std::to_string(random()));
      if (fs::create_directory(candidate)) {
        path_ = fs::canonical(candidate);
        return;
      }
    }
  }
  ~PragmaFolder() {
    std::error_code error;
    fs::remove_all(path_, error);
  }
  PragmaFolder(const PragmaFolder&) = delete;
  PragmaFolder& operator=(const PragmaFolder&) = delete;

  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path file = path_ / name;
    std::ofstream(file, std::ios::binary) << text;
    return file;
  }

 private:
  fs::path path_;
};

// "file:line:col: severity: message" of every diagnostic, the folder left out of the file names.
std::vector<std::string> pragma_messages(const Module& module, const fs::path& main) {
  const std::string prefix = main.parent_path().string() + "/";
  std::vector<std::string> out;
  for (const Diagnostic& d : module.diagnostics.diagnostics()) {
    std::string text = d.to_string();
    if (text.rfind(prefix, 0) == 0) text = text.substr(prefix.size());
    out.push_back(text);
  }
  return out;
}

constexpr const char* kPragmaFeatures =
    "#pragma multi_compile LOW HIGH\n"
    "#pragma fragment frag\n";

constexpr const char* kPragmaFrag =
    "float4 frag() : SV_Target {\n"
    "#ifdef LOW\n"
    "  return 0.25;\n"
    "#else\n"
    "  return 1;\n"
    "#endif\n"
    "}\n";

TEST(IncludeWithPragmas, TheIncludedFilesPragmasApplyAsIfWrittenInTheProgram) {
  PragmaFolder folder;
  folder.write("features.hlsl", kPragmaFeatures);
  const fs::path main =
      folder.write("main.hlsl", std::string("#include_with_pragmas \"features.hlsl\"\n") + kPragmaFrag);
  auto module = compile_file(main, {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  EXPECT_TRUE(module->diagnostics.diagnostics().empty()) << module->diagnostics.render_all();
  // The set is the program's: its first keyword is the variant's, and frag its fragment stage.
  ASSERT_EQ(module->reflection.keyword_sets.size(), 1u);
  EXPECT_EQ(module->reflection.keyword_sets[0].keywords, (std::vector<std::string>{"LOW", "HIGH"}));
  EXPECT_EQ(module->reflection.active_keywords, (std::vector<std::string>{"LOW"}));
  ASSERT_NE(module->entry_points.fragment, nullptr);
  EXPECT_EQ(module->entry_points.fragment->name, "frag");
}

TEST(IncludeWithPragmas, APlainIncludesUnityPragmasAreIgnoredWithAWarning) {
  PragmaFolder folder;
  folder.write("features.hlsl", std::string(kPragmaFeatures) + "#pragma warning(disable : 3205)\n");
  const fs::path main =
      folder.write("main.hlsl", std::string("#pragma fragment frag\n#include \"features.hlsl\"\n") + kPragmaFrag);
  auto module = compile_file(main, {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const std::string why =
      " is ignored: this file is read by a plain #include, and Unity takes its pragmas only from the shader's "
      "program and the files it includes with #include_with_pragmas; include this file with #include_with_pragmas "
      "to apply it";
  // HLSL's own `#pragma warning` goes to the compiler from any file, as in Unity.
  EXPECT_EQ(pragma_messages(*module, main),
            (std::vector<std::string>{"features.hlsl:1:9: warning: #pragma multi_compile" + why,
                                      "features.hlsl:2:9: warning: #pragma fragment" + why}));
  EXPECT_TRUE(module->reflection.keyword_sets.empty());
  EXPECT_TRUE(module->reflection.active_keywords.empty());
}

TEST(IncludeWithPragmas, OnlyAnUnbrokenChainFromTheProgramApplies) {
  PragmaFolder folder;
  folder.write("features.hlsl", kPragmaFeatures);
  folder.write("plain_then_pragmas.hlsl", "#include_with_pragmas \"features.hlsl\"\n");
  folder.write("pragmas_then_plain.hlsl", "#include \"features.hlsl\"\n");
  folder.write("both.hlsl", "#include_with_pragmas \"features.hlsl\"\n");
  // Unity's note: a file included by #include ignores the pragmas of what it includes by
  // #include_with_pragmas; and a plain #include inside an #include_with_pragmas file is plain.
  for (const char* chain :
       {"#include \"plain_then_pragmas.hlsl\"\n", "#include_with_pragmas \"pragmas_then_plain.hlsl\"\n"}) {
    SCOPED_TRACE(chain);
    const fs::path main = folder.write("main.hlsl", std::string("#pragma fragment frag\n") + chain + kPragmaFrag);
    auto module = compile_file(main, {});
    ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
    EXPECT_EQ(module->diagnostics.warning_count(), 2u);
    EXPECT_TRUE(module->reflection.keyword_sets.empty());
  }
  const fs::path main = folder.write("main.hlsl", std::string("#include_with_pragmas \"both.hlsl\"\n") + kPragmaFrag);
  auto module = compile_file(main, {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  EXPECT_EQ(module->diagnostics.warning_count(), 0u);
  EXPECT_EQ(module->reflection.active_keywords, (std::vector<std::string>{"LOW"}));
}

TEST(IncludeWithPragmas, IsFoundAndReportedAsIncludeIs) {
  PragmaFolder folder;
  const fs::path main = folder.write("main.hlsl",
                                     "#pragma fragment frag\n"
                                     "#include_with_pragmas\n"
                                     "#include_with_pragmas \"\"\n"
                                     "#include_with_pragmas \"missing.hlsl\" extra\n"
                                     "float4 frag() : SV_Target { return 1; }\n");
  auto module = compile_file(main, {});
  const std::vector<std::string> messages = pragma_messages(*module, main);
  ASSERT_EQ(messages.size(), 4u);
  EXPECT_EQ(messages[0], "main.hlsl:2:2: error: expected \"file\" or <file> after #include_with_pragmas");
  EXPECT_EQ(messages[1], "main.hlsl:3:23: error: empty file name in #include_with_pragmas");
  EXPECT_EQ(messages[2], "main.hlsl:4:38: warning: extra tokens at end of #include_with_pragmas directive");
  EXPECT_EQ(messages[3].rfind("main.hlsl:4:23: error: cannot find include file 'missing.hlsl' (searched: ", 0), 0u)
      << messages[3];
}

}  // namespace
}  // namespace xshade::hlsl
