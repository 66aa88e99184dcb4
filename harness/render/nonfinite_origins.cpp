#include "harness/render/nonfinite_origins.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace xshade::harness {

namespace {

// A record's channel as the whole number the shader wrote; anything else is no record of ours.
bool whole(float value, uint32_t& out) {
  if (!(value >= 0.0f) || value >= 16777216.0f || value != std::floor(value)) return false;
  out = uint32_t(value);
  return true;
}

glm::vec3 hue(float degrees) {
  const float h = std::fmod(degrees, 360.0f) / 60.0f;
  const float x = 1.0f - std::fabs(std::fmod(h, 2.0f) - 1.0f);
  const int sector = int(h);
  const glm::vec3 table[6] = {{1, x, 0}, {x, 1, 0}, {0, 1, x}, {0, x, 1}, {x, 0, 1}, {1, 0, x}};
  return table[std::clamp(sector, 0, 5)];
}

std::string caret_line(const std::string& source_line, uint32_t column) {
  std::string caret;
  for (uint32_t i = 1; i < column && i <= source_line.size(); ++i) caret += source_line[i - 1] == '\t' ? '\t' : ' ';
  return caret + "^";
}

}  // namespace

glm::vec4 origins_palette(size_t index) {
  // 137.5 degrees apart, at full saturation and value: bright on the black of finite pixels.
  return glm::vec4(hue(float(index) * 137.50776f), 1.0f);
}

Result<NonfiniteOrigins> find_nonfinite_origins(const FloatImage& output, const PassTrace& record,
                                                const std::vector<CompiledVariant>& variants, bool count_negative) {
  const FloatImage& trace = record.record;
  if (trace.width != output.width || trace.height != output.height)
    return fail(ErrorKind::Internal, fmt::format("the record of pass {} is {}x{}, its image {}x{}", record.pass,
                                                 trace.width, trace.height, output.width, output.height));
  using Key = std::tuple<uint32_t, uint32_t, uint32_t, uint32_t>;  // site number, calls innermost first
  std::map<Key, size_t> index_of;
  NonfiniteOrigins found;
  std::vector<size_t> origin_of_pixel(size_t(output.width) * output.height, SIZE_MAX);
  for (uint32_t y = 0; y < output.height; ++y) {
    for (uint32_t x = 0; x < output.width; ++x) {
      const glm::vec4 color = output.at(x, y);
      size_t nan = 0, inf = 0, negative = 0;
      for (int c = 0; c < 4; ++c) {
        if (std::isnan(color[c]))
          ++nan;
        else if (std::isinf(color[c]))
          ++inf;
        else if (count_negative && color[c] < 0.0f)
          ++negative;
      }
      const bool bad = nan + inf + negative > 0;
      const glm::vec4 channels = trace.at(x, y);
      uint32_t number = 0, call[3] = {0, 0, 0};
      if (!whole(channels.r, number) || !whole(channels.g, call[0]) || !whole(channels.b, call[1]) ||
          !whole(channels.a, call[2]))
        return fail(ErrorKind::Internal,
                    fmt::format("the record of pass {} holds ({:g}, {:g}, {:g}, {:g}) at ({}, {}), which no traced "
                                "program writes",
                                record.pass, channels.r, channels.g, channels.b, channels.a, x, y));
      if (number == 0) {
        if (bad) ++found.unattributed_pixels;
        continue;
      }
      if (!bad) {
        ++found.recovered_pixels;
        continue;
      }
      const Key key{number, call[0], call[1], call[2]};
      auto [it, added] = index_of.emplace(key, found.origins.size());
      if (added) {
        const uint32_t program = glsl::NonfiniteTrace::program_in(number);
        const glsl::TraceSite* site = program < variants.size() ? variants[program].trace.site_in(number) : nullptr;
        if (!site)
          return fail(ErrorKind::Internal,
                      fmt::format("the record of pass {} names site {} of program {}, which the traced variants do "
                                  "not have",
                                  record.pass, number & 0xFFFFu, program));
        const glsl::NonfiniteTrace& table = variants[program].trace;
        NonfiniteOrigin origin;
        origin.pass = record.pass;
        origin.program = variants[program].program.name;
        origin.site = *site;
        for (uint32_t c : call) {
          if (c == 0) break;
          if (c > table.calls.size())
            return fail(ErrorKind::Internal,
                        fmt::format("the record of pass {} names call {} of program {}, which has {}", record.pass, c,
                                    program, table.calls.size()));
          origin.calls.push_back(table.calls[c - 1]);
        }
        origin.first_x = x;
        origin.first_y = y;
        found.origins.push_back(std::move(origin));
      }
      NonfiniteOrigin& origin = found.origins[it->second];
      ++origin.pixels;
      origin.nan += nan;
      origin.inf += inf;
      origin.negative += negative;
      origin_of_pixel[size_t(y) * output.width + x] = it->second;
    }
  }
  // Most pixels first; the map's colours follow that order.
  std::vector<size_t> order(found.origins.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return found.origins[a].pixels > found.origins[b].pixels; });
  std::vector<size_t> rank(order.size());
  std::vector<NonfiniteOrigin> sorted;
  for (size_t i = 0; i < order.size(); ++i) {
    rank[order[i]] = i;
    sorted.push_back(std::move(found.origins[order[i]]));
  }
  found.origins = std::move(sorted);
  found.map = FloatImage(output.width, output.height);
  for (uint32_t y = 0; y < output.height; ++y)
    for (uint32_t x = 0; x < output.width; ++x) {
      const size_t origin = origin_of_pixel[size_t(y) * output.width + x];
      found.map.set(x, y, origin == SIZE_MAX ? glm::vec4(0.0f, 0.0f, 0.0f, 1.0f) : origins_palette(rank[origin]));
    }
  return found;
}

std::string describe_origins(const NonfiniteOrigins& origins, size_t rows) {
  std::string text;
  for (size_t i = 0; i < origins.origins.size() && i < rows; ++i) {
    const NonfiniteOrigin& origin = origins.origins[i];
    const glsl::TraceSite& site = origin.site;
    text += fmt::format("  {} pixels ({} NaN, {} Inf, {} negative values), first at ({}, {}): {}:{}:{}: {} in {}\n",
                        origin.pixels, origin.nan, origin.inf, origin.negative, origin.first_x, origin.first_y,
                        site.file, site.line, site.column, glsl::describe_site(site), site.function);
    if (!site.source_line.empty())
      text += "    " + site.source_line + "\n    " + caret_line(site.source_line, site.column) + "\n";
    for (const glsl::TraceCall& call : origin.calls)
      text += fmt::format("    called from {} at {}:{}:{}\n", call.caller, call.file, call.line, call.column);
    if (origin.calls.size() == glsl::NonfiniteTrace::kRecordedCalls)
      text += "    (calls further out are not recorded)\n";
  }
  if (origins.origins.size() > rows) text += fmt::format("  ... and {} more sites\n", origins.origins.size() - rows);
  if (origins.unattributed_pixels)
    text += fmt::format("  {} pixels non-finite with no site recorded (drawn by no traced program)\n",
                        origins.unattributed_pixels);
  if (origins.recovered_pixels)
    text += fmt::format("  {} pixels had a NaN or infinity on the way that did not reach the output\n",
                        origins.recovered_pixels);
  return text;
}

}  // namespace xshade::harness
