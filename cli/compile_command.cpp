// xshade compile: one shader through the front end to GLSL, SPIR-V or reflection.
#include <fmt/core.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <fstream>
#include <functional>
#include <memory>

#include <nlohmann/json.hpp>

#include "base/spelling.h"
#include "cli/commands.h"
#include "cli/compile_output.h"
#include "harness/render/material_source.h"
#include "harness/render/shader_program.h"
#include "harness/render/surface_program.h"
#include "hlsl_like/compiler.h"
#include "shaderlab/pass_program.h"
#include "shaderlab/reader.h"
#include "shaderlab/shader_json.h"

namespace xshade::cli {
namespace {

bool write_file(const std::filesystem::path& path, std::string_view bytes) {
  std::ofstream file(path, std::ios::binary);
  file.write(bytes.data(), std::streamsize(bytes.size()));
  return bool(file);
}

// Writes one stage's output to OUT.<stage><extension>, or to stdout under a header.
bool emit_stage(const CompileOptions& options, const char* stage, std::string_view text, bool binary,
                std::string_view binary_bytes = {}) {
  if (options.output.empty()) {
    fmt::print("// ---- {} ----\n{}", stage, text);
    return true;
  }
  const std::string extension = std::string(".") + stage + (binary ? ".spv" : ".glsl");
  const std::filesystem::path path = options.output.string() + extension;
  if (!write_file(path, binary ? binary_bytes : text)) {
    fmt::print(stderr, "xshade compile: cannot write {}\n", path.string());
    return false;
  }
  return true;
}

// A file with nothing to compile as it is (a post effect: #pragma pass, no #pragma fragment).
int no_stage(const hlsl::Module& module, const std::filesystem::path& file) {
  std::string passes;
  for (const hlsl::PassDeclaration& pass : module.passes) passes += (passes.empty() ? "" : ", ") + pass.name;
  if (!passes.empty())
    fmt::print(stderr,
               "xshade compile: {} is a post effect with no #pragma fragment: choose one of its passes ({}) "
               "with --pass NAME\n",
               file.string(), passes);
  else
    fmt::print(stderr, "xshade compile: {} has no entry point: give #pragma vertex/fragment, or --entry FUNCTION\n",
               file.string());
  return kBadInput;
}

// --all-variants compiles each combination, milliseconds to tens of them apiece: 2^14 is already
// minutes, and 40 `multi_compile _ KW` lines (2^40) once filled 8.5 GB listing them. Past this
// the count is refused before anything is listed or compiled.
constexpr uint64_t kMaxAllVariants = uint64_t(1) << 14;

std::string bracketed(const std::vector<std::string>& keywords) {
  std::string text = "[";
  for (size_t i = 0; i < keywords.size(); ++i) text += (i ? " " : "") + keywords[i];
  return text + "]";
}

// What run_compile does with the module of `compile(front_end)`: the target's output, every
// variant's status, or the reflection. `compile` compiles the file, or a .shader pass's text,
// with other options.
int compile_module(const CompileOptions& options, const std::filesystem::path& file,
                   const hlsl::CompileOptions& front_end,
                   const std::function<std::unique_ptr<hlsl::Module>(const hlsl::CompileOptions&)>& compile,
                   std::unique_ptr<hlsl::Module> module) {
  if (!module->diagnostics.diagnostics().empty()) fmt::print(stderr, "{}", module->diagnostics.render_all());
  if (!module->ok()) return kBadInput;
  const OutputOptions output_options{.target = *codegen::target_named(options.target),
                                     .half_emulation = options.precision == "half",
                                     .trace_nonfinite = options.trace_nonfinite};

  if (options.all_variants) {
    // Each combination compiled to the target as a lane would; a status line each, the errors in full.
    int worst = kPass;
    // A post effect without a pass chosen: every pass of every combination.
    std::vector<std::pair<std::string, std::string>> entries{{"", front_end.pass_fragment_entry}};
    if (module->reflection.fragment_entry.empty() && options.pass.empty() && options.entry.empty()) {
      entries.clear();
      for (const hlsl::PassDeclaration& pass : module->passes) entries.push_back({" pass " + pass.name, pass.entry});
    }
    const std::vector<hlsl::KeywordSet>& sets = module->reflection.keyword_sets;
    const uint64_t combinations = hlsl::keyword_combination_count(sets);
    if (combinations > kMaxAllVariants) {
      fmt::print(stderr,
                 "xshade compile: {}: --all-variants compiles at most {} keyword combinations, and the {} keyword sets "
                 "of this shader make more; compile the variants a scene uses (xshade run --plan lists them)\n",
                 file.string(), kMaxAllVariants, sets.size());
      return kBadInput;
    }
    for (uint64_t index = 0; index < combinations; ++index) {
      const std::vector<std::string> keywords = hlsl::keyword_combination(sets, index);
      for (const auto& [pass_label, pass_entry] : entries) {
        hlsl::CompileOptions variant = front_end;
        variant.keywords = keywords;
        variant.pass_fragment_entry = pass_entry;
        auto compiled = compile(variant);
        std::string failure;
        int code = kPass;
        if (!compiled->ok()) {
          failure = compiled->diagnostics.render_all();
          code = kBadInput;
        } else if (auto output = compile_output(*compiled, output_options); !output) {
          failure = output.error().to_string() + "\n";
          code = exit_code_of(output.error().kind);
        } else if (!output->vertex && !output->fragment) {
          failure = "the shader has no entry point (#pragma vertex or #pragma fragment)\n";
          code = kBadInput;
        }
        // An output a validator refused is xshade's failure, not the variant's (compile_output.h).
        fmt::print("{} {}{}: {}\n", file.string(), bracketed(keywords), pass_label,
                   code == kPass           ? "compiles"
                   : code == kBackendError ? "internal error: invalid output"
                                           : "does not compile");
        if (!failure.empty()) fmt::print(stderr, "{}", failure);
        worst = std::max(worst, code);
      }
    }
    fmt::print("{} keyword combinations{} for {}\n", combinations,
               entries.size() > 1 ? " x " + std::to_string(entries.size()) + " passes" : std::string(), options.target);
    return worst;
  }

  if (options.reflect) {
    const std::string json = hlsl::reflection_json(module->reflection) + "\n";
    if (options.output.empty())
      fmt::print("{}", json);
    else if (!write_file(options.output.string() + ".json", json))
      return kBackendError;
    return kPass;
  }

  // Every stage validated before any is written: an invalid output never leaves with exit 0.
  auto output = compile_output(*module, output_options);
  if (!output) {
    fmt::print(stderr, "{}\n", output.error().to_string());
    return exit_code_of(output.error().kind);
  }
  if (!output->vertex && !output->fragment) return no_stage(*module, file);
  for (const auto& [stage, written] : {std::pair{"vert", &output->vertex}, std::pair{"frag", &output->fragment}}) {
    if (!*written) continue;
    const std::vector<uint32_t>& words = (*written)->words;
    const std::string_view bytes(reinterpret_cast<const char*>(words.data()), words.size() * 4);
    // A SPIR-V target writes the module to a file and its disassembly to standard output.
    const bool binary = !words.empty() && !options.output.empty();
    if (!emit_stage(options, stage, (*written)->text, binary, bytes)) return kBackendError;
  }
  return kPass;
}

// A Unity .shader: each program pass of the SubShader it draws (or the one --pass names), its text
// composed as Unity composes it and compiled with the .shader's folder first among the include
// folders; several passes on standard output each under a header, or with -o OUT each in its own
// files, OUT.passN.vert and OUT.passN.frag.
int compile_unity_shader(const CompileOptions& options, const std::filesystem::path& file,
                         hlsl::CompileOptions front_end) {
  auto shader = shaderlab::read_shader_file(file);
  if (!shader) {
    fmt::print(stderr, "{}\n", shader.error().to_string());
    return kBadInput;
  }
  for (const Diagnostic& note : shader->notes) fmt::print(stderr, "{}\n", note.to_string());
  // main.cpp accepts only the platforms there are.
  const shaderlab::UnityPlatform platform =
      shaderlab::parse_unity_platform(options.unity_platform).value_or(shaderlab::UnityPlatform::GLCore);
  const shaderlab::SubShader* sub = shaderlab::drawn_subshader(*shader, platform);
  if (!sub) {
    fmt::print(stderr, "xshade compile: {}: '{}' {}\n", file.string(), shader->name,
               shaderlab::without_subshader(*shader, platform));
    return kBadInput;
  }
  // A surface shader's passes are generated (shaderlab/surface_shader.h).
  shaderlab::SubShader generated;
  if (sub->surface) {
    auto with_passes = harness::with_surface_passes(file, *sub, front_end, platform);
    if (!with_passes) {
      fmt::print(stderr, "{}\n", with_passes.error().to_string());
      return kBadInput;
    }
    generated = std::move(*with_passes);
    sub = &generated;
  }
  std::vector<const shaderlab::Pass*> passes;
  if (!options.pass.empty()) {
    auto chosen = shaderlab::find_pass_in(*sub, shader->name, options.pass);
    if (!chosen) {
      fmt::print(stderr, "xshade compile: {}: {}\n", file.string(), chosen.error().message);
      return kBadInput;
    }
    passes.push_back(*chosen);
  } else {
    for (const shaderlab::Pass& pass : sub->passes)
      if (pass.kind == shaderlab::PassKind::Program) passes.push_back(&pass);
  }
  if (passes.empty()) {
    fmt::print(stderr, "xshade compile: {}: the SubShader it draws has no pass with a program\n", file.string());
    return kBadInput;
  }
  // --reflect: one object, the Properties and each pass's reflection.
  std::string reflected_passes;
  int worst = kPass;
  for (const shaderlab::Pass* pass : passes) {
    auto program = shaderlab::pass_program(*sub, *pass);
    if (!program) {
      fmt::print(stderr, "{}\n", program.error().to_string());
      worst = std::max(worst, int(kBadInput));
      continue;
    }
    auto unity_options = harness::pass_compile_options(file, *program, front_end, platform);
    if (!unity_options) {
      fmt::print(stderr, "{}: {}\n", unity_options.error().where.to_string(), unity_options.error().message);
      worst = std::max(worst, int(kBadInput));
      continue;
    }
    if (options.generated) {
      // The text the pass compiles, as composed and generated, before Unity's defines.
      fmt::print("// ==== {} pass {}{} ====\n{}", file.string(), program->index,
                 pass->name.empty() ? "" : " \"" + pass->name + "\"", program->text);
      continue;
    }
    const auto compile = [&](const hlsl::CompileOptions& with) {
      return hlsl::compile_text(file.string(), program->text, with);
    };
    hlsl::CompileOptions pass_options = *unity_options;
    pass_options.pass_fragment_entry.clear();
    // The variant a material of the Properties' defaults draws: the keywords its [Toggle] and
    // [KeywordEnum] properties set, where the pass declares them and -D named none of their set.
    std::unique_ptr<hlsl::Module> first = compile(pass_options);
    if (!options.all_variants && first->ok()) {
      const std::vector<std::string> keywords =
          harness::with_inspector_keywords(shader->properties, first->reflection.keyword_sets, pass_options.keywords,
                                           [](const std::string&) -> std::optional<float> { return std::nullopt; });
      if (keywords != pass_options.keywords) {
        pass_options.keywords = keywords;
        first = compile(pass_options);
      }
    }
    if (options.reflect) {
      auto module = std::move(first);
      if (!module->diagnostics.diagnostics().empty()) fmt::print(stderr, "{}", module->diagnostics.render_all());
      if (!module->ok()) return kBadInput;
      reflected_passes +=
          fmt::format("{}{{\"index\": {}, \"name\": {}, \"reflection\": {}}}", reflected_passes.empty() ? "" : ", ",
                      program->index, nlohmann::json(pass->name).dump(), hlsl::reflection_json(module->reflection));
      continue;
    }
    // Several passes: each under a header on standard output, or in OUT.passN.<stage> files.
    CompileOptions pass_output = options;
    if (passes.size() > 1 && !options.output.empty())
      pass_output.output = options.output.string() + ".pass" + std::to_string(program->index);
    else if (options.output.empty() && (passes.size() > 1 || options.pass.empty()))
      fmt::print("// ==== {} pass {}{} ====\n", file.string(), program->index,
                 pass->name.empty() ? "" : " \"" + pass->name + "\"");
    worst = std::max(worst, compile_module(pass_output, file, pass_options, compile, std::move(first)));
  }
  if (options.reflect && worst == kPass) {
    const std::string json =
        nlohmann::json::parse(fmt::format("{{\"shader\": {}, \"properties\": {}, \"passes\": [{}]}}",
                                          nlohmann::json(shader->name).dump(), shaderlab::properties_json(*shader),
                                          reflected_passes))
            .dump(2) +
        "\n";
    if (options.output.empty())
      fmt::print("{}", json);
    else if (!write_file(options.output.string() + ".json", json))
      return kBackendError;
  }
  return worst;
}

}  // namespace

int run_compile(const CompileOptions& options) {
  // The include folders of a run here: -I, the project file's shader folders, xshade's library.
  auto folders = resolve_folders(options.folders, std::filesystem::current_path(), GoldenUse::None);
  if (!folders) {
    fmt::print(stderr, "xshade compile: {}\n", folders.error().to_string());
    return kBadInput;
  }
  hlsl::CompileOptions front_end;
  front_end.include_dirs = options.include_dirs;
  for (const std::filesystem::path& folder : folders->shaders.folders()) front_end.include_dirs.push_back(folder);
  // A file named as a scene names it ("materials/toon.hlsl") is found in the shader folders.
  std::filesystem::path file = options.file;
  std::error_code missing;
  if (!std::filesystem::exists(file, missing) && file.is_relative())
    if (auto found = folders->shaders.find(file.string())) file = *found;
  if (options.precision == "half") front_end.defines.push_back({harness::kHalfEmulationMacro, "1"});
  for (const std::string& define : options.defines) {
    const size_t equals = define.find('=');
    if (equals == std::string::npos)
      front_end.keywords.push_back(define);
    else
      front_end.defines.push_back({define.substr(0, equals), define.substr(equals + 1)});
  }
  front_end.fragment_only_entry = options.entry;
  if (!options.entry.empty() && !options.pass.empty()) {
    fmt::print(stderr, "xshade compile: --entry and --pass each choose the fragment function; give one\n");
    return kBadInput;
  }

  if (file.extension() == ".shader") return compile_unity_shader(options, file, front_end);
  auto module = hlsl::compile_file(file, front_end);
  if (!options.pass.empty() && module->ok()) {
    const auto& passes = module->passes;
    auto pass = std::find_if(passes.begin(), passes.end(),
                             [&](const hlsl::PassDeclaration& p) { return p.name == options.pass; });
    if (pass == passes.end()) {
      std::vector<std::string> names;
      for (const hlsl::PassDeclaration& p : passes) names.push_back(p.name);
      std::string list;
      for (const std::string& name : names) list += (list.empty() ? "" : ", ") + name;
      const auto near = nearest(options.pass, names);
      fmt::print(stderr, "xshade compile: {} declares no pass '{}'{} (its passes: {})\n", file.string(), options.pass,
                 near ? "; did you mean '" + *near + "'?" : std::string(), list.empty() ? "none" : list);
      return kBadInput;
    }
    front_end.pass_fragment_entry = pass->entry;
    module = hlsl::compile_file(file, front_end);
  }
  return compile_module(
      options, file, front_end, [&](const hlsl::CompileOptions& with) { return hlsl::compile_file(file, with); },
      std::move(module));
}

Verb add_compile_command(CLI::App& app) {
  auto options = std::make_shared<CompileOptions>();
  CLI::App* compile =
      app.add_subcommand("compile", "Compile one shader to GLSL (gl, vk), SPIR-V (spirv, vk-hlsl) or reflection");
  compile->footer(
      "Every output is validated before it is written: gl's GLSL by glslang as OpenGL GLSL 4.50 core, vk's as Vulkan "
      "GLSL, the SPIR-V of spirv and vk-hlsl by spirv-val. Exit 0: the output, valid. Exit 2: the shader is wrong, or "
      "the target cannot express it. Exit 3: a validator refused xshade's own output, an internal error: the output is "
      "not written, and the message gives the validator's words and the generated lines they name, for a bug report.");
  compile->add_option("file", options->file, "The hlsl_like source")->required()->type_name("FILE");
  compile->add_option("-I", options->include_dirs, "Search DIR for #include files")
      ->type_name("DIR")
      ->allow_extra_args(false);
  compile->add_option("-D", options->defines, "Enable KEYWORD (a variant), or define KEY=VALUE")
      ->type_name("KEYWORD")
      ->allow_extra_args(false);
  compile->add_option("--target", options->target, "gl, vk (GLSL text), spirv or vk-hlsl (SPIR-V)")
      ->check(CLI::IsMember({"gl", "vk", "spirv", "vk-hlsl"}))
      ->capture_default_str();
  compile
      ->add_option("--precision", options->precision,
                   "half: round every half/min16float/fixed result to fp16 (gl, vk, spirv; vk-hlsl cannot)")
      ->check(CLI::IsMember({"float", "half"}))
      ->capture_default_str();
  compile->add_flag("--trace-nonfinite", options->trace_nonfinite,
                    "Emit the fragment stage's tracing variant, which records where each pixel's first NaN or infinity "
                    "is born (gl, vk, spirv; docs/stability.md)");
  compile->add_flag("--reflect", options->reflect, "Print the reflection (JSON) instead of code");
  compile
      ->add_option(
          "--entry", options->entry,
          "Compile this fragment function as a full-screen pass (as eval runs it), whatever #pragma fragment says")
      ->type_name("FUNCTION");
  compile
      ->add_option("--pass", options->pass,
                   "Compile this post pass of the effect (its #pragma pass name), or this pass of a Unity .shader "
                   "(its index or Name; default: every pass with a program)")
      ->type_name("NAME");
  compile
      ->add_option("--unity-platform", options->unity_platform,
                   "Compile a Unity .shader for this platform, as a scene's [unity] platform does: glcore (default), "
                   "d3d11 or vulkan")
      ->check(CLI::IsMember({"glcore", "d3d11", "vulkan"}))
      ->type_name("PLATFORM");
  compile->add_flag("--generated", options->generated,
                    "Print each pass's HLSL as a Unity .shader composes it (its include blocks, and a surface shader's "
                    "generated passes, with #line back to the .shader's lines) instead of compiling it");
  compile->add_flag("--all-variants", options->all_variants,
                    "Compile every keyword combination the file declares for --target and report each; exit 2 if any "
                    "fails, 3 if any output is invalid (an internal error)");
  compile
      ->add_option("--shaders", options->folders.shaders,
                   "A shader folder to include from and find FILE in, before xshade's library; repeat for more "
                   "(default: the project file's)")
      ->type_name("DIR")
      ->allow_extra_args(false);
  compile->add_option("--project", options->folders.project, "The project file (default: xshade.toml here or above)")
      ->type_name("FILE");
  compile->add_flag("--no-project", options->folders.no_project, "Read no project file");
  compile
      ->add_option(
          "-o", options->output,
          "Write OUT.vert.glsl / OUT.frag.glsl (or .spv, or OUT.json) instead of standard output; each pass of a "
          ".shader to OUT.passN.vert.glsl / OUT.passN.frag.glsl")
      ->type_name("OUT");
  return {compile, [options](const std::string&) { return run_compile(*options); }};
}

}  // namespace xshade::cli
