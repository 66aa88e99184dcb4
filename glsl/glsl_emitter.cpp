// The GLSL emitter's driver: the parts of one stage's text and their order, the
// declarations (structs, uniform blocks, textures, static globals), the stage interface and main().
#include "glsl/glsl_emitter.h"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <functional>
#include <map>

#include "glsl/glsl_names.h"
#include "glsl/stage_emitter.h"
#include "hlsl_like/ast_walk.h"
#include "hlsl_like/semantics.h"

namespace xshade::glsl {

std::string constant_buffer_instance(std::string_view variable_name) {
  // Not the block's own name, which GLSL keeps apart; xs_ names are the emitter's.
  return "xs_cb_" + block_name(variable_name);
}

std::string block_name(std::string_view constant_buffer_name) {
  if (constant_buffer_name == hlsl::kGlobalsBufferName) return "xs_Globals";
  if (needs_renaming(constant_buffer_name)) return renamed(constant_buffer_name);
  return std::string(constant_buffer_name);
}

std::string buffer_block_name(std::string_view buffer_name) { return "xs_buffer_" + std::string(buffer_name); }

namespace detail {

using namespace hlsl;

std::string operand(const Code& code, int prec) {
  if (code.prec >= prec) return code.text;
  return "(" + code.text + ")";
}

std::string operand(Code&& code, int prec) {
  if (code.prec < prec) {
    code.text.insert(code.text.begin(), '(');
    code.text += ')';
  }
  return std::move(code.text);
}

void append_operand(std::string& out, const Code& code, int prec) {
  if (code.prec >= prec) {
    out += code.text;
    return;
  }
  out += '(';
  out += code.text;
  out += ')';
}

// ---------------------------------------------------------------------------------------------
// Writer and helpers

void Writer::line(const std::string& text) {
  text_.append(size_t(indent) * 2, ' ');
  text_ += text;
  text_ += '\n';
  if (mapped_) ++next_line_;
}

void Writer::line(std::initializer_list<std::string_view> parts) {
  text_.append(size_t(indent) * 2, ' ');
  for (std::string_view part : parts) text_ += part;
  text_ += '\n';
  if (mapped_) ++next_line_;
}

void Writer::mark(Loc loc) {
  if (loc.file == 0 || loc.line == 0) return;
  if (mapped_ && file_ == loc.file && next_line_ == loc.line) return;
  text_ += "#line ";
  text_ += std::to_string(loc.line);
  text_ += ' ';
  text_ += std::to_string(loc.file);
  text_ += '\n';
  mapped_ = true;
  file_ = loc.file;
  next_line_ = loc.line;
}

void Helpers::add(const std::string& signature, const std::string& definition) {
  if (definitions_.emplace(signature, definition).second) order_.push_back(signature);
}

std::string Helpers::text() const {
  std::string text;
  for (const std::string& signature : order_) text += definitions_.at(signature);
  return text;
}

// ---------------------------------------------------------------------------------------------
// The stage

namespace {

bool contains_matrix(const Type& type, int depth = 0) {
  if (depth > 64) return false;
  if (type.is_matrix()) return true;
  if (type.kind() == TypeKind::Array) return contains_matrix(type.element(), depth + 1);
  if (type.kind() == TypeKind::Struct && type.struct_decl()) {
    for (const FieldDecl& field : type.struct_decl()->fields)
      if (contains_matrix(field.type, depth + 1)) return true;
  }
  return false;
}

const char* interpolation_qualifier(Interpolation interpolation, const Type& type) {
  const Type& element = type.kind() == TypeKind::Array ? type.element() : type;
  if (element.is_integer() || element.is_bool()) return "flat ";
  switch (interpolation) {
    case Interpolation::NoInterpolation: return "flat ";
    case Interpolation::NoPerspective: return "noperspective ";
    case Interpolation::Centroid: return "centroid ";
    case Interpolation::Sample: return "sample ";
    case Interpolation::Default:
    case Interpolation::Linear: return "";
  }
  return "";
}

// One value crossing the stage boundary, after struct parameters and results are taken apart.
struct StageItem {
  std::string path;  // where the entry point's argument or result holds it: xs_arg0.uv
  Type type;
  std::string semantic;   // canonical
  ParsedSemantic parsed;  // parse_semantic of the author's spelling, which `semantic` parses to as well
  Interpolation interpolation = Interpolation::Default;
  Loc loc;
  std::string builtin = {};  // [[vk::builtin("PointSize")]]: written to GLSL's built-in, not a varying
};

void flatten(const Type& type, const std::string& path, const std::string& semantic, Interpolation interpolation,
             Loc loc, const std::string& builtin, const Names& names, std::vector<StageItem>& items, int depth = 0) {
  if (type.kind() == TypeKind::Struct && type.struct_decl() && depth < 64) {
    for (const FieldDecl& field : type.struct_decl()->fields)
      flatten(field.type, path + "." + names.of(field.name), field.semantic, field.interpolation, field.loc,
              field.vk.builtin, names, items, depth + 1);
    return;
  }
  if (semantic.empty()) return;
  const ParsedSemantic parsed = parse_semantic(semantic);
  items.push_back({path, type, canonical_semantic(parsed), parsed, interpolation, loc, builtin});
}

// The inputs (or outputs) of an entry point, with `xs_arg<i>` / `xs_result` paths.
std::vector<StageItem> stage_items(const FunctionDecl& entry, bool inputs, const Names& names) {
  std::vector<StageItem> items;
  for (size_t i = 0; i < entry.params.size(); ++i) {
    const ParamDecl* param = entry.params[i].get();
    if (!param || param->is_uniform || param->type.is_resource()) continue;
    const bool is_input = param->direction != ParamDirection::Out;
    const bool is_output = param->direction != ParamDirection::In;
    if (inputs ? is_input : is_output)
      flatten(param->type, "xs_arg" + std::to_string(i), param->semantic, param->interpolation, param->loc,
              param->vk.builtin, names, items);
  }
  if (!inputs && !entry.return_type.is_void())
    flatten(entry.return_type, "xs_result", entry.semantic, Interpolation::Default, entry.loc, {}, names, items);
  return items;
}

// "[N]" after the name of an array of N resources; nothing after a single one.
std::string array_suffix(uint32_t count) { return count > 1 ? "[" + std::to_string(count) + "]" : std::string(); }

// Direct3D's and Vulkan's clip and cull distance components, together.
constexpr uint32_t kMaxDistanceComponents = 8;

// Where each SV_ClipDistanceN (or SV_CullDistanceN) of a stage begins in gl_ClipDistance[] (or
// gl_CullDistance[]): in the order of N, as DXC packs them, each taking its components. Keyed by
// the item's path; `total` is the array's size.
struct DistancePacking {
  std::map<std::string, uint32_t> offsets;
  uint32_t total = 0;
};
DistancePacking pack_distances(const std::vector<StageItem>& items, SemanticKind kind) {
  std::vector<const StageItem*> distances;
  for (const StageItem& item : items)
    if (item.parsed.kind == kind) distances.push_back(&item);
  std::stable_sort(distances.begin(), distances.end(),
                   [](const StageItem* a, const StageItem* b) { return a->parsed.index < b->parsed.index; });
  DistancePacking packing;
  for (const StageItem* item : distances) {
    packing.offsets[item->path] = packing.total;
    packing.total += item->type.component_count();
  }
  return packing;
}

const StageVariable* find_variable(const std::vector<StageVariable>& variables, const std::string& semantic) {
  for (const StageVariable& variable : variables)
    if (variable.semantic == semantic) return &variable;
  return nullptr;
}

}  // namespace

namespace {

// `value` as a GLSL literal of `scalar`: a specialization constant's given value.
std::string scalar_value_text(double value, ScalarType scalar) {
  switch (scalar) {
    case ScalarType::Bool: return value != 0.0 ? "true" : "false";
    case ScalarType::Int: return std::to_string(int64_t(value));
    case ScalarType::Uint: return std::to_string(uint64_t(value)) + "u";
    default: {
      char buffer[32];
      const auto written = std::to_chars(buffer, buffer + sizeof buffer, float(value));  // the shortest exact spelling
      std::string text(buffer, written.ptr);
      if (text.find_first_of(".e") == std::string::npos) text += ".0";
      return text;
    }
  }
}

}  // namespace

StageEmitter::StageEmitter(const Module& module, const EmitOptions& options, const Names& names, bool vertex)
    : module_(module),
      reflection_(module.reflection),
      flavour_(options.flavour),
      half_(options.half_emulation),
      filter_comparisons_(options.filter_comparisons),
      specialization_(options.specialization),
      names_(names),
      vertex_(vertex),
      trace_(options.trace_nonfinite && !vertex),
      trace_program_(options.trace_program) {
  entry_ = vertex ? module.entry_points.vertex : module.entry_points.fragment;
}

void StageEmitter::fail(Loc loc, const std::string& message) {
  if (error_) return;
  // Rendered by the front end's own engine, so that what a target cannot express reads like every
  // other error: to_string() puts the location before "error: message" and the caret excerpt.
  hlsl::DiagnosticEngine diagnostics(module_.sources);
  diagnostics.error(loc, message);
  const SourceLocation where = module_.sources.resolve(loc);
  std::string rendered = diagnostics.render(0);
  if (where.known()) rendered.erase(0, where.to_string().size() + 2);  // "file:line:col: "
  error_ = Error{std::move(rendered), where, {}};
}

void StageEmitter::fail_internal(Loc loc, const std::string& what) {
  if (error_) return;
  fail(loc, "internal error: " + what);
  error_->kind = ErrorKind::Internal;
}

namespace {

// What a static global starts as in HLSL when it has no initializer: zero.
std::string zero_value(StageEmitter& emitter, const Type& type, Loc loc) {
  switch (type.kind()) {
    case TypeKind::Scalar:
    case TypeKind::Vector:
    case TypeKind::Matrix: {
      const char* zero = "0.0";
      switch (type.scalar_type()) {
        case ScalarType::Bool: zero = "false"; break;
        case ScalarType::Int: zero = "0"; break;
        case ScalarType::Uint: zero = "0u"; break;
        case ScalarType::Half:
        case ScalarType::Float: break;
      }
      if (type.component_count() == 1) return zero;
      return emitter.type_name(type, loc) + "(" + zero + ")";  // mat3(0.0) is all zeros
    }
    case TypeKind::Struct: {
      std::string text = emitter.type_name(type, loc) + "(";
      if (type.struct_decl()) {
        bool first = true;
        for (const FieldDecl& field : type.struct_decl()->fields) {
          if (!first) text += ", ";
          first = false;
          text += zero_value(emitter, field.type, loc);
        }
      }
      return text + ")";
    }
    case TypeKind::Array: {
      std::string text = emitter.type_name(type, loc) + "(";
      const std::string element = zero_value(emitter, type.element(), loc);
      for (uint32_t i = 0; i < type.array_length(); ++i) text += (i ? ", " : "") + element;
      return text + ")";
    }
    default: emitter.fail(loc, "cannot give a value of type " + in_quotes(type.name()) + " a zero value"); return "0";
  }
}

}  // namespace

std::string StageEmitter::run() {
  if (!entry_) return {};
  // The lowering passes decide; what follows prints what they decided.
  lower::UsedDeclarations used = lower::used_declarations(module_, entry_);
  functions_ = std::move(used.functions);
  statics_ = std::move(used.statics);
  used_structs_ = std::move(used.structs);
  constant_buffer_members_ = lower::split_constant_buffers(module_);
  unrolled_loops_ = lower::unroll_offset_loops(functions_);
  if (flavour_ == Flavour::Gl) compared_ = lower::compared_textures(module_);

  // Static globals first, so that functions see which of them are GLSL constants.
  Writer statics;
  std::vector<std::string> prologue;  // main() initializes the statics GLSL cannot
  for (const VarDecl* var : statics_) {
    if (var->storage == StorageClass::GroupShared) {
      fail(var->loc, "groupshared variable " + in_quotes(var->name) +
                         " is not supported: vertex and fragment shaders have no thread groups to share it");
      continue;
    }
    const std::string name = names_.variable(var);
    const std::string declaration = declarator(var->type, name, var->loc);
    if (!var->initializer) {
      statics.line(declaration + " = " + zero_value(*this, var->type, var->loc) + ";");
      continue;
    }
    // A constant rounded by half emulation calls xs_half, which no GLSL constant expression may.
    const std::string value = initializer(*var);
    if (is_constant(var->initializer.get()) && value.find("xs_half(") == std::string::npos) {
      if (var->is_const) const_decls_.insert(var);
      // [[vk::constant_id(N)]]: a specialization constant, whose default the pipeline replaces
      // on Vulkan; on OpenGL the value given for it is the constant's.
      const std::string specialized = var->vk.constant_id && flavour_ == Flavour::Vk
                                          ? "layout(constant_id = " + std::to_string(*var->vk.constant_id) + ") "
                                          : "";
      const auto given = var->vk.constant_id && flavour_ == Flavour::Gl ? specialization_.find(*var->vk.constant_id)
                                                                        : specialization_.end();
      const std::string written =
          given != specialization_.end() ? scalar_value_text(given->second, var->type.scalar_type()) : value;
      statics.line(specialized + (var->is_const ? "const " : "") + declaration + " = " + written + ";");
    } else {
      // main() assigns it first, but functions above main() read it, and Mesa's GLSL compiler,
      // which reads in source order, would warn that they read it uninitialized (a driver
      // warning fails the gl lane); a scalar, vector or matrix starts at zero to say otherwise.
      const TypeKind kind = var->type.kind();
      const bool zeroable = kind == TypeKind::Scalar || kind == TypeKind::Vector || kind == TypeKind::Matrix;
      statics.line(declaration + (zeroable ? " = " + zero_value(*this, var->type, var->loc) : std::string()) + ";");
      prologue.push_back(name + " = " + value + ";");
    }
  }

  for (const FunctionDecl* f : functions_) function(*f);
  if (trace_) traced_functions();

  // Declarations, the stage interface and main().
  std::string declared = declarations();
  declared += statics.text();
  main_prologue_ = std::move(prologue);
  const std::string main_text = interface_and_main();  // also sets interface_text_

  const std::string helpers = helpers_.text();
  std::string text;
  text.reserve(512 + declared.size() + interface_text_.size() + helpers.size() + out_.text().size() + main_text.size());
  text += flavour_ == Flavour::Gl ? "#version 450 core\n" : "#version 450\n";
  for (const std::string& extension : extensions_) text += "#extension " + extension + " : require\n";
  text += "// Generated by xshade from hlsl_like: the ";
  text += vertex_ ? "vertex" : "fragment";
  text += " stage of entry point '" + entry_->name + "', " + std::string(flavour_name(flavour_)) + " flavour.\n";
  for (uint32_t file = 1; file < module_.sources.file_count(); ++file)
    text += "// file " + std::to_string(file) + ": " + module_.sources.name(file) + "\n";
  text += declared;
  text += interface_text_;
  text += helpers;
  text += out_.text();
  size_t lines = 0;
  for (const char* at = text.data();
       (at = static_cast<const char*>(std::memchr(at, '\n', size_t(text.data() + text.size() - at)))); ++at)
    ++lines;
  text += "#line " + std::to_string(lines + 2) + " 0\n";  // main() is generated text
  text += main_text;
  return text;
}

std::string StageEmitter::declarations() {
  Writer w;
  for (const auto& decl : module_.unit.decls) {
    if (!decl || decl->kind != DeclKind::Struct) continue;
    const auto& s = static_cast<const StructDecl&>(*decl);
    // A struct of resources has no GLSL form: its locals and parameters are flattened.
    if (!used_structs_.count(&s) || !resource_paths(Type::structure(&s)).empty()) continue;
    if (s.fields.empty()) {
      fail(s.loc, "struct " + in_quotes(s.name) + " has no fields; GLSL does not allow empty structs");
      continue;
    }
    w.line("struct " + names_.type(&s) + " {");
    w.indent = 1;
    for (const FieldDecl& field : s.fields) w.line({declarator(field.type, names_.of(field.name), field.loc), ";"});
    w.indent = 0;
    w.line("};");
  }

  // Vulkan's descriptor set, and the binding: a uniform-block binding point or texture unit on gl.
  const auto place = [&](uint32_t set, uint32_t binding) {
    return (flavour_ == Flavour::Vk ? "set = " + std::to_string(set) + ", " : std::string()) +
           "binding = " + std::to_string(binding);
  };
  for (const ConstantBuffer& buffer : reflection_.constant_buffers) {
    // ConstantBuffer<S> cb is read as cb.field: a block with an instance name.
    const bool view = buffer.decl && buffer.decl->kind == DeclKind::Var;
    // A push-constant block keeps HLSL's packing (std140 strides, explicit offsets) as a uniform
    // block does; gl has no push constants and reads it as a uniform block.
    const std::string where =
        flavour_ == Flavour::Vk && buffer.push_constant ? "push_constant" : place(buffer.set, buffer.binding);
    w.line("layout(std140, " + where + ") uniform " + block_name(buffer.name) + " {");
    w.indent = 1;
    for (const ConstantBufferMember& member : buffer.members) {
      const std::string name = names_.of(member.name);
      const auto decl =
          view ? constant_buffer_members_.by_name.end() : constant_buffer_members_.by_name.find(member.name);
      const Loc loc = decl != constant_buffer_members_.by_name.end() ? decl->second->loc
                      : buffer.decl                                  ? buffer.decl->loc
                                                                     : Loc{};
      if (member.split_into_scalars && view) {
        fail(loc, "field " + in_quotes(member.name) + " of " + in_quotes(buffer.name) + " is at offset " +
                      std::to_string(member.offset) + ", which std140 cannot give a " + in_quotes(member.type.name()) +
                      "; reorder the struct's fields or pad them to 16-byte registers");
        continue;
      }
      if (member.split_into_scalars) {
        const std::string scalar = type_name(Type::scalar(member.type.scalar_type()), loc);
        for (uint32_t i = 0; i < member.type.cols(); ++i)
          w.line("layout(offset = " + std::to_string(member.offset + 4 * i) + ") " + scalar + " " +
                 names_.split_member(member.name, i) + ";");
        continue;
      }
      // HLSL's column_major M is GLSL's row_major G = M^T, byte for byte.
      const char* major = !contains_matrix(member.type) ? "" : member.row_major ? ", column_major" : ", row_major";
      w.line({"layout(offset = ", std::to_string(member.offset), major, ") ", declarator(member.type, name, loc), ";"});
    }
    w.indent = 0;
    w.line(view ? "} " + constant_buffer_instance(buffer.name) + array_suffix(buffer.count) + ";" : "};");
  }

  // An array of resources is a GLSL array: its elements at consecutive bindings on gl (texture
  // units, uniform-block binding points), one binding of that many descriptors on vk.
  const auto element_type = [](const VarDecl& decl) -> const Type& {
    return decl.type.is_resource_array() ? decl.type.element() : decl.type;
  };
  for (const TextureResource& texture : reflection_.textures) {
    if (!texture.used || !texture.decl) continue;
    // A subpass input names its input attachment on vk; gl reads it as a texture.
    const std::optional<uint32_t> attachment = texture.decl->vk.input_attachment_index;
    const std::string binding =
        "layout(" +
        (flavour_ == Flavour::Vk && attachment ? "input_attachment_index = " + std::to_string(*attachment) + ", "
                                               : std::string()) +
        place(texture.set, texture.binding) + ") uniform ";
    w.line(binding + resource_type(element_type(*texture.decl), texture.decl, texture.decl->loc) + " " +
           names_.of(texture.name) + array_suffix(texture.count) + ";");
  }
  for (const StorageBufferResource& buffer : reflection_.buffers)
    if (buffer.used && buffer.decl) w.line(buffer_declaration(buffer));
  if (flavour_ == Flavour::Vk) {
    for (const SamplerResource& sampler : reflection_.samplers)
      if (sampler.used && sampler.decl)
        w.line("layout(" + place(sampler.set, sampler.binding) + ") uniform " +
               resource_type(element_type(*sampler.decl), sampler.decl, sampler.decl->loc) + " " +
               names_.of(sampler.name) + array_suffix(sampler.count) + ";");
  }
  return w.text();
}

std::string StageEmitter::interface_and_main() {
  const FunctionDecl& entry = *entry_;
  Writer interface;
  Writer main;
  main.line("void main() {");
  main.indent = 1;
  for (const std::string& line : main_prologue_) main.line(line);

  // Arguments.
  for (size_t i = 0; i < entry.params.size(); ++i) {
    const ParamDecl* param = entry.params[i].get();
    if (!param) continue;
    if (param->is_uniform) {
      fail(param->loc, "uniform parameter " + in_quotes(param->name) +
                           " of an entry point is not supported on this target; declare it as a global");
      continue;
    }
    if (param->type.is_resource()) {
      fail(param->loc,
           "entry point parameter " + in_quotes(param->name) + " cannot be a resource; declare it as a global");
      continue;
    }
    main.line(declarator(param->type, "xs_arg" + std::to_string(i), param->loc) + ";");
  }

  // Inputs.
  std::vector<TracedItem> traced_inputs, traced_outputs;  // the tracing variant's (emit_trace.cpp)
  std::vector<std::string> declared;
  auto declare = [&](const std::string& line) {
    if (std::find(declared.begin(), declared.end(), line) != declared.end()) return;
    declared.push_back(line);
    interface.line(line);
  };
  auto check_storable = [&](const StageItem& item) {
    const Type& element = item.type.kind() == TypeKind::Array ? item.type.element() : item.type;
    if (element.is_bool()) {
      fail(item.loc, in_quotes(item.semantic) + " has type " + in_quotes(item.type.name()) +
                         "; stage inputs and outputs cannot be bool in GLSL; use int or uint");
      return false;
    }
    return true;
  };
  // Clip and cull distances cross as GLSL's built-in arrays, sized to what the stage packs in
  // them; Direct3D allows eight components of both together.
  const std::vector<StageItem> distance_items = stage_items(entry, !vertex_, names_);
  const DistancePacking clip = pack_distances(distance_items, SemanticKind::SvClipDistance);
  const DistancePacking cull = pack_distances(distance_items, SemanticKind::SvCullDistance);
  if (clip.total + cull.total > kMaxDistanceComponents)
    fail(entry.loc, "entry point " + in_quotes(entry.name) + " has " + std::to_string(clip.total + cull.total) +
                        " clip and cull distance components; Direct3D and Vulkan allow " +
                        std::to_string(kMaxDistanceComponents) + " in all");
  for (const auto& [packing, array] : {std::pair{&clip, "gl_ClipDistance"}, std::pair{&cull, "gl_CullDistance"}})
    if (packing->total != 0)
      interface.line(std::string(vertex_ ? "out" : "in") + " float " + array + "[" + std::to_string(packing->total) +
                     "];");
  // The components of one distance item as `array[offset + c]`.
  auto distance_element = [&](const StageItem& item, uint32_t component) {
    const bool is_clip = item.parsed.kind == SemanticKind::SvClipDistance;
    const DistancePacking& packing = is_clip ? clip : cull;
    return std::string(is_clip ? "gl_ClipDistance[" : "gl_CullDistance[") +
           std::to_string(packing.offsets.at(item.path) + component) + "]";
  };
  auto is_distance = [](const StageItem& item) {
    return item.parsed.kind == SemanticKind::SvClipDistance || item.parsed.kind == SemanticKind::SvCullDistance;
  };

  for (const StageItem& item : stage_items(entry, true, names_)) {
    if (!item.builtin.empty()) {
      // vk::builtin("PointSize") of a struct the fragment stage reads too: nothing arrives in it.
      main.line(item.path + " = " + zero_value(*this, item.type, item.loc) + ";");
      continue;
    }
    const SemanticKind kind = item.parsed.kind;
    Code source;
    Type source_type = item.type;
    if (vertex_) {
      if (kind == SemanticKind::SvVertexId) {
        source = {flavour_ == Flavour::Gl ? "gl_VertexID" : "gl_VertexIndex"};
        source_type = Type::scalar(ScalarType::Int);
      } else if (kind == SemanticKind::SvInstanceId) {
        // Draws start at instance 0 on both APIs, where the two builtins agree.
        source = {flavour_ == Flavour::Gl ? "gl_InstanceID" : "gl_InstanceIndex"};
        source_type = Type::scalar(ScalarType::Int);
      } else {
        if (!check_storable(item)) continue;
        std::optional<uint32_t> location;
        if (const StageVariable* variable = find_variable(reflection_.vertex_inputs, item.semantic))
          location = variable->location;
        else
          location = vertex_input_location(item.semantic);
        if (!location) {
          fail(item.loc, "vertex input " + in_quotes(item.semantic) + " has no location in the vertex format");
          continue;
        }
        const std::string name = "xs_in_" + item.semantic;
        declare("layout(location = " + std::to_string(*location) + ") in " + declarator(item.type, name, item.loc) +
                ";");
        source = {name};
      }
    } else if (kind == SemanticKind::SvPosition || is_clip_position_alias(item.parsed, item.type)) {
      // Direct3D's position w is the clip-space w; GL's gl_FragCoord.w is its reciprocal.
      source = {"vec4(gl_FragCoord.xyz, 1.0 / gl_FragCoord.w)"};
      source_type = Type::vector(ScalarType::Float, 4);
    } else if (kind == SemanticKind::SvIsFrontFace) {
      source = {"gl_FrontFacing"};
      source_type = Type::scalar(ScalarType::Bool);
    } else if (kind == SemanticKind::Vface) {
      source = {"(gl_FrontFacing ? 1.0 : -1.0)"};
      source_type = Type::scalar(ScalarType::Float);
    } else if (kind == SemanticKind::SvShadingRate) {
      // OpenGL has no variable-rate shading: every fragment is shaded alone, D3D's 1x1, 0.
      if (flavour_ == Flavour::Vk) require_extension("GL_EXT_fragment_shading_rate");
      source = {flavour_ == Flavour::Vk ? "uint(gl_ShadingRateEXT)" : "0u"};
      source_type = Type::scalar(ScalarType::Uint);
    } else if (is_distance(item)) {
      const uint32_t n = item.type.component_count();
      std::string elements;
      for (uint32_t c = 0; c < n; ++c) elements += (c ? ", " : "") + distance_element(item, c);
      source = {n == 1 ? elements : "vec" + std::to_string(n) + "(" + elements + ")"};
      source_type = Type::with_scalar(item.type, ScalarType::Float);
    } else {
      if (!check_storable(item)) continue;
      // Declared as the vertex stage writes it, so that both stages agree on the type.
      std::optional<uint32_t> location;
      if (const StageVariable* variable = find_variable(reflection_.varyings, item.semantic)) {
        location = variable->location;
        source_type = variable->type;
      } else {
        location = varying_location(item.semantic);
      }
      if (!location) {
        fail(item.loc, "fragment input " + in_quotes(item.semantic) + " has no varying location");
        continue;
      }
      const std::string name = "xs_v_" + item.semantic;
      declare("layout(location = " + std::to_string(*location) + ") " +
              interpolation_qualifier(item.interpolation, source_type) + "in " +
              declarator(source_type, name, item.loc) + ";");
      source = {name};
    }
    main.line(item.path + " = " + convert(source, source_type, item.type, item.loc).text + ";");
    if (trace_) {  // what arrives from the vertex stage is tested by its semantic; builtins are not
      const bool varying = !vertex_ && source.text.rfind("xs_v_", 0) == 0;
      traced_inputs.push_back({item.path, item.type, varying ? item.semantic : std::string(), item.loc});
    }
  }

  // The call.
  std::string call = names_.function(&entry) + "(";
  for (size_t i = 0; i < entry.params.size(); ++i) call += (i ? ", xs_arg" : "xs_arg") + std::to_string(i);
  call += ")";
  if (entry.return_type.is_void())
    main.line(call + ";");
  else
    main.line(declarator(entry.return_type, "xs_result", entry.loc) + " = " + call + ";");

  // Outputs.
  std::unordered_map<std::string, Interpolation> fragment_interpolation;
  if (vertex_ && module_.entry_points.fragment) {
    for (const StageItem& item : stage_items(*module_.entry_points.fragment, true, names_))
      fragment_interpolation.emplace(item.semantic, item.interpolation);
  }
  for (const StageItem& item : stage_items(entry, false, names_)) {
    const ParsedSemantic& parsed = item.parsed;
    const Code value{item.path, kPostfix};
    if (vertex_ && (parsed.kind == SemanticKind::SvPosition || is_clip_position_alias(parsed, item.type))) {  // DX9's
      main.line("gl_Position = " + convert(value, item.type, Type::vector(ScalarType::Float, 4), item.loc).text + ";");
      continue;
    }
    if (vertex_ && item.builtin == "PointSize") {
      main.line("gl_PointSize = " + convert(value, item.type, Type::scalar(ScalarType::Float), item.loc).text + ";");
      continue;
    }
    if (vertex_ && is_distance(item)) {
      const uint32_t n = item.type.component_count();
      static const char* const kComponent[] = {".x", ".y", ".z", ".w"};
      for (uint32_t c = 0; c < n; ++c)
        main.line(distance_element(item, c) + " = float(" + item.path + (n == 1 ? "" : kComponent[c]) + ");");
      continue;
    }
    if (!vertex_ && parsed.kind == SemanticKind::SvDepth) {
      main.line("gl_FragDepth = " + convert(value, item.type, Type::scalar(ScalarType::Float), item.loc).text + ";");
      continue;
    }
    if (!check_storable(item)) continue;
    if (vertex_) {
      std::optional<uint32_t> location;
      if (const StageVariable* variable = find_variable(reflection_.varyings, item.semantic))
        location = variable->location;
      else
        location = varying_location(item.semantic);
      if (!location) {
        fail(item.loc, "vertex output " + in_quotes(item.semantic) + " has no varying location");
        continue;
      }
      // The fragment stage's interpolation, so that both sides declare the same.
      Interpolation interpolation = item.interpolation;
      if (auto it = fragment_interpolation.find(item.semantic); it != fragment_interpolation.end())
        interpolation = it->second;
      const std::string name = "xs_v_" + item.semantic;
      declare("layout(location = " + std::to_string(*location) + ") " +
              interpolation_qualifier(interpolation, item.type) + "out " + declarator(item.type, name, item.loc) + ";");
      main.line(name + " = " + item.path + ";");
    } else {
      // SV_TargetN, and DX9's COLORn, are render target N.
      const std::string name = "xs_target" + std::to_string(parsed.index);
      declare("layout(location = " + std::to_string(parsed.index) + ") out " + declarator(item.type, name, item.loc) +
              ";");
      main.line(name + " = " + item.path + ";");
      if (trace_ && parsed.index == 1)
        fail(item.loc, "the tracing variant records at fragment output location 1, which " + in_quotes(item.semantic) +
                           " takes; trace a shader that writes SV_Target0 only");
      if (trace_) traced_outputs.push_back({item.path, item.type, item.semantic, item.loc});
    }
  }
  if (trace_) traced_main(main, interface, traced_inputs, traced_outputs);
  main.indent = 0;
  main.line("}");
  interface_text_ = interface.text();
  return main.text();
}

}  // namespace detail

Result<EmittedProgram> emit(const hlsl::Module& module, const EmitOptions& options) {
  if (!module.ok()) return fail(ErrorKind::UserInput, "cannot emit GLSL for a module with errors");
  EmittedProgram program;
  program.source_files.emplace_back();
  for (uint32_t file = 1; file < module.sources.file_count(); ++file)
    program.source_files.push_back(module.sources.name(file));
  const lower::Names names(module.unit, options.flavour);
  for (const bool vertex : {true, false}) {
    const hlsl::FunctionDecl* entry = vertex ? module.entry_points.vertex : module.entry_points.fragment;
    if (!entry) continue;
    if (options.trace_nonfinite && options.trace_program >= NonfiniteTrace::kMaxPrograms)
      return fail(ErrorKind::UserInput,
                  "the tracing variant numbers at most " + std::to_string(NonfiniteTrace::kMaxPrograms) + " programs");
    detail::StageEmitter emitter(module, options, names, vertex);
    std::string text = emitter.run();
    if (emitter.error()) return fail(*emitter.error());
    (vertex ? program.vertex : program.fragment) = EmittedStage{std::move(text)};
    if (!vertex && options.trace_nonfinite) program.trace = emitter.take_trace();
  }
  for (const hlsl::ConstantBuffer& buffer : module.reflection.constant_buffers)
    program.names.blocks[buffer.name] = block_name(buffer.name);
  for (const hlsl::TextureResource& texture : module.reflection.textures)
    program.names.textures[texture.name] = names.of(texture.name);
  for (const hlsl::StorageBufferResource& buffer : module.reflection.buffers)
    program.names.storage_blocks[buffer.name] = buffer_block_name(buffer.name);
  return program;
}

}  // namespace xshade::glsl
