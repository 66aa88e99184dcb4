// SHADERS.md section 5, cases 13 to 15: the depth of field (post/depth_of_field.hlsl) run as the
// library has it, all five passes, on synthetic colour and depth images
// (harness::render_post_effects). C++ makes the images and computes the expected values and the
// metrics; every number of the effect comes from the shader.
//
// One camera and focus for every case: near 1, far 3, focus distance 2, focus range 0.5, bokeh
// radius 4. Depth 0.75 is then exactly in focus (3 / (3 - 2 * 0.75) = 2, exact in float), depth 0
// and 1 lie beyond the range on either side (coc -4 and +4), and 1 is the far plane, so a depth
// image of 1 blurs everything by the full radius.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "harness/image/image_compare.h"
#include "harness/render/nonfinite_origins.h"
#include "harness/render/planner.h"
#include "harness/render/scene_renderer.h"
#include "stability/cases.h"
#include "stability/forms.h"
#include "stability/probe.h"

namespace xshade::stability {
namespace {

using harness::FloatImage;

constexpr float kNear = 1.0f;
constexpr float kFar = 3.0f;
constexpr float kFocusDistance = 2.0f;
constexpr float kFocusRange = 0.5f;
constexpr float kBokehRadius = 4.0f;
constexpr float kInFocusDepth = 0.75f;

struct Kernel {
  std::string keyword;
  std::string label;  // "16 samples"
};
const std::vector<Kernel> kSampledKernels = {{"_KERNEL_SMALL", "16 samples"},
                                             {"_KERNEL_MEDIUM", "22 samples"},
                                             {"_KERNEL_LARGE", "43 samples"},
                                             {"_KERNEL_VERY_LARGE", "71 samples"}};
// Every texel offset within the radius 4: the 49 integer points of x^2 + y^2 <= 16.
const Kernel kDenseKernel{"_KERNEL_DENSE", "dense (49 samples)"};
// For the tests whose result no kernel decides (the CoC, zero weights, image sizes): 43 samples,
// because llvmpipe compiles the 16- and 22-sample bokeh loops unrolled, which under fp16
// emulation takes it 2 to 3 s per program against 0.2 s for 43.
const Kernel kAnyKernel{"_KERNEL_LARGE", "43 samples"};

// How far a lit half-resolution texel h reaches in the output, per axis, in full-resolution
// pixels. The bokeh's samples lie within the radius R (texels of the half-resolution source)
// and a bilinear sample at offset o reads only the texels less than one texel from it (up to the
// rounding of its uv: see kLit), so texel
// h reaches bokeh texels h - R .. h + R; the tent adds one texel (h - R - 1 .. h + R + 1); the
// combine's bilinear upsample reads half-resolution texel q at full-resolution pixels 2q - 1 ..
// 2q + 2. Together: pixels 2h - 2R - 3 .. 2h + 2R + 4. A bright pixel at 2h or 2h + 1 therefore
// lights nothing farther than 2R + 4 pixels from it; a 2x2 block (pixels 2h and 2h + 1) nothing
// farther than 2R + 3 from its nearest pixel.
constexpr int kPixelSpread = 2 * int(kBokehRadius) + 4;
constexpr int kBlockSpread = 2 * int(kBokehRadius) + 3;

// A constant image's mean over any set of its pixels is the constant; what a lane adds is
// rounding. fp32: each of the five passes rounds a mean of at most 71 equal values a few ulps
// (6e-8 each) away; 1e-5 relative covers 71 such roundings. fp16 emulation rounds each half
// result to 11 bits (2^-11 = 4.9e-4 relative) in every pass; five passes: 5 x 4.9e-4 = 2.5e-3.
double constant_tolerance(Precision precision) { return precision == Precision::Float ? 1e-5 : 2.5e-3; }
const std::string kConstantBound = "<= 1e-5 relative in fp32, 2.5e-3 in fp16 (rounding of means of equal values)";

// 1/255: one 8-bit step, SHADERS.md's bound for "output = source".
constexpr double kOneStep = 1.0 / 255.0;

struct DofSettings {
  std::string kernel = kAnyKernel.keyword;
  float focus_range = kFocusRange;
  bool keep_coc = false;  // read back the coc pass's image too
};

struct DofImages {
  FloatImage output;
  FloatImage coc;  // the coc pass's output: the signed circle of confusion in pixels, in red
};

// When the effect's output has NaN or infinities: the effect again, traced, and the first pass whose
// image has them names where most of them were born, for every non-finite measurement of the run
// (context.born_at["*"]). The output's own site is often a texture read of an earlier pass's NaN.
Result<void> name_where_born(const CaseContext& context, const harness::Scene& scene, const harness::Plan& plan,
                             const FloatImage& color, const FloatImage& depth) {
  if (context.lane == harness::Lane::VkHlsl || context.born_at.contains("*")) return {};
  auto variants = context.compiler.compile_plan(plan, context.lane, context.precision == Precision::Half,
                                                /*trace_nonfinite=*/true);
  if (!variants) return fail(variants.error());
  auto traced = harness::render_post_effects(context.backend, scene, plan, *variants, color, depth,
                                             {.keep_pass_images = true, .trace_nonfinite = true});
  if (!traced) return fail(traced.error());
  auto born = first_born_at(*traced, *variants);
  if (!born) return fail(born.error());
  if (!born->empty()) context.born_at["*"] = std::move(*born);
  return {};
}

// The depth of field in the context's form, lane and precision over `color` and `depth` (the
// depth-buffer value in red). The scene has no objects: the effect is its whole plan. `programs`
// keeps the passes' programs for the case's next renders on the same backend.
Result<DofImages> run_depth_of_field(const CaseContext& context, harness::ProgramCache& programs,
                                     const DofSettings& settings, const FloatImage& color, const FloatImage& depth) {
  harness::Scene scene;
  scene.name = "stability_depth_of_field";
  scene.width = color.width;
  scene.height = color.height;
  scene.camera.position = {0.0f, 0.0f, 0.0f};
  scene.camera.target = {0.0f, 0.0f, -1.0f};
  scene.camera.fov_y_degrees = 60.0f;
  scene.camera.near_plane = kNear;
  scene.camera.far_plane = kFar;
  std::vector<std::string> keywords = context.form.keywords;
  keywords.push_back(settings.kernel);
  scene.post = {{"post/depth_of_field.hlsl",
                 keywords,
                 {{"_FocusDistance", harness::PropertyValue::scalar(kFocusDistance)},
                  {"_FocusRange", harness::PropertyValue::scalar(settings.focus_range)},
                  {"_BokehRadius", harness::PropertyValue::scalar(kBokehRadius)}},
                 {},
                 {},
                 {}}};
  auto plan = harness::plan_scene(scene, context.shaders_dir);
  if (!plan) return fail(plan.error());
  auto variants = context.compiler.compile_plan(*plan, context.lane, context.precision == Precision::Half);
  if (!variants) return fail(variants.error());
  auto rendered = harness::render_post_effects(context.backend, scene, *plan, *variants, color, depth,
                                               {.keep_pass_images = settings.keep_coc, .programs = &programs});
  if (!rendered) return fail(rendered.error());
  if (const harness::NonFiniteCount bad = harness::count_non_finite(rendered->image); bad.nan + bad.inf > 0)
    if (auto named = name_where_born(context, scene, *plan, color, depth); !named) return fail(named.error());
  DofImages images{std::move(rendered->image), {}};
  if (settings.keep_coc) {
    auto coc = std::find_if(rendered->pass_images.begin(), rendered->pass_images.end(),
                            [](const auto& pass) { return pass.first == "depth_of_field.coc"; });
    if (coc == rendered->pass_images.end())
      return fail(ErrorKind::UserInput, "the depth of field ran no pass named 'coc'");
    images.coc = std::move(coc->second);
  }
  return images;
}

FloatImage image_of(uint32_t width, uint32_t height, const std::function<glm::vec4(uint32_t, uint32_t)>& pixel) {
  FloatImage image(width, height);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) image.set(x, y, pixel(x, y));
  return image;
}

FloatImage filled(uint32_t width, uint32_t height, glm::vec4 value) {
  return image_of(width, height, [value](uint32_t, uint32_t) { return value; });
}

// A depth image: the depth-buffer value in red.
FloatImage depth_of(uint32_t width, uint32_t height, const std::function<float(uint32_t, uint32_t)>& depth) {
  return image_of(width, height, [&depth](uint32_t x, uint32_t y) { return glm::vec4(depth(x, y), 0.0f, 0.0f, 1.0f); });
}

// A texture with detail at every scale: each channel of each pixel a hash of (x, y, channel),
// uniform in [0, 1).
float noise(uint32_t x, uint32_t y, uint32_t channel) {
  uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ channel * 0xcb1ab31fu;
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return float(h >> 8) / float(1u << 24);
}
FloatImage noise_image(uint32_t width, uint32_t height) {
  return image_of(width, height, [](uint32_t x, uint32_t y) {
    return glm::vec4(noise(x, y, 0), noise(x, y, 1), noise(x, y, 2), 1.0f);
  });
}

bool finite(glm::vec4 v) {
  return std::isfinite(v.r) && std::isfinite(v.g) && std::isfinite(v.b) && std::isfinite(v.a);
}

double non_finite_pixels(const FloatImage& image) {
  size_t count = 0;
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x) count += finite(image.at(x, y)) ? 0 : 1;
  return double(count);
}

// The largest |a - b| over the colour channels of the pixels `where` selects; NaN as soon as one
// of them is not finite (so that the bound fails).
double largest_difference(const FloatImage& a, const FloatImage& b,
                          const std::function<bool(uint32_t, uint32_t)>& where) {
  double worst = 0.0;
  for (uint32_t y = 0; y < a.height; ++y)
    for (uint32_t x = 0; x < a.width; ++x) {
      if (!where(x, y)) continue;
      const glm::vec4 d = a.at(x, y) - b.at(x, y);
      for (int c = 0; c < 3; ++c) {
        if (!std::isfinite(d[c])) return std::nan("");
        worst = std::max(worst, double(std::abs(d[c])));
      }
    }
  return worst;
}

// The largest relative difference of the colour channels from `constant` over the pixels `where`
// selects; NaN as soon as one is not finite.
double largest_relative_difference(const FloatImage& image, glm::vec4 constant,
                                   const std::function<bool(uint32_t, uint32_t)>& where) {
  double worst = 0.0;
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x) {
      if (!where(x, y)) continue;
      const glm::vec4 v = image.at(x, y);
      for (int c = 0; c < 3; ++c) {
        if (!std::isfinite(v[c])) return std::nan("");
        worst = std::max(worst, std::abs(double(v[c]) - constant[c]) / constant[c]);
      }
    }
  return worst;
}

// Root-mean-square difference of the colour channels over rows [row_begin, row_end).
double rmse(const FloatImage& a, const FloatImage& b, uint32_t row_begin, uint32_t row_end) {
  double sum = 0.0;
  size_t count = 0;
  for (uint32_t y = row_begin; y < row_end; ++y)
    for (uint32_t x = 0; x < a.width; ++x) {
      const glm::vec4 d = a.at(x, y) - b.at(x, y);
      sum += double(d.r) * d.r + double(d.g) * d.g + double(d.b) * d.b;
      count += 3;
    }
  return std::sqrt(sum / double(count));
}

// ---- 5.13 -------------------------------------------------------------------------------------

// The CoC ramp: column x has depth min(x, 80) / 80, so depth runs from 0 to 1 in steps of 1/80
// and column 60 is exactly in focus. The colour is a checkerboard of single pixels, 0.2 and 0.8:
// an in-focus pixel whose neighbours differ from it, where any blur shows.
constexpr uint32_t kRampWidth = 82;
constexpr uint32_t kRampHeight = 8;
constexpr uint32_t kFocusColumn = 60;
float ramp_depth(uint32_t x) { return float(std::min(x, 80u)) / 80.0f; }
FloatImage checkerboard(uint32_t width, uint32_t height) {
  return image_of(width, height, [](uint32_t x, uint32_t y) {
    const float v = (x + y) % 2 ? 0.8f : 0.2f;
    return glm::vec4(v, v, v, 1.0f);
  });
}

// The value of column x of the coc image farthest from `expected` (its rows should agree).
double column_value(const FloatImage& coc, uint32_t x, double expected) {
  double worst = expected;
  for (uint32_t y = 0; y < coc.height; ++y) {
    const double v = coc.at(x, y).r;
    if (!std::isfinite(v)) return v;
    if (std::abs(v - expected) > std::abs(worst - expected)) worst = v;
  }
  return worst;
}

const std::string kRampInput =
    "depth min(x, 80) / 80 across 82x8 (0 to 1 in steps of 1/80), 0.2/0.8 checkerboard, " + kAnyKernel.label;
const std::string kFocusCocInput = "depth 0.75 (column 60 of the ramp)";
// In focus at and left of column 60, behind the focus right of it: nothing in front of the focus
// blurs over the in-focus pixels (foreground blur does, by design, where there is foreground).
const std::string kFocusInput =
    "depth 0.75 up to column 60, the ramp behind it, 0.2/0.8 checkerboard, column 60, " + kAnyKernel.label;
const std::string kRangeZeroFocusInput = "focus range 0, depth 0.75 (column 60 of the ramp)";
const std::string kRangeZeroRampInput = "focus range 0, " + kRampInput;
const std::string kAllInFocusInput = "every pixel at depth 0.75 (coc = 0), 82x8, colour 0.5, " + kAnyKernel.label;

Case coc_case() {
  Case c;
  c.id = "coc";
  c.title =
      "CoC: in focus at depth = focus distance, monotone in depth, +-bokeh radius at depth 0 and 1, finite "
      "at focus range 0 (near 1, far 3, focus 2, range 0.5, radius 4)";
  c.section = "5.13";
  c.forms = {kSeed, kGuardedOnly};
  c.run = [](const CaseContext& context) -> Result<std::vector<Measurement>> {
    harness::ProgramCache& programs = context.programs;
    std::vector<Measurement> m;
    const FloatImage color = checkerboard(kRampWidth, kRampHeight);
    const FloatImage depth = depth_of(kRampWidth, kRampHeight, [](uint32_t x, uint32_t) { return ramp_depth(x); });

    auto ramp = run_depth_of_field(context, programs, {.keep_coc = true}, color, depth);
    if (!ramp) return fail(ramp.error());
    const double focus_coc = column_value(ramp->coc, kFocusColumn, 0.0);
    m.push_back({kFocusCocInput, "coc (pixels)", focus_coc,
                 "= 0: linear depth 3 / (3 - 2 x 0.75) = 2 = the focus distance, exact in float", focus_coc == 0.0});
    const FloatImage behind_focus =
        depth_of(kRampWidth, kRampHeight, [](uint32_t x, uint32_t) { return std::max(ramp_depth(x), kInFocusDepth); });
    auto focused_edge = run_depth_of_field(context, programs, {}, color, behind_focus);
    if (!focused_edge) return fail(focused_edge.error());
    const double focus_error =
        largest_difference(focused_edge->output, color, [](uint32_t x, uint32_t) { return x == kFocusColumn; });
    m.push_back(
        {kFocusInput, "largest |output - source|", focus_error, "<= 1/255 (one 8-bit step)", focus_error <= kOneStep});
    // The largest drop of the coc from one column (depth) to the next, over every row.
    double drop = 0.0;
    for (uint32_t y = 0; y < kRampHeight; ++y)
      for (uint32_t x = 0; x + 1 < kRampWidth; ++x) {
        const double step = double(ramp->coc.at(x, y).r) - ramp->coc.at(x + 1, y).r;
        if (!(step <= drop)) drop = step;  // NaN included
      }
    m.push_back({kRampInput, "largest decrease of coc from one depth to the next", drop,
                 "<= 0 (non-decreasing in depth)", drop <= 0.0});
    const double near_coc = column_value(ramp->coc, 0, -kBokehRadius);
    m.push_back({"depth 0 (column 0 of the ramp)", "coc (pixels)", near_coc, "= -4 (-bokeh radius)",
                 near_coc == -kBokehRadius});
    const double far_coc = column_value(ramp->coc, 80, kBokehRadius);
    m.push_back(
        {"depth 1 (column 80 of the ramp)", "coc (pixels)", far_coc, "= +4 (+bokeh radius)", far_coc == kBokehRadius});

    // Focus range 0 (hazard 10): coc = (d - focus) / 0, +-inf off the focus and 0/0 on it.
    auto sharp = run_depth_of_field(context, programs, {.focus_range = 0.0f, .keep_coc = true}, color, depth);
    if (!sharp) return fail(sharp.error());
    const double sharp_focus_coc = column_value(sharp->coc, kFocusColumn, 0.0);
    m.push_back({kRangeZeroFocusInput, "coc (pixels)", sharp_focus_coc,
                 "= 0: the point at the focus distance stays in focus however thin the range", sharp_focus_coc == 0.0});
    double largest_coc = 0.0;
    for (uint32_t y = 0; y < kRampHeight; ++y)
      for (uint32_t x = 0; x < kRampWidth; ++x) {
        const double v = std::abs(double(sharp->coc.at(x, y).r));
        if (x != kFocusColumn && !(v <= largest_coc)) largest_coc = v;
      }
    m.push_back({kRangeZeroRampInput + ", every column but 60", "largest |coc| (pixels)", largest_coc,
                 "<= 4: +-inf clamped to +-bokeh radius", largest_coc <= kBokehRadius});
    const double bad = non_finite_pixels(sharp->output);
    m.push_back({kRangeZeroRampInput, "non-finite output pixels", bad, "= 0", bad == 0.0});

    // Everything in focus: coc = 0 at every pixel.
    const glm::vec4 grey(0.5f, 0.5f, 0.5f, 1.0f);
    const FloatImage flat = filled(kRampWidth, kRampHeight, grey);
    auto focused = run_depth_of_field(context, programs, {}, flat,
                                      filled(kRampWidth, kRampHeight, glm::vec4(kInFocusDepth, 0.0f, 0.0f, 1.0f)));
    if (!focused) return fail(focused.error());
    const double focused_error = largest_difference(focused->output, flat, [](uint32_t, uint32_t) { return true; });
    m.push_back({kAllInFocusInput, "largest |output - source|", focused_error, "<= 1/255 (one 8-bit step)",
                 focused_error <= kOneStep});
    return m;
  };
  c.predict = [](const Form& form, Precision) {
    Prediction p;
    if (form.seed) {
      p.failing_inputs = {kFocusInput, kAllInFocusInput, kRangeZeroFocusInput};
      p.note =
          "In focus the seed's output is not the source: the combine blends the bokeh over the source by its "
          "foreground coverage dof.a even where coc = 0, and the seed's bokeh counts in-focus samples as foreground "
          "(bokeh_weight(-0, r) = saturate((2 - r) / 2): 1 for the pixel's own sample, 0.27 for the 43-sample "
          "kernel's inner ring at 1.45 px), so dof.a = (1 + 7 x 0.27) pi / 43 = 0.21 where everything is in focus. "
          "An in-focus pixel gets a fifth of its blurred neighbourhood: 0.12 off on the checkerboard (the "
          "catlikecoding tutorial's combine does the same; the guarded form cuts in-focus samples from the "
          "foreground, as Unity PPv2 does). "
          "Everything in focus: every prefilter weight is |coc| / (1 + brightness) = 0 and the seed divides 0 by 0 "
          "(hazard 10): NaN everywhere. Focus range 0: SHADERS.md predicts coc = 0/0 = NaN at the focus distance; "
          "0/0 is NaN there, but on llvmpipe and lavapipe max and min return the operand that is not NaN "
          "(max(NaN, -1) = -1, min(NaN, 1) = 1 on every lane), so the clamp, max then min, turns it into the lower "
          "bound: the in-focus pixel gets coc = -4, the largest foreground blur, finite but wrong. Off the focus, "
          "+-inf is clamped to +-4 as predicted.";
    }
    return p;
  };
  return c;
}

// ---- 5.14 -------------------------------------------------------------------------------------

// One image per kernel, three parts far enough apart that none reaches another (each reaches at
// most kPixelSpread = 12 pixels): a constant block over x < 40, one bright pixel at (72, 16) and
// a 2x2 bright block at (72, 48) (one half-resolution texel) on black. Depth 1 everywhere:
// coc = +4, the whole radius.
constexpr uint32_t kEnergyWidth = 96;
constexpr uint32_t kEnergyHeight = 80;
constexpr uint32_t kConstantEnd = 40;  // the constant part: x < 40
const glm::vec4 kConstant(0.75f, 0.5f, 0.25f, 1.0f);
constexpr uint32_t kPixelX = 72, kPixelY = 16;
constexpr uint32_t kBlockX = 72, kBlockY = 48;
// The parts' windows: the pixel's is x >= 56, y < 32, the block's x >= 56, y >= 32; each holds
// its part's reach (12 pixels) with room to see a wider spread.
constexpr uint32_t kWindowX = 56, kWindowSplitY = 32;

FloatImage energy_image() {
  return image_of(kEnergyWidth, kEnergyHeight, [](uint32_t x, uint32_t y) {
    if (x < kConstantEnd) return kConstant;
    const bool pixel = x == kPixelX && y == kPixelY;
    const bool block = x >= kBlockX && x < kBlockX + 2 && y >= kBlockY && y < kBlockY + 2;
    return pixel || block ? glm::vec4(1.0f) : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  });
}

// A pixel counts as lit above 1e-6 (the spot is 1). A sample aimed exactly R texels along an axis
// lands on a texel centre only up to the fp32 rounding of its interpolated uv, and gives the next
// texel a weight of that order (1e-10 measured, 14 pixels out); 1e-6 is far above such ghosts
// and far below one 8-bit step (3.9e-3).
constexpr float kLit = 1e-6f;

struct Spot {
  double energy_ratio;  // output energy / input energy (the sum of r, g and b)
  double spread;        // the farthest lit output pixel from the spot, Chebyshev distance in pixels
};

// The spot [x0, x1) x [y0, y1) of value 1 within the window [kWindowX, width) x [wy0, wy1).
Spot measure_spot(const FloatImage& output, uint32_t x0, uint32_t x1, uint32_t y0, uint32_t y1, uint32_t wy0,
                  uint32_t wy1) {
  double energy = 0.0;
  int spread = 0;
  for (uint32_t y = wy0; y < wy1; ++y)
    for (uint32_t x = kWindowX; x < output.width; ++x) {
      const glm::vec4 v = output.at(x, y);
      const double sum = double(v.r) + v.g + v.b;
      if (!std::isfinite(sum)) return {std::nan(""), std::nan("")};
      energy += sum;
      if (std::max({v.r, v.g, v.b}) > kLit) {
        const int dx = x < x0 ? int(x0 - x) : x >= x1 ? int(x - x1 + 1) : 0;
        const int dy = y < y0 ? int(y0 - y) : y >= y1 ? int(y - y1 + 1) : 0;
        spread = std::max({spread, dx, dy});
      }
    }
  return {energy / (3.0 * (x1 - x0) * (y1 - y0)), double(spread)};
}

// 2%: SHADERS.md's bound. With every weight 1 (coc = +4 reaches every sample) the bokeh is a mean
// and the tent and the bilinear upsample are partitions of unity, so the energy is kept up to
// rounding.
constexpr double kEnergyTolerance = 0.02;

std::string pixel_input(const Kernel& kernel) {
  return fmt::format("one pixel of 1 at ({}, {}) on black, depth 1 (coc = +4), {}", kPixelX, kPixelY, kernel.label);
}
std::string block_input(const Kernel& kernel) {
  return fmt::format("2x2 pixels of 1 at ({}, {}) on black (one half-resolution texel), depth 1, {}", kBlockX, kBlockY,
                     kernel.label);
}
std::string constant_input(const Kernel& kernel) {
  return fmt::format("constant (0.75, 0.5, 0.25) over x < 40 of 96x80, depth 1, {}", kernel.label);
}
const std::string kZeroWeightsInput =
    "every pixel at depth 0.75 (coc = 0: every prefilter weight 0), 96x80, colour 0.5, " + kAnyKernel.label;

Case constant_and_energy_case() {
  Case c;
  c.id = "dof_constant_and_energy";
  c.title =
      "DoF, 16, 22, 43 and 71 samples: a constant image is unchanged; a bright pixel keeps its energy within 2% and "
      "spreads no further than the bokeh radius; all-zero prefilter weights give no NaN";
  c.section = "5.14";
  c.forms = {kSeed, kGuardedOnly};
  c.run = [](const CaseContext& context) -> Result<std::vector<Measurement>> {
    harness::ProgramCache& programs = context.programs;
    std::vector<Measurement> m;
    const FloatImage color = energy_image();
    const FloatImage far = filled(kEnergyWidth, kEnergyHeight, glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
    const double tolerance = constant_tolerance(context.precision);
    for (const Kernel& kernel : kSampledKernels) {
      auto dof = run_depth_of_field(context, programs, {.kernel = kernel.keyword}, color, far);
      if (!dof) return fail(dof.error());
      // The constant part's pixels that nothing else reaches: 12 pixels or more from x = 40.
      const double constant_error = largest_relative_difference(
          dof->output, kConstant, [](uint32_t x, uint32_t) { return x + kPixelSpread < kConstantEnd; });
      m.push_back({constant_input(kernel), "largest relative |output - constant| at x < 28", constant_error,
                   kConstantBound, constant_error <= tolerance});
      const Spot pixel = measure_spot(dof->output, kPixelX, kPixelX + 1, kPixelY, kPixelY + 1, 0, kWindowSplitY);
      m.push_back({pixel_input(kernel), "output energy / input energy", pixel.energy_ratio, "= 1 within 2%",
                   std::abs(pixel.energy_ratio - 1.0) <= kEnergyTolerance});
      m.push_back(
          {pixel_input(kernel), "farthest pixel above 1e-6 (Chebyshev distance, pixels)", pixel.spread,
           fmt::format("<= {}: 2 x radius 4 at half resolution, + 2 for the tent, + 2 for the upsample", kPixelSpread),
           pixel.spread <= kPixelSpread});
      const Spot block =
          measure_spot(dof->output, kBlockX, kBlockX + 2, kBlockY, kBlockY + 2, kWindowSplitY, kEnergyHeight);
      m.push_back({block_input(kernel), "output energy / input energy", block.energy_ratio, "= 1 within 2%",
                   std::abs(block.energy_ratio - 1.0) <= kEnergyTolerance});
      m.push_back(
          {block_input(kernel), "farthest pixel above 1e-6 from the block (Chebyshev distance, pixels)", block.spread,
           fmt::format("<= {}: 2 x radius 4 at half resolution, + 2 for the tent, + 1 for the upsample", kBlockSpread),
           block.spread <= kBlockSpread});
    }
    // Everything in focus: every prefilter weight |coc| / (1 + brightness) is 0.
    auto focused = run_depth_of_field(context, programs, {},
                                      filled(kEnergyWidth, kEnergyHeight, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f)),
                                      filled(kEnergyWidth, kEnergyHeight, glm::vec4(kInFocusDepth, 0.0f, 0.0f, 1.0f)));
    if (!focused) return fail(focused.error());
    const double bad = non_finite_pixels(focused->output);
    m.push_back({kZeroWeightsInput, "non-finite output pixels", bad, "= 0", bad == 0.0});
    return m;
  };
  c.predict = [](const Form& form, Precision) {
    Prediction p;
    for (const Kernel& kernel : kSampledKernels) p.failing_inputs.insert(pixel_input(kernel));
    p.note =
        "One bright pixel on black does not keep its energy, on every form and kernel: the prefilter weights each "
        "of its four texels by 1 / (1 + brightness) against flicker (as Unity PPv2 does), so the pixel of 1 gets "
        "weight 1/2 against 1 for each black texel and its half-resolution texel holds (1/2) / (1/2 + 3) = 1/7 "
        "instead of 1/4: 4/7 = 0.571 of the energy is left. A 2x2 block of one half-resolution texel has equal "
        "weights and keeps its energy.";
    if (form.seed) {
      p.failing_inputs.insert(kZeroWeightsInput);
      p.note += " Everything in focus: the seed divides the prefilter's colour by its weight sum 0 (hazard 10): NaN.";
    }
    return p;
  };
  return c;
}

// ---- 5.15 -------------------------------------------------------------------------------------

// One image, two tests 56 rows apart (each reaches at most 12 pixels): noise everywhere; rows
// < 40 all at depth 1 (coc = +4); rows >= 40 at depth 1 left of x = 48 and depth 0 (coc = -4,
// foreground) right of it. The first test is judged on rows 0-23, the depth edge on rows 56-95.
constexpr uint32_t kKernelImageSize = 96;
constexpr uint32_t kEdgeStartRow = 40;
constexpr uint32_t kEdgeColumn = 48;
constexpr uint32_t kFarRowsEnd = 24;
constexpr uint32_t kEdgeRowsBegin = 56;

std::string far_input(const Kernel& kernel) {
  return "hash noise, depth 1 everywhere (coc = +4), 96x96 rows 0-23, " + kernel.label;
}
std::string edge_input(const Kernel& kernel) {
  return "hash noise, depth 1 left of x = 48 and 0 right of it (coc +4 / -4), 96x96 rows 56-95, " + kernel.label;
}

Case kernels_case() {
  Case c;
  c.id = "dof_kernels";
  c.title =
      "DoF kernels: the error against the dense gather (every texel within the radius) does not grow from 16 to 22, "
      "43 and 71 samples";
  c.section = "5.15";
  c.forms = {kSeed, kGuardedOnly};
  c.run = [](const CaseContext& context) -> Result<std::vector<Measurement>> {
    harness::ProgramCache& programs = context.programs;
    const FloatImage color = noise_image(kKernelImageSize, kKernelImageSize);
    const FloatImage depth = depth_of(kKernelImageSize, kKernelImageSize, [](uint32_t x, uint32_t y) {
      return y >= kEdgeStartRow && x >= kEdgeColumn ? 0.0f : 1.0f;
    });
    auto reference = run_depth_of_field(context, programs, {.kernel = kDenseKernel.keyword}, color, depth);
    if (!reference) return fail(reference.error());
    std::vector<Measurement> m;
    double previous_far = 0.0, previous_edge = 0.0;
    const Kernel* previous = nullptr;
    for (const Kernel& kernel : kSampledKernels) {
      auto dof = run_depth_of_field(context, programs, {.kernel = kernel.keyword}, color, depth);
      if (!dof) return fail(dof.error());
      const double far = rmse(dof->output, reference->output, 0, kFarRowsEnd);
      const double edge = rmse(dof->output, reference->output, kEdgeRowsBegin, kKernelImageSize);
      for (auto [input, value, last] :
           {std::tuple{far_input(kernel), far, previous_far}, std::tuple{edge_input(kernel), edge, previous_edge}}) {
        if (!previous)
          m.push_back(
              {input, "RMSE against the dense gather", value, "finite (the first kernel)", std::isfinite(value)});
        else
          m.push_back({input, "RMSE against the dense gather", value, "<= the " + previous->label + " kernel's",
                       value <= last});
      }
      previous_far = far;
      previous_edge = edge;
      previous = &kernel;
    }
    return m;
  };
  c.predict = [](const Form&, Precision) {
    Prediction p;
    p.failing_inputs = {far_input(kSampledKernels[1]), edge_input(kSampledKernels[1])};
    p.note =
        "The 22-sample kernel's error is about 1% above the 16-sample kernel's, on every form: after the tent and "
        "the bilinear upsample, both low-pass filters, what is left of a kernel's error against the dense disk is its "
        "difference in shape, not the angular sampling that more samples improve, and SHADERS.md's 22-sample rings are "
        "farther from a uniform disk than the 16-sample ones: 14 of 22 samples (64%) on the outer ring against 10 of "
        "16 (62.5%), 1/22 at the centre against 1/16, a mean squared radius of 11.90 texels^2 against 11.77 (the "
        "dense disk's: 7.84). From the kernels' bilinear texel weights, the expected error of the filtered output on "
        "white noise is 0.0456 (22) against 0.0448 (16), 0.0351 (43) and 0.0280 (71) times the noise's deviation: "
        "the measured ratios to 16 samples are 1.011, 0.78 and 0.62.";
    return p;
  };
  return c;
}

const glm::vec4 kSizeConstant(0.75f, 0.5f, 0.25f, 1.0f);
std::string constant_size_input(uint32_t size) {
  return fmt::format("{}x{}, constant (0.75, 0.5, 0.25), depth 1 (coc = +4), {}", size, size, kAnyKernel.label);
}
const std::string kLargeInput = "1921x1081, hash noise, depth x / 1920 across the columns, " + kAnyKernel.label;

Case image_sizes_case() {
  Case c;
  c.id = "dof_image_sizes";
  c.title =
      "DoF at image sizes 1x1, 3x3 and 1921x1081: no NaN, and a constant image at 1x1 and 3x3 comes out as the "
      "constant (reads clamped to the image)";
  c.section = "5.15";
  c.forms = {kSeed, kGuardedOnly};
  c.run = [](const CaseContext& context) -> Result<std::vector<Measurement>> {
    harness::ProgramCache& programs = context.programs;
    std::vector<Measurement> m;
    const double tolerance = constant_tolerance(context.precision);
    for (uint32_t size : {1u, 3u}) {
      auto dof = run_depth_of_field(context, programs, {}, filled(size, size, kSizeConstant),
                                    filled(size, size, glm::vec4(1.0f, 0.0f, 0.0f, 1.0f)));
      if (!dof) return fail(dof.error());
      const double error =
          largest_relative_difference(dof->output, kSizeConstant, [](uint32_t, uint32_t) { return true; });
      m.push_back({constant_size_input(size), "largest relative |output - constant|", error, kConstantBound,
                   error <= tolerance});
    }
    // Odd in both directions: the half-resolution passes are 960x540 and leave the last column
    // and row of the full-resolution images unread; the ramp puts every CoC from -4 to +4 in it.
    const uint32_t width = 1921, height = 1081;
    auto dof = run_depth_of_field(context, programs, {}, noise_image(width, height),
                                  depth_of(width, height, [](uint32_t x, uint32_t) { return float(x) / 1920.0f; }));
    if (!dof) return fail(dof.error());
    const double bad = non_finite_pixels(dof->output);
    m.push_back({kLargeInput, "non-finite output pixels", bad, "= 0", bad == 0.0});
    return m;
  };
  return c;
}

}  // namespace

std::vector<Case> dof_cases() { return {coc_case(), constant_and_energy_case(), kernels_case(), image_sizes_case()}; }

}  // namespace xshade::stability
