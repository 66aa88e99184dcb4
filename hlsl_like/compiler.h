// The front end as one call: preprocess, parse, analyse and reflect one variant of a shader.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "hlsl_like/ast.h"
#include "hlsl_like/diagnostic_engine.h"
#include "hlsl_like/pass_declarations.h"
#include "hlsl_like/preprocessor.h"
#include "hlsl_like/reflection.h"
#include "hlsl_like/sema.h"
#include "hlsl_like/source_manager.h"

namespace xshade::hlsl {

struct CompileOptions {
  std::vector<std::filesystem::path> include_dirs;
  // Keywords of the variant, each defined as 1. A keyword set of `#pragma multi_compile` or
  // `shader_feature` that none of these names gets its first keyword (unless that is `_`), as
  // Unity does.
  std::vector<std::string> keywords;
  std::vector<MacroDefinition> defines;  // -D KEY=VALUE
  // Compile only this fragment function, whatever the pragmas say, and no vertex stage: the
  // shader then runs as a full-screen pass (xshade eval).
  std::string fragment_only_entry;
  // With fragment_only_entry empty: #pragma fragment's function alone, no vertex stage.
  bool fragment_only = false;
  // Compile this fragment function in place of #pragma fragment's, with the vertex function of
  // #pragma vertex if the file names one: a post pass (#pragma pass), which draws through its
  // effect's own vertex shader where it has one (Unity's VertDefault) and else full-screen.
  std::string pass_fragment_entry;
};

// Everything the front end made of one variant. The tree, the reflection and the diagnostics
// refer to the sources held here, so the module is passed around whole.
struct Module {
  SourceManager sources;
  DiagnosticEngine diagnostics{sources};
  uint32_t main_file = 0;
  TranslationUnit unit;
  EntryPoints entry_points;
  Reflection reflection;
  ResourceOrigins resource_origins;     // which global or parameter each resource read is
  std::vector<Pragma> pragmas;          // those that apply: Unity's own only from the program (Pragma::in_program)
  std::vector<PassDeclaration> passes;  // a post effect's `#pragma pass` lines
  // The macros the variant was compiled with (prelude, keywords, defines), for other compilers
  // of the same source (glslang's HLSL front end on the vk-hlsl lane); a prelude macro the source
  // defines or undefines itself is left out, so that the other compiler sees the source's alone.
  std::vector<MacroDefinition> macros;
  std::vector<std::filesystem::path> include_dirs;  // as given to the compile
  // Tokens made by macros keep their text in the preprocessor, so it lives as long as the tree.
  std::unique_ptr<Preprocessor> preprocessor;

  bool ok() const { return !diagnostics.has_errors(); }
  // Every file the variant read: the main file and its includes.
  std::vector<std::filesystem::path> dependencies() const;
};

std::unique_ptr<Module> compile_file(const std::filesystem::path& path, const CompileOptions& options);
std::unique_ptr<Module> compile_text(std::string name, std::string text, const CompileOptions& options);

}  // namespace xshade::hlsl
