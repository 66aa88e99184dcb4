// The source files of one compilation, and compact locations into them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"

namespace xshade::hlsl {

// A location as the front end carries it: a file index and a 1-based line and column. Turned
// into a printable SourceLocation only when a diagnostic is reported.
struct Loc {
  uint32_t file = 0;  // index in the SourceManager; 0 = no file
  uint32_t line = 0;
  uint32_t column = 0;
};

class SourceManager {
 public:
  SourceManager();

  // Registers a file given as text (tests, the command line's stdin); returns its index.
  uint32_t add(std::string name, std::string text);
  // Reads a file from disk once; the same canonical path yields the same index. Only a regular
  // file of at most kMaxSourceFileBytes (base/file_io.h) is read.
  Result<uint32_t> load(const std::filesystem::path& path);
  // load() for a path already canonical (an #include, resolved to be held to its folders), which
  // is not resolved again; `name` is what messages call the file; `known_size`: a stat of the path
  // has just found a regular file this large (read_regular_file).
  Result<uint32_t> load_canonical(const std::filesystem::path& canonical, std::string name,
                                  std::optional<size_t> known_size = std::nullopt);

  std::string_view text(uint32_t file) const { return files_[file]->text; }
  const std::string& name(uint32_t file) const { return files_[file]->name; }
  // The canonical path of a file read from disk; empty for text given to add().
  const std::filesystem::path& path(uint32_t file) const { return files_[file]->path; }
  // Whether load() resolved the file's path through the file system (base/paths.h), links and
  // all, before reading it; a path it could not resolve is only made as canonical as it could be.
  // The preprocessor then looks names up in the file's folder without resolving the folder again.
  bool path_resolved_on_load(uint32_t file) const { return files_[file]->resolved_on_load; }
  size_t file_count() const { return files_.size(); }

  // The text of one line, without its line ending; empty when out of range.
  std::string_view line_text(uint32_t file, uint32_t line) const;
  // Where `loc` is as messages give it: after a `#line N "name"` in its file, the lines that
  // follow are counted from N and the file is called `name` (the text a tool composed from
  // another file, such as a Unity .shader's program blocks, points into that file).
  SourceLocation resolve(Loc loc) const;
  // Records a #line of `file`: its physical line `from_line` is line `line`; `name`, where not
  // empty, is what messages call the file from there on.
  void add_line_mapping(uint32_t file, uint32_t from_line, uint32_t line, std::string name);

 private:
  struct File {
    std::string name;  // as the user spelled it, for messages
    std::filesystem::path path;
    bool resolved_on_load = false;
    std::string text;
    mutable std::vector<uint32_t> line_starts;  // computed on first use
    struct LineMapping {
      uint32_t from_line, line;
      std::string name;
    };
    std::vector<LineMapping> line_mappings;  // by from_line, as the #line directives come
  };
  std::vector<std::unique_ptr<File>> files_;  // stable addresses: tokens point into text
};

}  // namespace xshade::hlsl
