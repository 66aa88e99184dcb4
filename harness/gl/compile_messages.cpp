#include "harness/gl/compile_messages.h"

#include <cstdio>

#include <xxhash.h>

#include "base/file_io.h"

namespace xshade::harness {
namespace {

std::string hex(std::string_view bytes) {
  const XXH128_hash_t hash = XXH3_128bits(bytes.data(), bytes.size());
  char text[33];
  std::snprintf(text, sizeof text, "%016llx%016llx", static_cast<unsigned long long>(hash.high64),
                static_cast<unsigned long long>(hash.low64));
  return text;
}

}  // namespace

// An entry: the hash of the rest on the first line, then each message ended by a NUL byte.
std::vector<std::string> CompileMessages::settle(const std::string& driver, const std::string& source,
                                                 std::vector<std::string> fresh) const {
  if (folder_.empty()) return fresh;
  const std::filesystem::path entry = folder_ / (hex(driver + '\0' + source) + ".messages");
  if (!fresh.empty()) {
    std::string body;
    for (const std::string& message : fresh) body += message + '\0';
    std::error_code ignored;
    std::filesystem::create_directories(folder_, ignored);
    // Keeping them is worth a try, not a failure: without them, a warm run's cache only costs time.
    [[maybe_unused]] const auto written = write_file_atomically(entry, hex(body) + "\n" + body);
    return fresh;
  }
  const std::optional<std::string> stored = read_file(entry);
  if (!stored) return fresh;
  const size_t newline = stored->find('\n');
  if (newline == std::string::npos || stored->substr(0, newline) != hex(stored->substr(newline + 1))) return fresh;
  std::vector<std::string> messages;
  for (size_t at = newline + 1, end; (end = stored->find('\0', at)) != std::string::npos; at = end + 1)
    messages.push_back(stored->substr(at, end - at));
  return messages;
}

}  // namespace xshade::harness
