#include "harness/report/viewer_data.h"

#include <bit>
#include <cstring>
#include <map>
#include <optional>

#include <fmt/format.h>
#include <zlib.h>
#include <nlohmann/json.hpp>

#include "harness/gate/result_json.h"
#include "harness/image/image_compare.h"
#include "harness/image/image_io.h"
#include "harness/image/metric_layers.h"
#include "harness/image/srgb8_encoder.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string base64(const unsigned char* bytes, size_t size) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  for (size_t i = 0; i < size; i += 3) {
    const uint32_t chunk = uint32_t(bytes[i]) << 16 | (i + 1 < size ? uint32_t(bytes[i + 1]) << 8 : 0) |
                           (i + 2 < size ? uint32_t(bytes[i + 2]) : 0);
    out += kDigits[chunk >> 18 & 63];
    out += kDigits[chunk >> 12 & 63];
    out += i + 1 < size ? kDigits[chunk >> 6 & 63] : '=';
    out += i + 2 < size ? kDigits[chunk & 63] : '=';
  }
  return out;
}

// The image as little-endian float32 RGBA, deflated (zlib's format, which the browser's
// DecompressionStream("deflate") reads) at the fastest level: a report's images are written once
// and read once, and the fastest level already takes a render's flat areas to a few percent.
std::string deflated_base64(const FloatImage& image) {
  std::vector<unsigned char> raw(image.rgba.size() * sizeof(float));
  std::memcpy(raw.data(), image.rgba.data(), raw.size());
  if constexpr (std::endian::native == std::endian::big)
    for (size_t i = 0; i < raw.size(); i += 4) std::swap(raw[i], raw[i + 3]), std::swap(raw[i + 1], raw[i + 2]);
  uLongf size = compressBound(uLong(raw.size()));
  std::vector<unsigned char> packed(size);
  if (compress2(packed.data(), &size, raw.data(), uLong(raw.size()), Z_BEST_SPEED) != Z_OK) return {};
  return base64(packed.data(), size);
}

// "#rrggbb" of a linear colour, through the encoding the PNGs use.
std::string hex_colour(const glm::vec4& linear) {
  return fmt::format("#{:02x}{:02x}{:02x}", linear_to_srgb8(linear.r), linear_to_srgb8(linear.g),
                     linear_to_srgb8(linear.b));
}

// Empty when the image library cannot be loaded: the report's images cannot be written then
// either, and that error says why.
json palette_json(const Result<std::array<glm::vec4, 256>>& palette) {
  json colours = json::array();
  if (palette)
    for (const glm::vec4& colour : *palette) colours.push_back(hex_colour(colour));
  return colours;
}

json or_null(const std::string& text) { return text.empty() ? json(nullptr) : json(text); }

// The scene's metric against the golden, with its heat map, or null.
json metric_or_null(const LaneResult& lane) {
  if (!lane.against_golden || !lane.against_golden->metric) return nullptr;
  json metric = metric_to_json(*lane.against_golden->metric);
  metric["map"] = or_null(lane.metric_map);
  return metric;
}

json pixel_or_null(const std::optional<std::pair<uint32_t, uint32_t>>& pixel) {
  return pixel ? json{{"x", pixel->first}, {"y", pixel->second}} : json(nullptr);
}

json worst_or_null(const ImageMetrics& metrics) {
  if (metrics.max_steps == 0) return nullptr;
  return {{"x", metrics.worst_x}, {"y", metrics.worst_y}, {"steps", metrics.max_steps}};
}

// The float images of a page, each read once, named by its path in the report.
class FloatImages {
 public:
  FloatImages(fs::path report_dir, const std::map<std::string, const FloatImage*>& in_memory)
      : report_dir_(std::move(report_dir)), in_memory_(in_memory) {}

  const FloatImage* get(const std::string& path) {
    if (path.empty()) return nullptr;
    if (auto known = in_memory_.find(path); known != in_memory_.end()) return known->second;
    auto [entry, first] = images_.try_emplace(path);
    if (first) {
      auto read = read_image(report_dir_ / path);
      if (read) entry->second = std::move(*read);
    }
    return entry->second ? &*entry->second : nullptr;
  }
  // A path whose image read, for the page's script; nothing for one that did not, or one too
  // large to carry: a 2048 x 2048 image is 64 MB of float32 before deflate, which a browser
  // still decodes in a second; a 4096 x 4096 scene's page shows its PNGs without the values.
  json key(const std::string& path) {
    constexpr size_t kMostPixels = size_t(2048) * 2048;
    const FloatImage* image = get(path);
    if (!image || size_t(image->width) * image->height > kMostPixels) return nullptr;
    used_.emplace(path, image);
    return path;
  }
  std::vector<ViewerPage::PixelScript> scripts(std::set<std::string>* scripted) const {
    std::vector<ViewerPage::PixelScript> out;
    for (const auto& [path, image] : used_) {
      if (scripted && scripted->count(path)) {
        out.push_back({path, {}});
        continue;
      }
      const std::string data = deflated_base64(*image);
      if (data.empty()) continue;
      const json entry = {
          {"width", image->width}, {"height", image->height}, {"encoding", "deflate-f32le-rgba"}, {"data", data}};
      out.push_back({path, "(window.XSHADE_PIXELS = window.XSHADE_PIXELS || {})[" + json(path).dump() +
                               "] = " + entry.dump() + ";\n"});
      if (scripted) scripted->insert(path);
    }
    return out;
  }

 private:
  fs::path report_dir_;
  const std::map<std::string, const FloatImage*>& in_memory_;
  std::map<std::string, std::optional<FloatImage>> images_;
  std::map<std::string, const FloatImage*> used_;
};

// The golden's values as the comparison held them: its float image where it has one, else its
// PNG, decoded as every 8-bit golden is.
const std::string& golden_floats(const LaneResult& lane) {
  return lane.golden_exr.empty() ? lane.golden : lane.golden_exr;
}

bool same_pixels(const FloatImage* a, const FloatImage* b) {
  if (!a || !b) return a == b;
  return a->width == b->width && a->height == b->height &&
         std::memcmp(a->rgba.data(), b->rgba.data(), a->rgba.size() * sizeof(float)) == 0;
}

}  // namespace

std::string pixel_script_path(const std::string& image) { return "pixels/" + image + ".js"; }

ViewerPage viewer_page(const SceneResult& scene, const fs::path& report_dir,
                       const std::map<std::string, const FloatImage*>& in_memory, std::set<std::string>* scripted) {
  FloatImages images(report_dir, in_memory);
  const uint32_t tolerance = scene.compare.channel_tolerance;

  // Lanes that rendered, grouped with the first lane whose image, golden and verdict they share.
  std::vector<std::vector<const LaneResult*>> groups;
  for (const LaneResult& lane : scene.lanes) {
    if (lane.image.empty()) continue;
    const FloatImage* output = images.get(lane.image_exr);
    const FloatImage* golden = images.get(golden_floats(lane));
    bool joined = false;
    for (auto& group : groups) {
      const LaneResult& first = *group.front();
      // Without float images there is nothing to prove them identical with.
      if (output && first.verdict == lane.verdict && first.golden.empty() == lane.golden.empty() &&
          same_pixels(images.get(first.image_exr), output) && same_pixels(images.get(golden_floats(first)), golden)) {
        group.push_back(&lane);
        joined = true;
        break;
      }
    }
    if (!joined) groups.push_back({&lane});
  }

  json page = {{"scene", scene.scene},
               {"channel_tolerance", tolerance},
               {"heat_palette", palette_json(heat_palette(tolerance))}};
  if (scene.compare.metric) page["metric_palette"] = palette_json(metric_palette());
  uint32_t width = 0, height = 0;
  json group_list = json::array();
  for (const auto& group : groups) {
    const LaneResult& lane = *group.front();
    if (const FloatImage* output = images.get(lane.image_exr); output && width == 0)
      width = output->width, height = output->height;
    json names = json::array();
    for (const LaneResult* each : group) names.push_back(each->lane);
    const ImageMetrics metrics = lane.against_golden.value_or(ImageMetrics{});
    group_list.push_back(
        {{"lanes", names},
         {"verdict", verdict_name(lane.verdict)},
         {"output", {{"pixels", images.key(lane.image_exr)}, {"png", lane.image}}},
         {"golden", lane.golden.empty() ? json(nullptr)
                                        : json{{"pixels", images.key(golden_floats(lane))}, {"png", lane.golden}}},
         {"heat_map", or_null(lane.diff)},
         {"heat_palette", page["heat_palette"]},
         {"metric", metric_or_null(lane)},
         {"channel_tolerance", tolerance},
         {"worst", lane.against_golden ? worst_or_null(metrics) : json(nullptr)},
         {"first_failing", pixel_or_null(metrics.first_failing)},
         {"failing_pixels", metrics.failing_pixels}});
  }
  json pairs = json::array();
  for (const CrossLaneResult& pair : scene.cross_lane) {
    if (pair.identical) continue;
    pairs.push_back({{"first", pair.first_lane},
                     {"second", pair.second_lane},
                     {"verdict", verdict_name(pair.verdict)},
                     {"heat_map", or_null(pair.diff)},
                     {"worst", worst_or_null(pair.metrics)}});
  }
  json starts = json::array();
  for (int code = 0; code < 256; ++code) starts.push_back(srgb8_code_start(uint8_t(code)));
  page["width"] = width;
  page["height"] = height;
  page["srgb_code_starts"] = std::move(starts);
  page["groups"] = std::move(group_list);
  page["cross_lane"] = std::move(pairs);

  ViewerPage out;
  // '<' only occurs inside JSON strings, where \u003c means the same: no scene name can then
  // end the <script> element the data sits in, or open a comment in it.
  for (const char c : page.dump(-1, ' ', false, json::error_handler_t::replace))
    out.data_json += c == '<' ? std::string("\\u003c") : std::string(1, c);
  out.pixels = images.scripts(scripted);
  return out;
}

}  // namespace xshade::harness
