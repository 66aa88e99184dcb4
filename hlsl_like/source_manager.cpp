#include "hlsl_like/source_manager.h"

#include <cerrno>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace xshade::hlsl {
namespace {

enum class ReadError { None, Directory, Open, Read };

// The whole file in one read of the size fstat gives (a file that grows meanwhile, or says no
// size, is read on to its end): a shader is read once per compile, where a stream and a string
// stream cost more than the reading.
ReadError read_whole_file(const std::filesystem::path& path, std::string& text) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    std::error_code error;
    return std::filesystem::is_directory(path, error) ? ReadError::Directory : ReadError::Open;
  }
  struct stat status {};
  if (::fstat(fd, &status) == 0 && S_ISDIR(status.st_mode)) {
    ::close(fd);
    return ReadError::Directory;
  }
  const size_t expected = status.st_size > 0 ? size_t(status.st_size) : 0;
  text.resize(expected + 1);  // one byte more: a read that fills it says the file has grown
  size_t size = 0;
  for (;;) {
    if (size == text.size()) text.resize(text.size() * 2);
    const ssize_t n = ::read(fd, text.data() + size, text.size() - size);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      ::close(fd);
      return ReadError::Read;
    }
    if (n == 0) break;
    size += size_t(n);
    // A regular file reads short only at its end: no second read to see that.
    if (S_ISREG(status.st_mode) && size < text.size()) break;
  }
  ::close(fd);
  text.resize(size);
  return ReadError::None;
}

}  // namespace

SourceManager::SourceManager() { files_.push_back(std::make_unique<File>()); }  // index 0: none

uint32_t SourceManager::add(std::string name, std::string text) {
  auto file = std::make_unique<File>();
  file->name = std::move(name);
  file->text = std::move(text);
  files_.push_back(std::move(file));
  return uint32_t(files_.size() - 1);
}

Result<uint32_t> SourceManager::load(const std::filesystem::path& path) {
  std::error_code error;
  std::filesystem::path canonical = std::filesystem::weakly_canonical(path, error);
  if (error) canonical = path;
  return load_canonical(canonical, path.string());
}

Result<uint32_t> SourceManager::load_canonical(const std::filesystem::path& canonical, std::string name) {
  for (uint32_t i = 1; i < files_.size(); ++i)
    if (!files_[i]->path.empty() && files_[i]->path == canonical) return i;
  std::string text;
  switch (read_whole_file(canonical, text)) {
    case ReadError::None:
      break;
    case ReadError::Directory:
      return fail("'" + name + "' is a directory");
    case ReadError::Open:
      return fail("cannot open '" + name + "'");
    case ReadError::Read:
      return fail("cannot read '" + name + "'");
  }
  uint32_t index = add(std::move(name), std::move(text));
  files_[index]->path = canonical;
  return index;
}
std::string_view SourceManager::line_text(uint32_t file, uint32_t line) const {
  if (file == 0 || file >= files_.size() || line == 0) return {};
  const File& f = *files_[file];
  if (f.line_starts.empty()) {
    f.line_starts.push_back(0);
    for (uint32_t i = 0; i < f.text.size(); ++i)
      if (f.text[i] == '\n') f.line_starts.push_back(i + 1);
  }
  if (line > f.line_starts.size()) return {};
  const uint32_t start = f.line_starts[line - 1];
  uint32_t end = line < f.line_starts.size() ? f.line_starts[line] - 1 : uint32_t(f.text.size());
  if (end > start && f.text[end - 1] == '\r') --end;
  return std::string_view(f.text).substr(start, end - start);
}

SourceLocation SourceManager::resolve(Loc loc) const {
  if (loc.file == 0 || loc.file >= files_.size()) return {};
  return {files_[loc.file]->name, loc.line, loc.column};
}

}  // namespace xshade::hlsl
