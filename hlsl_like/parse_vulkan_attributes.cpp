// Vulkan's attributes in C++11 form, `[[vk::name(args)]]`, as DXC's SPIR-V back end defines
// them: read onto the declaration that follows (a global, a parameter, a struct field, a
// cbuffer). What each means is decided where it is used (reflection, the emitter); here each is
// read with its arguments' kinds checked, and one xshade does not implement is an error at its
// name that says what it is.
#include <string>

#include "hlsl_like/parser_internal.h"

namespace xshade::hlsl::parser_detail {
namespace {

// Attributes DXC defines that xshade reads but does not implement, with what to do instead.
std::optional<std::string> not_implemented(const std::string& name) {
  if (name.rfind("ext_", 0) == 0)
    return "SPIR-V extension instructions and types (vk::" + name +
           ") are not supported: they need DXC's SPIR-V "
           "back end";
  if (name == "counter_binding" || name == "shader_record_nv" || name == "shader_record_ext" ||
      name == "shader_record_buffer" || name == "index" || name == "post_depth_coverage" ||
      name == "early_and_late_tests")
    return "vk::" + name + " is not supported: it belongs to resources or stages xshade does not compile";
  return std::nullopt;
}

}  // namespace

// [[ns::name(args), ...]] [[...]]: any number of groups in a row. Only the vk namespace means
// something to xshade; another namespace's attribute is skipped with a note.
bool Parser::parse_vulkan_attributes(VulkanAttributes& out) {
  while (at_vulkan_attribute()) {
    const size_t open = pos_;
    advance();
    advance();
    for (;;) {
      if (cur().kind != TokenKind::Identifier) {
        error_here("expected an attribute name, as in [[vk::location(0)]]");
        return false;
      }
      const size_t name_index = pos_;
      std::string space, name(cur().text);
      advance();
      if (accept("::")) {
        if (cur().kind != TokenKind::Identifier) {
          error_here("expected an attribute name after '" + name + "::'");
          return false;
        }
        space = std::move(name);
        name = std::string(cur().text);
        advance();
      }
      // The arguments: integers, or one string (vk::builtin, vk::image_format).
      std::vector<uint32_t> numbers;
      std::string text;
      if (is("(")) {
        const size_t paren = pos_;
        advance();
        while (!is(")")) {
          if (cur().kind == TokenKind::StringLiteral) {
            text = std::string(cur().text.substr(1, cur().text.size() - 2));
            advance();
          } else if (cur().kind == TokenKind::IntLiteral) {
            const IntValue value = parse_int_spelling(cur().text);
            if (!value.valid || value.too_large || value.value > UINT32_MAX) {
              error_here("invalid integer " + in_quotes(cur().text));
              return false;
            }
            numbers.push_back(uint32_t(value.value));
            advance();
          } else {
            error_here("expected an integer or a string as the argument of an attribute");
            return false;
          }
          if (accept(",")) continue;
          if (!is(")")) {
            error_unmatched(")", paren);
            return false;
          }
        }
        advance();
      }
      const Loc loc = tok(name_index).loc;
      if (!out.any()) out.loc = loc;
      const auto arguments = [&](size_t least, size_t most, bool string) {
        if (numbers.size() >= least && numbers.size() <= most && string == !text.empty()) return true;
        const std::string takes = string          ? "a string"
                                  : most == 0     ? "no arguments"
                                  : least == most ? std::to_string(least) + " integer" + (least == 1 ? "" : "s")
                                                  : std::to_string(least) + " or " + std::to_string(most) + " integers";
        error_at(name_index, "vk::" + name + " takes " + takes);
        return false;
      };
      if (space != "vk") {
        diagnostics_.note(loc, "attribute " + in_quotes(space.empty() ? name : space + "::" + name) + " is ignored");
      } else if (name == "location") {
        if (!arguments(1, 1, false)) return false;
        out.location = numbers[0];
      } else if (name == "binding") {
        if (!arguments(1, 2, false)) return false;
        out.binding = numbers[0];
        out.set = numbers.size() > 1 ? numbers[1] : 0;
      } else if (name == "push_constant") {
        if (!arguments(0, 0, false)) return false;
        out.push_constant = true;
      } else if (name == "constant_id") {
        if (!arguments(1, 1, false)) return false;
        out.constant_id = numbers[0];
      } else if (name == "builtin") {
        if (!arguments(0, 0, true)) return false;
        if (text != "PointSize") {
          error_at(name_index,
                   "vk::builtin(\"" + text + "\") is not supported; xshade writes vk::builtin(\"PointSize\")");
          return false;
        }
        out.builtin = text;
      } else if (name == "combinedImageSampler") {
        if (!arguments(0, 0, false)) return false;
        out.combined_image_sampler = true;
      } else if (name == "offset") {
        if (!arguments(1, 1, false)) return false;
        out.offset = numbers[0];
      } else if (name == "input_attachment_index") {
        if (!arguments(1, 1, false)) return false;
        out.input_attachment_index = numbers[0];
      } else if (name == "image_format") {
        // The format of a storage image's texels, for reads without the shaderStorageImageReadWithoutFormat
        // feature: xshade reads no storage image in a vertex or fragment stage.
        if (!arguments(0, 0, true)) return false;
        diagnostics_.note(loc, "attribute 'vk::image_format' is ignored: it describes a storage image");
      } else if (const std::optional<std::string> why = not_implemented(name)) {
        error_at(name_index, *why);
        return false;
      } else {
        error_at(name_index, "unknown Vulkan attribute " + in_quotes("vk::" + name) +
                                 "; DXC defines vk::location, vk::binding, vk::push_constant, vk::constant_id, "
                                 "vk::builtin and others");
        return false;
      }
      if (accept(",")) continue;
      break;
    }
    if (!is("]") || tok(pos_ + 1).kind != TokenKind::Punct || tok(pos_ + 1).text != "]") {
      error_unmatched("]]", open);
      return false;
    }
    advance();
    advance();
  }
  return true;
}

}  // namespace xshade::hlsl::parser_detail
