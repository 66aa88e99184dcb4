#include "harness/scene/project_file.h"

#include <system_error>

#include <fmt/format.h>

#include "base/file_io.h"
#include "base/paths.h"
#include "harness/scene/toml_reader.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;
using namespace toml_text;

class ProjectFileReader : TomlReader {
 public:
  explicit ProjectFileReader(const fs::path& file) : TomlReader(file.string()) {
    std::error_code ignored;
    project_.path = fs::absolute(file, ignored).lexically_normal();
    project_.root = project_.path.parent_path();
  }

  Result<ProjectFile> read(std::string_view text) {
    std::optional<toml::table> root = parse(text);
    if (!root) return finish(ProjectFile{});
    check_keys(*root, "", {"scenes", "golden", "shaders"}, " in a project file");
    if (const toml::node* node = root->get("scenes")) project_.scenes = folder(*node, "scenes", Kind::MustExist);
    if (const toml::node* node = root->get("golden")) project_.golden = folder(*node, "golden", Kind::MayBeNew);
    if (const toml::node* node = root->get("shaders")) read_shaders(*node);
    return finish(std::move(project_));
  }

 private:
  enum class Kind { MustExist, MayBeNew };

  void read_shaders(const toml::node& node) {
    if (node.is_string()) {
      if (auto path = folder(node, "shaders", Kind::MustExist)) project_.shaders.push_back(*path);
      return;
    }
    const toml::array* array = node.as_array();
    if (!array) return expected(node, "shaders", "a folder or an array of folders");
    for (size_t i = 0; i < array->size(); ++i)
      if (auto path = folder(*array->get(i), index_path("shaders", i), Kind::MustExist))
        project_.shaders.push_back(*path);
  }

  // A folder relative to the project file's folder, inside it, made absolute.
  std::optional<fs::path> folder(const toml::node& node, std::string_view key, Kind kind) {
    auto text = string(node, key, "a folder relative to the project file");
    if (!text) return std::nullopt;
    const fs::path relative(*text);
    if (relative.is_absolute() || relative.has_root_name()) {
      report(node.source(), fmt::format("{}: expected a folder relative to the project file, got the absolute path {}",
                                        key, quote_text(*text)));
      return std::nullopt;
    }
    const fs::path full = (project_.root / relative).lexically_normal();
    if (full != project_.root && !path_is_inside(full, project_.root)) {
      report(node.source(), fmt::format("{}: expected a folder inside the project file's folder {}, got {}, which "
                                        "leads out of it",
                                        key, project_.root.string(), quote_text(*text)));
      return std::nullopt;
    }
    std::error_code error;
    const fs::file_status status = fs::status(full, error);
    if (fs::exists(status) && !fs::is_directory(status)) {
      report(node.source(), fmt::format("{}: expected a folder, got {}, which is a file", key, quote_text(*text)));
      return std::nullopt;
    }
    if (kind == Kind::MustExist && !fs::exists(status)) {
      report(node.source(), fmt::format("{}: expected an existing folder, got {}, which does not exist ({})", key,
                                        quote_text(*text), full.string()));
      return std::nullopt;
    }
    return full;
  }

  ProjectFile project_;
};

}  // namespace

Result<ProjectFile> parse_project_file(std::string_view text, const fs::path& file) {
  return ProjectFileReader(file).read(text);
}

Result<ProjectFile> load_project_file(const fs::path& file) {
  // The project file is held to its folder like the folders it names: a checkout's xshade.toml
  // that is a symbolic link to a file elsewhere would point xshade at that file's contents.
  std::error_code error;
  if (fs::exists(file, error) && !path_is_inside(file, fs::absolute(file, error).parent_path())) {
    const fs::path target = fs::weakly_canonical(file, error);
    return fail(ErrorKind::UserInput,
                "the project file is a symbolic link that points outside its folder" +
                    (error ? std::string() : " (to " + target.string() + ")") +
                    "; a project file must be inside the folder it is for",
                SourceLocation{file.string(), 0, 0});
  }
  auto text = read_input_file(file, kMaxProjectFileBytes, "the project file");
  if (!text) return fail(text.error());
  return parse_project_file(*text, file);
}

Result<std::optional<fs::path>> find_project_file(const fs::path& start) {
  std::error_code error;
  fs::path folder = fs::absolute(start, error).lexically_normal();
  if (error) return std::optional<fs::path>();
  while (true) {
    const fs::path candidate = folder / kProjectFileName;
    if (fs::is_regular_file(candidate, error)) return std::optional<fs::path>(candidate);
    // Passed over, it would leave xshade checking its own fixed scenes and calling that a pass.
    if (const std::string kind = not_a_file(candidate); !kind.empty())
      return fail(ErrorKind::UserInput,
                  "the project file " + candidate.string() + " is " + kind +
                      ", not a file: make it the project's xshade.toml or remove it (--no-project ignores it)");
    if (fs::exists(folder / ".git", error) || folder == folder.parent_path() || !folder.has_relative_path())
      return std::optional<fs::path>();
    folder = folder.parent_path();
  }
}

}  // namespace xshade::harness
