#include "base/file_io.h"

#include <fstream>
#include <sstream>

#include <unistd.h>

namespace xshade {

namespace fs = std::filesystem;

std::optional<std::string> read_file(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return std::nullopt;
  std::stringstream bytes;
  bytes << file.rdbuf();
  return bytes.str();
}

Result<void> write_file_atomically(const fs::path& path, std::string_view bytes) {
  // Beside the target, so that the rename stays within one file system and is atomic; the pid
  // keeps two processes writing the same file from sharing a temporary.
  const fs::path temporary = path.string() + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    if (file) file.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (file) file.close();
    if (!file) {
      std::error_code ignored;
      fs::remove(temporary, ignored);
      return fail("cannot write " + temporary.string());
    }
  }
  std::error_code error;
  fs::rename(temporary, path, error);
  if (error) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    return fail("cannot write " + path.string() + ": " + error.message());
  }
  return {};
}

}  // namespace xshade
