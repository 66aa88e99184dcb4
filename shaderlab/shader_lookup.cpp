#include "shaderlab/shader_lookup.h"

#include <fstream>
#include <map>
#include <mutex>

namespace xshade::shaderlab {

namespace fs = std::filesystem;

namespace {

// A .shader's `Shader "name"` line comes before anything else; a licence comment before it is
// the longest thing seen there, far below this.
constexpr std::streamsize kHeaderBytes = 64 * 1024;

size_t skip_space_and_comments(std::string_view text, size_t at) {
  while (at < text.size()) {
    if (text[at] == ' ' || text[at] == '\t' || text[at] == '\r' || text[at] == '\n') {
      ++at;
    } else if (text.substr(at, 2) == "//") {
      at = text.find('\n', at);
      if (at == std::string_view::npos) return text.size();
    } else if (text.substr(at, 2) == "/*") {
      at = text.find("*/", at + 2);
      if (at == std::string_view::npos) return text.size();
      at += 2;
    } else {
      break;
    }
  }
  return at;
}

// Every .shader under `folder` with the name it declares, read once a process.
const std::vector<std::pair<std::string, fs::path>>& shaders_in(const fs::path& folder) {
  static std::mutex mutex;
  static std::map<fs::path, std::vector<std::pair<std::string, fs::path>>> folders;
  std::lock_guard lock(mutex);
  auto [entry, added] = folders.try_emplace(folder);
  if (!added) return entry->second;
  std::error_code error;
  for (fs::recursive_directory_iterator it(folder, fs::directory_options::skip_permission_denied, error), end;
       !error && it != end; it.increment(error)) {
    if (it->path().extension() != ".shader" || !it->is_regular_file(error)) continue;
    std::ifstream file(it->path(), std::ios::binary);
    std::string header(kHeaderBytes, '\0');
    file.read(header.data(), kHeaderBytes);
    header.resize(size_t(file.gcount()));
    if (std::string name = declared_shader_name(header); !name.empty()) entry->second.emplace_back(name, it->path());
  }
  return entry->second;
}

}  // namespace

// Unity 5 moved its shaders of before the Standard shader under this prefix and still finds them
// by their old names, which its own shaders use (Fallback "VertexLit" for "Legacy
// Shaders/VertexLit").
constexpr std::string_view kLegacyPrefix = "Legacy Shaders/";

std::string declared_shader_name(std::string_view text) {
  size_t at = text.starts_with("\xEF\xBB\xBF") ? 3 : 0;
  at = skip_space_and_comments(text, at);
  if (text.substr(at, 6) != "Shader") return {};
  at = skip_space_and_comments(text, at + 6);
  if (at >= text.size() || text[at] != '"') return {};
  const size_t end = text.find('"', at + 1);
  if (end == std::string_view::npos) return {};
  return std::string(text.substr(at + 1, end - at - 1));
}

Result<fs::path> find_shader_named(const std::string& name, const std::vector<fs::path>& folders) {
  std::vector<std::string> names = {name};
  if (!name.starts_with(kLegacyPrefix)) names.push_back(std::string(kLegacyPrefix) + name);
  for (const std::string& wanted : names) {
    for (const fs::path& folder : folders)
      for (const auto& [declared, path] : shaders_in(folder))
        if (declared == wanted) return path;
  }
  std::string list;
  for (const fs::path& folder : folders) list += (list.empty() ? "" : ", ") + folder.string();
  return fail(ErrorKind::UserInput, "no .shader in the shader folders declares Shader \"" + name + "\" (searched " +
                                        (list.empty() ? std::string("no folder") : list) + " and their subfolders)");
}

std::pair<std::string, std::string> split_used_pass(const std::string& used) {
  const size_t slash = used.rfind('/');
  if (slash == std::string::npos) return {used, ""};
  return {used.substr(0, slash), used.substr(slash + 1)};
}

}  // namespace xshade::shaderlab
