// Validating what xshade generated: a refusal is xshade's bug, so the error is Internal and shows
// the validator's words at the generated lines they name.
#include <fmt/core.h>

#include <algorithm>
#include <charconv>
#include <functional>

#include "codegen/codegen_internal.h"
#include "codegen/generate.h"

namespace xshade::codegen {
namespace {

// Lines of an excerpt before and after each line a validator names, and how many named lines
// of one message are shown: enough to see a declaration beside the one it clashes with.
constexpr uint32_t kContextLines = 3;
constexpr size_t kMaxShownPerMessage = 3;

const char* stage_name(spirv::Stage stage) { return stage == spirv::Stage::Vertex ? "vertex" : "fragment"; }

std::vector<std::string_view> split_lines(std::string_view text) {
  std::vector<std::string_view> lines;
  while (!text.empty()) {
    const size_t newline = text.find('\n');
    lines.push_back(text.substr(0, newline));
    text = newline == std::string_view::npos ? std::string_view{} : text.substr(newline + 1);
  }
  return lines;
}

std::optional<uint32_t> number(std::string_view digits) {
  uint32_t value = 0;
  auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (ec != std::errc() || end != digits.data() + digits.size() || digits.empty()) return std::nullopt;
  return value;
}

// Where glslang says a line of the text is: its source string (0, the generated text itself,
// until a `#line L N` names the author's file N) and its line there.
struct LogicalLine {
  uint32_t source = 0;
  uint32_t line = 0;
};

// For each line of `text` (index 0 = line 1), where glslang says it is. `#line L N` makes the
// next line line L of source string N, as GLSL 4.50 and the emitter read it.
std::vector<LogicalLine> logical_lines(const std::vector<std::string_view>& lines) {
  std::vector<LogicalLine> logical(lines.size());
  LogicalLine next{0, 1};
  for (size_t index = 0; index < lines.size(); ++index) {
    logical[index] = next;
    ++next.line;
    std::string_view line = lines[index];
    line.remove_prefix(std::min(line.find_first_not_of(" \t"), line.size()));
    if (!line.starts_with("#line ")) continue;
    line.remove_prefix(6);
    const size_t space = line.find(' ');
    if (auto at = number(line.substr(0, space))) next.line = *at;
    if (space == std::string_view::npos) continue;
    std::string_view source = line.substr(space + 1);
    while (!source.empty() && (source.back() == ' ' || source.back() == '\r')) source.remove_suffix(1);
    if (auto string = number(source)) next.source = *string;
  }
  return logical;
}

// The source string a validator's diagnostic names: glslang names string 0 by the name it was
// given (or "0" after a #line back to it), the others by their number.
std::optional<uint32_t> source_string(const std::string& file, std::string_view stage_name) {
  if (file.empty() || file == stage_name) return 0;
  return number(file);
}

// The generated lines (1-based) that are `line` of source string `source`: one, unless the emitter
// wrote several lines for one of the author's. At most kMaxShownPerMessage.
std::vector<uint32_t> generated_lines(const std::vector<LogicalLine>& logical, uint32_t source, uint32_t line) {
  std::vector<uint32_t> found;
  for (size_t index = 0; index < logical.size() && found.size() < kMaxShownPerMessage; ++index)
    if (logical[index].source == source && logical[index].line == line) found.push_back(uint32_t(index + 1));
  return found;
}

// The lines around each of `marked`, numbered, the marked ones flagged; ranges that touch are
// shown as one.
std::string excerpt_around(std::string_view text, const std::vector<uint32_t>& marked) {
  std::string excerpt;
  for (size_t first = 0; first < marked.size();) {
    size_t last = first;
    while (last + 1 < marked.size() && marked[last + 1] <= marked[last] + 2 * kContextLines + 1) ++last;
    const uint32_t from = marked[first] > kContextLines ? marked[first] - kContextLines : 1;
    excerpt += (excerpt.empty() ? "" : "    ...\n") + numbered_lines(text, from, marked[last] + kContextLines, marked);
    first = last + 1;
  }
  if (excerpt.ends_with('\n')) excerpt.pop_back();  // Error::to_string() puts one between
  return excerpt;
}

// The Internal error for a stage of xshade's output that a validator refused: the validator's
// messages, each at the generated line it names with the lines around it, or, where none names
// a line, the whole stage, numbered.
Error invalid_output(Target target, spirv::Stage stage, std::string_view text, std::string_view name,
                     const Error& refusal, const std::vector<std::string>& source_files) {
  const std::string what = spirv::is_spirv_validation_failure(refusal)
                               ? "compiles to SPIR-V that spirv-val refuses"
                               : fmt::format("is not valid {} (glslang refuses it)",
                                             target == Target::Gl ? "OpenGL GLSL 4.50 core" : "Vulkan GLSL");
  Error error{fmt::format("internal error: the {} stage xshade generated for --target {} {}. This is a bug in xshade, "
                          "not in the shader: please report it with the shader and what follows.",
                          stage_name(stage), target_name(target), what),
              {std::string(name), 0, 0},
              {},
              ErrorKind::Internal};
  std::vector<Diagnostic> refused = refusal.diagnostics;
  // glslang's log has its warnings too, and a summary without a line ("1 compilation errors.")
  // after the errors it counts; the errors are what the refusal is about.
  const auto keep_only = [&](auto&& wanted) {
    if (std::any_of(refused.begin(), refused.end(), wanted)) std::erase_if(refused, std::not_fn(wanted));
  };
  keep_only([](const Diagnostic& d) { return d.severity == Severity::Error; });
  keep_only([](const Diagnostic& d) { return d.where.line != 0; });
  // After its first error glslang says where it stopped, at the same line: nothing to add.
  std::erase_if(refused, [](const Diagnostic& d) { return d.message.starts_with("'' : compilation terminated"); });

  const std::vector<LogicalLine> logical = logical_lines(split_lines(text));
  std::vector<uint32_t> shown;  // generated lines already in an excerpt ("compilation terminated" repeats one)
  for (const Diagnostic& said : refused) {
    Diagnostic diagnostic{Severity::Error, said.where, said.message};
    while (diagnostic.message.ends_with(' ')) diagnostic.message.pop_back();  // glslang ends some with one
    const std::optional<uint32_t> source = source_string(said.where.file, name);
    if (!source || said.where.line == 0) {
      error.diagnostics.push_back(std::move(diagnostic));
      continue;
    }
    const std::vector<uint32_t> at = generated_lines(logical, *source, said.where.line);
    if (*source > 0 && *source < source_files.size()) {
      // The author's line: named, and which generated line it became.
      diagnostic.message += fmt::format(" (at {}:{}{})", source_files[*source], said.where.line,
                                        at.empty() ? "" : ", generated line " + std::to_string(at.front()));
      diagnostic.where.file = source_files[*source];
    }
    if (!at.empty()) {
      diagnostic.where = {std::string(name), at.front(), 0};
      if (std::find(shown.begin(), shown.end(), at.front()) == shown.end())
        diagnostic.excerpt = excerpt_around(text, at);
      shown.insert(shown.end(), at.begin(), at.end());
    }
    error.diagnostics.push_back(std::move(diagnostic));
  }
  if (shown.empty()) {
    std::string whole = numbered_lines(text, 1, uint32_t(logical.size()));
    if (whole.ends_with('\n')) whole.pop_back();
    error.diagnostics.push_back({Severity::Note,
                                 {std::string(name), 0, 0},
                                 fmt::format("the {} stage as generated:", stage_name(stage)),
                                 std::move(whole)});
  }
  return error;
}

// vk-hlsl: the source through glslang's HLSL front end, as the vk-hlsl lane runs it. What glslang
// refuses there is the author's HLSL (or a known divergence, docs/divergences.md); a module
}  // namespace

std::string numbered_lines(std::string_view text, uint32_t first, uint32_t last, const std::vector<uint32_t>& marked) {
  const std::vector<std::string_view> lines = split_lines(text);
  last = std::min<uint32_t>(last, uint32_t(lines.size()));
  const size_t width = std::to_string(last).size();
  std::string numbered;
  for (uint32_t line = std::max<uint32_t>(first, 1); line <= last; ++line) {
    const bool mark = std::find(marked.begin(), marked.end(), line) != marked.end();
    numbered += fmt::format("  {} {:>{}} | {}\n", mark ? '>' : ' ', line, width, lines[line - 1]);
  }
  return numbered;
}

Result<std::vector<uint32_t>> validate_generated_glsl(Target target, spirv::Stage stage, std::string_view text,
                                                      std::string_view name,
                                                      const std::vector<std::string>& source_files) {
  if (target == Target::Gl) {
    // Warnings are the driver's business; only a refusal stops the output.
    if (auto valid = spirv::validate_opengl_glsl(text, stage, name); !valid)
      return fail(invalid_output(target, stage, text, name, valid.error(), source_files));
    return std::vector<uint32_t>{};
  }
  // Vulkan GLSL is checked by compiling it, as the vk lane does, and the module by spirv-val.
  auto module = spirv::compile_vulkan_glsl(text, stage, name);
  if (!module) return fail(invalid_output(target, stage, text, name, module.error(), source_files));
  return std::move(module->words);
}

}  // namespace xshade::codegen
