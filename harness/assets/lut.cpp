#include "harness/assets/lut.h"

#include <charconv>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "base/file_io.h"

namespace xshade::harness {
namespace {

TextureData lut_texture(uint32_t size, const std::vector<glm::vec4>& texels) {
  TextureData lut{TextureFormat::Rgba32Float, size, size, {}};
  lut.dimension = TextureDimension::Tex3D;
  lut.layers = size;
  std::vector<std::byte> bytes(texels.size() * sizeof(glm::vec4));
  std::memcpy(bytes.data(), texels.data(), bytes.size());
  lut.levels.push_back(std::move(bytes));
  return lut;
}

// The words of a line with the column each starts at (1-based).
std::vector<std::pair<std::string_view, uint32_t>> words_of(std::string_view line) {
  std::vector<std::pair<std::string_view, uint32_t>> words;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) words.emplace_back(line.substr(start, i - start), uint32_t(start + 1));
  }
  return words;
}

std::optional<float> number(std::string_view word) {
  float value = 0.0f;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (error != std::errc() || end != word.data() + word.size()) return std::nullopt;
  return value;
}

}  // namespace

Result<TextureData> lut_from_strip(const FloatImage& strip) {
  const uint32_t n = strip.height;
  if (n < 2 || strip.width != n * n)
    return fail(ErrorKind::UserInput,
                fmt::format("a LUT strip is N * N x N texels (Unity's is 1024 x 32), this image is {}x{}", strip.width,
                            strip.height));
  std::vector<glm::vec4> texels;
  texels.reserve(size_t(n) * n * n);
  for (uint32_t b = 0; b < n; ++b)
    for (uint32_t g = 0; g < n; ++g)
      for (uint32_t r = 0; r < n; ++r) texels.push_back(strip.at(b * n + r, n - 1 - g));
  return lut_texture(n, texels);
}

Result<TextureData> read_cube_lut(const std::filesystem::path& file) {
  // Checked as a file first (a FIFO is not waited on).
  auto text = read_input_file(file, kMaxCubeFileBytes, "the LUT file");
  if (!text) return fail(text.error());
  std::istringstream stream(std::move(*text));
  const std::string name = file.string();
  uint32_t size = 0;
  std::vector<glm::vec4> texels;
  std::string line;
  for (uint32_t line_number = 1; std::getline(stream, line); ++line_number) {
    const auto at = [&](uint32_t column) { return SourceLocation{name, line_number, column}; };
    const auto words = words_of(std::string_view(line).substr(0, line.find('#')));
    if (words.empty()) continue;
    const std::string_view key = words[0].first;
    if (key == "TITLE") continue;
    if (key == "LUT_1D_SIZE")
      return fail(ErrorKind::UserInput, "a 1D LUT cannot be a 3D texture; give a file with LUT_3D_SIZE",
                  at(words[0].second));
    if (key == "LUT_3D_SIZE") {
      const float value = words.size() == 2 ? number(words[1].first).value_or(0.0f) : 0.0f;
      if (size || !(value >= 2.0f && value <= 256.0f) || value != float(uint32_t(value)))
        return fail(ErrorKind::UserInput,
                    size ? "LUT_3D_SIZE is given twice" : "LUT_3D_SIZE: expected an integer in 2..256",
                    at(words.size() > 1 ? words[1].second : words[0].second));
      size = uint32_t(value);
      texels.reserve(size_t(size) * size * size);
      continue;
    }
    if (key == "DOMAIN_MIN" || key == "DOMAIN_MAX") {
      const float expected = key == "DOMAIN_MIN" ? 0.0f : 1.0f;
      for (size_t i = 1; i < 4; ++i)
        if (words.size() != 4 || number(words[i].first) != expected)
          return fail(ErrorKind::UserInput,
                      fmt::format("{}: expected {} {} {}: xshade reads LUTs over the domain [0, 1]", key, expected,
                                  expected, expected),
                      at(words[std::min(i, words.size() - 1)].second));
      continue;
    }
    if (!size) return fail(ErrorKind::UserInput, "expected LUT_3D_SIZE before the table's values", at(words[0].second));
    if (words.size() != 3)
      return fail(ErrorKind::UserInput,
                  fmt::format("expected three numbers (red green blue), got {} words", words.size()),
                  at(words[0].second));
    glm::vec4 texel{0.0f, 0.0f, 0.0f, 1.0f};
    for (int c = 0; c < 3; ++c) {
      const auto value = number(words[size_t(c)].first);
      if (!value)
        return fail(ErrorKind::UserInput, fmt::format("expected a number, got '{}'", words[size_t(c)].first),
                    at(words[size_t(c)].second));
      texel[c] = *value;
    }
    if (texels.size() == size_t(size) * size * size)
      return fail(ErrorKind::UserInput,
                  fmt::format("more than the {}^3 = {} values LUT_3D_SIZE asks for", size, texels.size()),
                  at(words[0].second));
    texels.push_back(texel);
  }
  if (stream.bad()) return fail(ErrorKind::UserInput, "cannot read the LUT file", SourceLocation{name, 0, 0});
  if (!size) return fail(ErrorKind::UserInput, "no LUT_3D_SIZE line: not a 3D .cube LUT", SourceLocation{name, 0, 0});
  if (texels.size() != size_t(size) * size * size)
    return fail(ErrorKind::UserInput,
                fmt::format("{} values, LUT_3D_SIZE {} asks for {}", texels.size(), size, size_t(size) * size * size),
                SourceLocation{name, 0, 0});
  return lut_texture(size, texels);
}

}  // namespace xshade::harness
