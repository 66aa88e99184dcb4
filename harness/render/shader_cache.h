// A content-addressed cache of compiled shader variants on disk, so that a shader whose source,
// includes, keywords, target and compiler are all unchanged is never compiled again.
//
// Two levels, as ccache's direct mode: a request key (compiler identity, lane, source path,
// keywords, entry) names a manifest listing every file the compile read with a hash of its
// contents; when those hashes still match the files on disk, the manifest's result key names
// the stored program. Each file carries the hash of its contents, checked on every read: a
// damaged entry (a flipped bit, an edit, a torn write) is a miss, compiled again and rewritten,
// never a program that renders something else. Writes go to a temporary file with a unique name
// renamed into place, so an interrupted run never leaves a torn entry, and several runs (or
// worker processes) may share a cache and write the same entry at once.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "glsl/glsl_emitter.h"
#include "harness/backend/backend.h"
#include "harness/render/lanes.h"
#include "harness/render/planner.h"
#include "harness/render/shader_interface.h"

namespace xshade::harness {

// What a lane needs to draw with a variant.
struct CompiledVariant {
  ProgramDesc program;
  ShaderInterface interface;
  // A traced variant's sites and calls (VariantRequest::trace_nonfinite); traced variants are
  // never cached, so an entry never holds one.
  glsl::NonfiniteTrace trace = {};
};

struct CacheLookup {
  std::optional<CompiledVariant> variant;  // a hit
  // Set when an entry was there but its contents did not match their hash (or did not parse):
  // the lookup is a miss, and the caller says so once.
  std::optional<Error> damage = std::nullopt;
  // A hit's dependencies as its manifest lists them: every file the compile read.
  std::vector<std::filesystem::path> dependencies = {};
};

class ShaderCache {
 public:
  // `compiler_identity` must change whenever the compiler could produce different output (see
  // compiler_identity()).
  ShaderCache(std::filesystem::path directory, std::string compiler_identity);

  CacheLookup look_up(const VariantRequest& request, Lane lane) const;
  // look_up's variant alone.
  std::optional<CompiledVariant> find(const VariantRequest& request, Lane lane) const;
  // `dependencies`: every file the compile read (the source and its includes).
  Result<void> store(const VariantRequest& request, Lane lane, const CompiledVariant& variant,
                     const std::vector<std::filesystem::path>& dependencies) const;

  const std::filesystem::path& directory() const { return directory_; }

 private:
  std::string request_key(const VariantRequest& request, Lane lane) const;

  std::filesystem::path directory_;
  std::string compiler_identity_;
};

// A hash of the running xshade executable and the glslang it links: any rebuild of the
// compiler invalidates every entry.
std::string compiler_identity();

// 128-bit XXH3 of bytes, as 32 hex digits.
std::string content_hash(std::string_view bytes);

}  // namespace xshade::harness
