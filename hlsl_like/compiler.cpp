#include "hlsl_like/compiler.h"

#include <algorithm>
#include <set>

#include "hlsl_like/keyword_pragmas.h"
#include "hlsl_like/parser.h"
#include "hlsl_like/prelude.h"

namespace xshade::hlsl {
namespace {

// Pragmas the front end reads; others are reported as unknown, since a misspelt `#pragma
// fragmnet` would otherwise silently drop a stage.
struct PragmaReading {
  EntryPointNames entry_points;
  std::vector<KeywordSet> keyword_sets;
  std::vector<Loc> keyword_set_locs;  // of each set's pragma name
};

// Unity's pragmas that say how Unity builds a shader (its target is read where a .shader is
// composed, as SHADER_TARGET) and change nothing of what a variant draws.
constexpr std::string_view kUnityBuildPragmas[] = {"target",
                                                   "require",
                                                   "only_renderers",
                                                   "exclude_renderers",
                                                   "hardware_tier_variants",
                                                   "enable_d3d11_debug_symbols",
                                                   "fragmentoption",
                                                   "glsl_no_auto_normalization",
                                                   "instancing_options",
                                                   "editor_sync_compilation",
                                                   "skip_optimizations",
                                                   "disable_fastmath",
                                                   "prefer_hlslcc",
                                                   "enable_cbuffer"};

PragmaReading read_pragmas(const std::vector<Pragma>& pragmas, DiagnosticEngine& diagnostics) {
  PragmaReading reading;
  std::vector<std::string> skipped;  // #pragma skip_variants
  for (const Pragma& pragma : pragmas) {
    if (pragma.name == "vertex" || pragma.name == "fragment") {
      const bool vertex = pragma.name == "vertex";
      std::string& name = vertex ? reading.entry_points.vertex : reading.entry_points.fragment;
      if (pragma.args.size() != 1 || pragma.args[0].kind != TokenKind::Identifier) {
        diagnostics.error(pragma.loc, "#pragma " + std::string(pragma.name) + " takes one function name");
        continue;
      }
      if (!name.empty()) {
        diagnostics.error(pragma.loc, "the " + std::string(pragma.name) + " entry point is already '" + name + "'");
        continue;
      }
      name = std::string(pragma.args[0].text);
      (vertex ? reading.entry_points.vertex_loc : reading.entry_points.fragment_loc) = pragma.args[0].loc;
    } else if (const auto kind = keyword_pragma(pragma.name)) {
      KeywordSet set;
      set.shader_feature = *kind == KeywordPragma::ShaderFeature;
      for (const Token& token : pragma.args) {
        if (token.kind != TokenKind::Identifier) {
          diagnostics.error(token.loc, "#pragma " + std::string(pragma.name) + " takes keyword names, not '" +
                                           std::string(token.text) + "'");
          continue;
        }
        set.keywords.emplace_back(token.text);
      }
      // shader_feature A alone means "A or nothing", as in Unity.
      if (set.shader_feature && set.keywords.size() == 1) set.keywords.insert(set.keywords.begin(), "_");
      if (!set.keywords.empty()) {
        reading.keyword_sets.push_back(std::move(set));
        reading.keyword_set_locs.push_back(pragma.loc);
      }
    } else if (auto shortcut = keyword_shortcut(pragma.name)) {
      for (KeywordSet& set : *shortcut) {
        reading.keyword_sets.push_back(std::move(set));
        reading.keyword_set_locs.push_back(pragma.loc);
      }
    } else if (pragma.name == "skip_variants") {
      for (const Token& token : pragma.args) skipped.emplace_back(token.text);
    } else if (pragma.name == "pass") {
      // A post effect's pass (pass_declarations.h), read once the variant's pragmas are final.
    } else if (pragma.name == "surface") {
      diagnostics.error(pragma.loc,
                        "#pragma surface makes a surface shader, whose passes Unity generates; xshade does "
                        "not generate them yet: write the pass's vertex and fragment functions");
    } else if (pragma.name == "geometry" || pragma.name == "hull" || pragma.name == "domain") {
      diagnostics.error(pragma.loc, "xshade compiles vertex and fragment stages; a " + std::string(pragma.name) +
                                        " stage cannot be compiled, and leaving it out would draw something else");
    } else if (pragma.name == "warning") {
      // fxc's and DXC's `#pragma warning(disable : 3205)` turns their own numbered warnings off;
      // xshade's warnings have no such numbers, so there is nothing to turn off or to say.
    } else if (pragma.name == "pack_matrix") {
      diagnostics.warning(pragma.loc, "#pragma " + std::string(pragma.name) + " is ignored");
    } else if (std::find(std::begin(kUnityBuildPragmas), std::end(kUnityBuildPragmas), pragma.name) ==
               std::end(kUnityBuildPragmas)) {
      diagnostics.warning(pragma.loc, "unknown pragma '" + std::string(pragma.name) + "'");
    }
  }
  // Unity compiles no variant with a skipped keyword: the keyword is no choice of its set (a set
  // left with none keeps its keywords, and a scene that asks for one gets what it asked).
  for (KeywordSet& set : reading.keyword_sets) {
    std::vector<std::string> kept;
    for (const std::string& keyword : set.keywords)
      if (std::find(skipped.begin(), skipped.end(), keyword) == skipped.end()) kept.push_back(keyword);
    if (!kept.empty()) set.keywords = std::move(kept);
  }
  return reading;
}

// The pragmas Unity (and xshade's `pass`) reads itself, which it ignores in a file read by a
// plain #include; the others (`warning`, `pack_matrix`) are HLSL's own and go to the compiler.
bool is_unity_pragma(std::string_view name) {
  constexpr std::string_view kStages[] = {"vertex", "fragment", "geometry",      "hull",
                                          "domain", "surface",  "skip_variants", "pass"};
  return std::find(std::begin(kStages), std::end(kStages), name) != std::end(kStages) ||
         std::find(std::begin(kUnityBuildPragmas), std::end(kUnityBuildPragmas), name) !=
             std::end(kUnityBuildPragmas) ||
         keyword_pragma(name) || keyword_shortcut(name);
}

// The pragmas that apply to the program, as Unity reads them: its own pragmas count only in the
// program and in files included by #include_with_pragmas; elsewhere each is reported and dropped,
// so that a multi_compile in a plain include does not silently declare keywords Unity would not.
std::vector<Pragma> program_pragmas(const std::vector<Pragma>& pragmas, DiagnosticEngine& diagnostics) {
  std::vector<Pragma> kept;
  kept.reserve(pragmas.size());
  for (const Pragma& pragma : pragmas) {
    if (pragma.in_program || !is_unity_pragma(pragma.name)) {
      kept.push_back(pragma);
      continue;
    }
    diagnostics.warning(pragma.loc,
                        "#pragma " + std::string(pragma.name) +
                            " is ignored: this file is read by a plain #include, and Unity takes its "
                            "pragmas only from the shader's program and the files it includes with "
                            "#include_with_pragmas; include this file with #include_with_pragmas to apply it");
  }
  return kept;
}

bool is_no_keyword(const std::string& keyword) {
  return !keyword.empty() && keyword.find_first_not_of('_') == std::string::npos;
}

// A variant has one keyword of each set: asking for two of one set is an error at the set's
// pragma, since either keyword alone would make a valid variant and the front end cannot choose.
void check_one_keyword_per_set(const PragmaReading& reading, const std::vector<std::string>& asked,
                               DiagnosticEngine& diagnostics) {
  for (size_t i = 0; i < reading.keyword_sets.size(); ++i) {
    const KeywordSet& set = reading.keyword_sets[i];
    std::vector<std::string> named;
    for (const std::string& keyword : asked)
      if (std::find(set.keywords.begin(), set.keywords.end(), keyword) != set.keywords.end() &&
          std::find(named.begin(), named.end(), keyword) == named.end())
        named.push_back(keyword);
    for (size_t k = 1; k < named.size(); ++k)
      diagnostics.error(reading.keyword_set_locs[i], "keywords '" + named[0] + "' and '" + named[k] +
                                                         "' are both of this #pragma " +
                                                         (set.shader_feature ? "shader_feature" : "multi_compile") +
                                                         " set; a variant can have only one keyword of each set");
  }
}

// The keywords of the variant: those asked for, plus the first keyword of each set none of them is in.
std::vector<std::string> active_keywords(const std::vector<KeywordSet>& sets, const std::vector<std::string>& asked) {
  std::vector<std::string> active = asked;
  for (const KeywordSet& set : sets) {
    const bool named = std::any_of(set.keywords.begin(), set.keywords.end(), [&](const std::string& k) {
      return std::find(asked.begin(), asked.end(), k) != asked.end();
    });
    if (!named && !is_no_keyword(set.keywords.front())) active.push_back(set.keywords.front());
  }
  return active;
}

std::unique_ptr<Module> compile(std::unique_ptr<Module> module, const CompileOptions& options) {
  module->include_dirs = options.include_dirs;
  auto preprocess = [&](const std::vector<std::string>& keywords) {
    PreprocessorOptions pp_options;
    pp_options.include_dirs = options.include_dirs;
    if (const auto& prelude = prelude_table(); prelude) {
      pp_options.predefined = *prelude;
    } else {
      module->diagnostics.error({}, prelude.error().message);
    }
    pp_options.defines.reserve(keywords.size() + options.defines.size());
    for (const std::string& keyword : keywords) pp_options.defines.push_back({keyword, "1"});
    pp_options.defines.insert(pp_options.defines.end(), options.defines.begin(), options.defines.end());
    module->macros = prelude_macros();
    module->macros.insert(module->macros.end(), pp_options.defines.begin(), pp_options.defines.end());
    module->preprocessor = std::make_unique<Preprocessor>(module->sources, module->diagnostics, std::move(pp_options));
    std::vector<Token> tokens = module->preprocessor->run(module->main_file);
    module->pragmas = program_pragmas(module->preprocessor->pragmas(), module->diagnostics);
    const std::set<std::string>& redefined = module->preprocessor->redefined_predefined();
    std::erase_if(module->macros, [&](const MacroDefinition& m) { return redefined.count(m.name) > 0; });
    return tokens;
  };

  std::vector<Token> tokens = preprocess(options.keywords);
  // Pragmas are read before the variant is known; a keyword set's default, if it was not asked
  // for, needs a second pass with it defined.
  PragmaReading reading = read_pragmas(module->pragmas, module->diagnostics);
  const std::vector<std::string> keywords = active_keywords(reading.keyword_sets, options.keywords);
  if (keywords.size() != options.keywords.size()) {
    module->diagnostics.clear();  // the second pass reports everything again
    tokens = preprocess(keywords);
    reading = read_pragmas(module->pragmas, module->diagnostics);
  }
  for (const std::string& keyword : options.keywords) {
    const bool declared =
        std::any_of(reading.keyword_sets.begin(), reading.keyword_sets.end(), [&](const KeywordSet& set) {
          return std::find(set.keywords.begin(), set.keywords.end(), keyword) != set.keywords.end();
        });
    if (!declared)
      module->diagnostics.warning(
          {module->main_file, 1, 1},
          "keyword '" + keyword + "' is not declared by #pragma multi_compile or shader_feature");
  }

  check_one_keyword_per_set(reading, options.keywords, module->diagnostics);
  module->passes = read_pass_declarations(module->pragmas, module->diagnostics);

  if (!options.fragment_only_entry.empty()) {
    reading.entry_points.vertex.clear();
    reading.entry_points.fragment = options.fragment_only_entry;
    reading.entry_points.fragment_loc = {module->main_file, 1, 1};
  } else if (options.fragment_only) {
    reading.entry_points.vertex.clear();
  } else if (!options.pass_fragment_entry.empty()) {
    reading.entry_points.fragment = options.pass_fragment_entry;
    reading.entry_points.fragment_loc = {module->main_file, 1, 1};
  }
  module->unit = parse(tokens, module->diagnostics);
  {
    AstArenaScope nodes(module->unit.arena);  // the nodes analysis adds join the tree's
    module->entry_points = analyze(module->unit, reading.entry_points, module->diagnostics);
  }
  if (!module->diagnostics.has_errors())
    module->resource_origins = resolve_resource_origins(module->entry_points, module->diagnostics);
  if (!module->diagnostics.has_errors())
    module->reflection = reflect(module->unit, module->entry_points, module->resource_origins, module->diagnostics);
  module->reflection.keyword_sets = std::move(reading.keyword_sets);
  module->reflection.active_keywords = keywords;
  return module;
}

}  // namespace

std::vector<std::filesystem::path> Module::dependencies() const {
  std::vector<std::filesystem::path> files;
  for (uint32_t i = 1; i < sources.file_count(); ++i)
    files.push_back(sources.path(i).empty() ? std::filesystem::path(sources.name(i)) : sources.path(i));
  return files;
}

std::unique_ptr<Module> compile_file(const std::filesystem::path& path, const CompileOptions& options) {
  auto module = std::make_unique<Module>();
  auto file = module->sources.load(path);
  if (!file) {
    module->diagnostics.error({}, file.error().message);
    return module;
  }
  module->main_file = *file;
  return compile(std::move(module), options);
}

std::unique_ptr<Module> compile_text(std::string name, std::string text, const CompileOptions& options) {
  auto module = std::make_unique<Module>();
  module->main_file = module->sources.add(std::move(name), std::move(text));
  return compile(std::move(module), options);
}

}  // namespace xshade::hlsl
