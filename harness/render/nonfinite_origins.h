// Where the non-finite pixels of a render were born: a traced render's record
// (glsl::NonfiniteTrace) read against the image it drew, site by site.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "glsl/glsl_emitter.h"
#include "harness/image/image.h"
#include "harness/render/scene_renderer.h"
#include "harness/render/shader_cache.h"

namespace xshade::harness {

// One site, reached through one chain of calls, and the output pixels it was the first
// non-finite value of.
struct NonfiniteOrigin {
  std::string pass;     // the pass whose program holds the site
  std::string program;  // that program's name (its source file)
  glsl::TraceSite site;
  std::vector<glsl::TraceCall> calls;  // the calls that led there, innermost first
  size_t pixels = 0;                   // output pixels with a NaN, Inf or negative channel
  size_t nan = 0;                      // their channel values, as the finite layer counts them
  size_t inf = 0;
  size_t negative = 0;
  uint32_t first_x = 0;  // the first such pixel in row order
  uint32_t first_y = 0;
};

struct NonfiniteOrigins {
  std::vector<NonfiniteOrigin> origins;  // most pixels first
  // Output pixels with a non-finite or negative channel and no site recorded: nothing the
  // tracing variant tests made them (a pass without a traced program, a cleared target).
  size_t unattributed_pixels = 0;
  // Pixels where a site failed but the output is finite: a NaN or infinity that a later step
  // (a min, a select, a saturate) took out again. Not counted in `origins`.
  size_t recovered_pixels = 0;
  // Each pixel of the output in its origin's colour (origins_palette), black where it is finite.
  FloatImage map;
};

// `output` is a pass's image of a traced render, `record` what that pass recorded, and
// `variants` the traced variants it drew with (the record's program number indexes them).
// Negative values count only with `count_negative` (a colour; an earlier pass's signed
// quantities, a circle of confusion, are meant to be negative). Fails when a record names a
// program or a site the variants do not have.
Result<NonfiniteOrigins> find_nonfinite_origins(const FloatImage& output, const PassTrace& record,
                                                const std::vector<CompiledVariant>& variants,
                                                bool count_negative = true);

// The colour of origin `index` in the map: hues apart by the golden angle, so that neighbours in
// the list differ most.
glm::vec4 origins_palette(size_t index);

// For a console: each origin (at most `rows`) with its counts, its first pixel, its source line
// with a caret under the column, and the calls that led there.
std::string describe_origins(const NonfiniteOrigins& origins, size_t rows = 8);

}  // namespace xshade::harness
