#include "harness/render/variant_compiler.h"

#include <algorithm>

#include "base/file_io.h"
#include "harness/render/material_source.h"
#include "harness/render/shader_program.h"

namespace xshade::harness {
namespace {

// The contents hash of `path`, or empty when it cannot be read (a file deleted since is changed).
std::string hash_of_file(const std::filesystem::path& path) {
  const std::optional<std::string> contents = read_file(path);
  return contents ? content_hash(*contents) : std::string();
}

}  // namespace

VariantCompiler::VariantCompiler(ShaderSearchPath shaders, const ShaderCache* cache)
    : shaders_(std::move(shaders)), cache_(cache) {}

bool VariantCompiler::in_cache(const VariantRequest& request, Lane lane) const {
  return cache_ && cache_->find(request, lane).has_value();
}

Result<const hlsl::Module*> VariantCompiler::front_end(const VariantRequest& request) {
  const std::string key = request.source.string() + "\n" + request.label();
  auto known = modules_.find(key);
  files_read_.insert(request.source);
  if (known != modules_.end() &&
      std::any_of(known->second.read.begin(), known->second.read.end(),
                  [](const auto& file) { return hash_of_file(file.first) != file.second; })) {
    modules_.erase(known);
    known = modules_.end();
  }
  if (known == modules_.end()) {
    hlsl::CompileOptions options;
    options.include_dirs = shaders_.folders();
    options.keywords = request.keywords;
    options.pass_fragment_entry = request.fragment_entry;
    if (request.half_emulation) options.defines.push_back({kHalfEmulationMacro, "1"});
    auto source = compile_source(request.source, options, request.shader_pass, request.unity_platform);
    if (!source) return fail(source.error());
    KeptModule kept{std::move(source->module), {}};
    // The hash of each file as the front end read it (its text is in the module): exactly what
    // this module was made from, with no second read.
    const hlsl::SourceManager& sources = kept.module->sources;
    for (uint32_t file = 1; file < sources.file_count(); ++file)
      if (!sources.path(file).empty()) kept.read.emplace_back(sources.path(file), content_hash(sources.text(file)));
    known = modules_.emplace(key, std::move(kept)).first;
  }
  for (const auto& file : known->second.read) files_read_.insert(file.first);
  const hlsl::Module& module = *known->second.module;
  if (!module.ok()) {
    return fail(Error{request.label() + " does not compile",
                      {request.source.string(), 0, 0},
                      module.diagnostics.errors_with_excerpts()});
  }
  return &module;
}

Result<CompiledVariant> VariantCompiler::compile(const VariantRequest& request, Lane lane) {
  // A traced variant is made only where a render failed or was asked for: not worth a cache
  // entry, and its sites would have to be stored with it.
  const bool cached = cache_ && !request.trace_nonfinite;
  if (cached) {
    CacheLookup found = cache_->look_up(request, lane);
    if (found.variant) {
      ++cached_;
      files_read_.insert(request.source);
      files_read_.insert(found.dependencies.begin(), found.dependencies.end());
      return std::move(*found.variant);
    }
    // Compiled and stored again below, which repairs the entry.
    if (found.damage && !cache_damage_) cache_damage_ = std::move(found.damage);
  }
  auto module = front_end(request);
  if (!module) return fail(module.error());
  glsl::NonfiniteTrace trace;
  auto program = program_for_lane(**module, lane,
                                  {.half_emulation = request.half_emulation,
                                   .trace_nonfinite = request.trace_nonfinite,
                                   .trace_program = request.trace_program,
                                   .filter_comparisons = request.filtered_comparison,
                                   .specialization = request.specialization},
                                  &trace);
  if (!program) return fail(program.error());
  CompiledVariant variant{std::move(*program), shader_interface((*module)->reflection), std::move(trace)};
  ++compiled_;
  if (cached) {
    if (auto stored = cache_->store(request, lane, variant, (*module)->dependencies()); !stored && !cache_write_error_)
      cache_write_error_ = stored.error();
  }
  return variant;
}

Result<std::vector<CompiledVariant>> VariantCompiler::compile_plan(const Plan& plan, Lane lane, bool half_emulation,
                                                                   bool trace_nonfinite) {
  if (trace_nonfinite && plan.variants.size() > glsl::NonfiniteTrace::kMaxPrograms)
    return fail(ErrorKind::UserInput, "the tracing variant numbers at most " +
                                          std::to_string(glsl::NonfiniteTrace::kMaxPrograms) +
                                          " programs in a scene; this one has " + std::to_string(plan.variants.size()));
  std::vector<CompiledVariant> variants;
  for (VariantRequest request : plan.variants) {
    request.half_emulation = half_emulation;
    request.trace_nonfinite = trace_nonfinite;
    request.trace_program = uint32_t(variants.size());
    auto compiled = compile(request, lane);
    if (!compiled) return fail(compiled.error());
    variants.push_back(std::move(*compiled));
  }
  return variants;
}

}  // namespace xshade::harness
