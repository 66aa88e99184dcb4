#include "harness/render/environment_cache.h"

#include <cstring>
#include <optional>

#include "base/file_io.h"
#include "harness/render/shader_cache.h"  // content_hash

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

// An entry is "xsenv1\n", the hash of the rest, "\n", then the environment as plain bytes in
// this machine's order (the cache is the machine's own): the radiance image, the SH and the
// prefiltered texture with its levels.
constexpr std::string_view kMagic = "xsenv1\n";

class Writer {
 public:
  template <class T>
  void value(const T& v) {
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void block(const void* data, size_t size) {
    value(uint64_t(size));
    bytes_.append(static_cast<const char*>(data), size);
  }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}
  template <class T>
  bool value(T& v) {
    if (bytes_.size() < sizeof v) return false;
    std::memcpy(&v, bytes_.data(), sizeof v);
    bytes_.remove_prefix(sizeof v);
    return true;
  }
  // A block of exactly `size` bytes into `out`.
  bool block(void* out, size_t size) {
    uint64_t stored = 0;
    if (!value(stored) || stored != size || bytes_.size() < size) return false;
    std::memcpy(out, bytes_.data(), size);
    bytes_.remove_prefix(size);
    return true;
  }
  bool done() const { return bytes_.empty(); }

 private:
  std::string_view bytes_;
};

std::string serialize(const Environment& environment) {
  Writer out;
  out.value(environment.radiance.width);
  out.value(environment.radiance.height);
  out.block(environment.radiance.rgba.data(), environment.radiance.rgba.size() * sizeof(float));
  out.value(environment.sh);
  const TextureData& texture = environment.prefiltered;
  out.value(texture.format);
  out.value(texture.width);
  out.value(texture.height);
  out.value(texture.dimension);
  out.value(texture.layers);
  out.value(texture.samples);
  out.value(uint64_t(texture.levels.size()));
  for (const std::vector<std::byte>& level : texture.levels) {
    out.value(uint64_t(level.size()));
    out.block(level.data(), level.size());
  }
  return std::move(out.bytes());
}

std::optional<Environment> deserialize(std::string_view bytes) {
  Reader in(bytes);
  Environment environment;
  uint32_t width = 0, height = 0;
  if (!in.value(width) || !in.value(height)) return std::nullopt;
  environment.radiance = FloatImage(width, height);
  if (!in.block(environment.radiance.rgba.data(), environment.radiance.rgba.size() * sizeof(float)) ||
      !in.value(environment.sh))
    return std::nullopt;
  TextureData& texture = environment.prefiltered;
  uint64_t levels = 0;
  if (!in.value(texture.format) || !in.value(texture.width) || !in.value(texture.height) ||
      !in.value(texture.dimension) || !in.value(texture.layers) || !in.value(texture.samples) || !in.value(levels) ||
      levels > 64)
    return std::nullopt;
  for (uint64_t i = 0; i < levels; ++i) {
    uint64_t size = 0;
    if (!in.value(size) || size > bytes.size()) return std::nullopt;
    std::vector<std::byte>& level = texture.levels.emplace_back(size);
    if (!in.block(level.data(), size)) return std::nullopt;
  }
  if (!in.done()) return std::nullopt;
  return environment;
}

// What the environment is made of, as bytes to hash; nullopt when its file cannot be read (the
// build then says why).
std::optional<std::string> ingredients(const EnvironmentSpec& spec, const std::string& builder_identity) {
  Writer out;
  out.bytes() = builder_identity + "\n";
  out.value(spec.kind);
  out.value(spec.color);
  out.value(spec.sky);
  out.value(spec.horizon);
  out.value(spec.ground);
  out.value(spec.intensity);
  if (spec.kind == EnvironmentKind::Equirect) {
    const std::optional<std::string> file = read_file(spec.file);
    if (!file) return std::nullopt;
    out.block(file->data(), file->size());
  }
  return std::move(out.bytes());
}

}  // namespace

EnvironmentCache::EnvironmentCache(fs::path folder, std::string builder_identity)
    : folder_(std::move(folder)), builder_identity_(std::move(builder_identity)) {}

Result<std::shared_ptr<const Environment>> EnvironmentCache::get(const EnvironmentSpec& spec) {
  const std::optional<std::string> made_of = ingredients(spec, builder_identity_);
  const std::string key = made_of ? content_hash(*made_of) : std::string();
  std::lock_guard lock(mutex_);
  if (!key.empty()) {
    if (auto kept = kept_.find(key); kept != kept_.end()) return kept->second;
    if (!folder_.empty())
      if (const std::optional<std::string> entry = read_file(folder_ / ("environment-" + key + ".bin"))) {
        const std::string_view text = *entry;
        const size_t newline = text.find('\n', kMagic.size());
        if (text.starts_with(kMagic) && newline != std::string_view::npos &&
            text.substr(kMagic.size(), newline - kMagic.size()) == content_hash(text.substr(newline + 1)))
          if (std::optional<Environment> found = deserialize(text.substr(newline + 1)))
            return kept_[key] = std::make_shared<const Environment>(std::move(*found));
      }
  }
  auto built = build_environment(spec);
  if (!built) return fail(built.error());
  ++built_;
  auto environment = std::make_shared<const Environment>(std::move(*built));
  if (key.empty()) return environment;
  if (!folder_.empty()) {
    const std::string body = serialize(*environment);
    std::error_code ignored;
    fs::create_directories(folder_, ignored);
    // Keeping it is worth a try, not a failure: without it the next run builds it again.
    [[maybe_unused]] const auto written = write_file_atomically(folder_ / ("environment-" + key + ".bin"),
                                                                std::string(kMagic) + content_hash(body) + "\n" + body);
  }
  return kept_[key] = std::move(environment);
}

}  // namespace xshade::harness
