// Why this file is long: the reflection is one walk of the analysed tree that fills every part of
// it (constant-buffer packing with packoffset, bindings, texture shapes, stage interfaces,
// properties, keywords) and its JSON, each part reading what the earlier ones found.
#include "hlsl_like/reflection.h"

#include <algorithm>
#include <map>
#include <set>
#include <unordered_set>

#include "hlsl_like/ast_walk.h"
#include "hlsl_like/resource_origins.h"
#include "hlsl_like/sema_internal.h"
#include "hlsl_like/semantics.h"
#include "hlsl_like/vulkan_bindings.h"

namespace xshade::hlsl {
namespace {

constexpr uint32_t kRegister = 16;  // bytes in one HLSL constant register

uint32_t align_up(uint32_t value, uint32_t alignment) { return (value + alignment - 1) / alignment * alignment; }

// ---------------------------------------------------------------------------------------------
// HLSL constant-buffer packing (the fxc/dxc rules for cbuffers):
// - a scalar or vector packs after the previous member unless it would cross a 16-byte register;
// - arrays, matrices and structs start a new register; array elements are 16-byte aligned and the
//   last one is not padded; a matrix is an array of its columns (column_major) or rows;
// - the member after a struct starts a new register.

uint32_t packed_size(const Type& type, bool row_major);

uint32_t struct_packed_size(const StructDecl* decl) {
  uint32_t offset = 0;
  bool new_register = false;
  for (const FieldDecl& field : decl->fields) {
    const uint32_t size = packed_size(field.type, false);
    const bool starts_register = new_register || (!field.type.is_scalar() && !field.type.is_vector());
    if (starts_register || (offset % kRegister) + size > kRegister) offset = align_up(offset, kRegister);
    offset += size;
    new_register = field.type.kind() == TypeKind::Struct;
  }
  return offset;
}

uint32_t packed_size(const Type& type, bool row_major) {
  switch (type.kind()) {
    case TypeKind::Scalar:
    case TypeKind::Vector: return 4 * type.cols();
    case TypeKind::Matrix:
      return row_major ? kRegister * (type.rows() - 1) + 4 * type.cols()
                       : kRegister * (type.cols() - 1) + 4 * type.rows();
    case TypeKind::Array: {
      const uint32_t element = packed_size(type.element(), row_major);
      return align_up(element, kRegister) * (type.array_length() - 1) + element;
    }
    case TypeKind::Struct: return type.struct_decl() ? struct_packed_size(type.struct_decl()) : 0;
    default: return 0;
  }
}

// The bytes std140 gives a member (what a following explicit offset must not fall inside).
uint32_t std140_size(const Type& type, bool row_major) {
  switch (type.kind()) {
    case TypeKind::Scalar:
    case TypeKind::Vector: return 4 * type.cols();
    // A matrix is an array of vectors, each rounded up to a register. HLSL column_major floatRxC
    // is GLSL row_major with C rows (the emitter stores HLSL's M as GLSL's transpose).
    case TypeKind::Matrix: return kRegister * (row_major ? type.rows() : type.cols());
    case TypeKind::Array: return align_up(std140_size(type.element(), row_major), kRegister) * type.array_length();
    case TypeKind::Struct: return align_up(packed_size(type, row_major), kRegister);
    default: return 0;
  }
}

// Offsets std140 gives the fields of a struct; HLSL's must be the same, since GLSL allows no
// explicit offsets inside a struct.
std::optional<std::string> struct_layout_mismatch(const StructDecl* decl) {
  uint32_t hlsl = 0, std140 = 0;
  bool new_register = false;
  for (const FieldDecl& field : decl->fields) {
    const Type& type = field.type;
    const uint32_t size = packed_size(type, false);
    if (new_register || (!type.is_scalar() && !type.is_vector()) || (hlsl % kRegister) + size > kRegister)
      hlsl = align_up(hlsl, kRegister);
    const uint32_t alignment = type.is_scalar() ? 4 : type.is_vector() ? (type.cols() == 2 ? 8 : 16) : 16;
    std140 = align_up(std140, alignment);
    if (hlsl != std140)
      return "field " + in_quotes(field.name) + " is at offset " + std::to_string(hlsl) + " in HLSL but " +
             std::to_string(std140) + " in std140";
    if (type.kind() == TypeKind::Struct && type.struct_decl())
      if (auto inner = struct_layout_mismatch(type.struct_decl())) return inner;
    hlsl += size;
    std140 += std140_size(type, false);
    new_register = type.kind() == TypeKind::Struct;
  }
  return std::nullopt;
}

// A constant-buffer member as packing sees it: a cbuffer's variable or a ConstantBuffer<S>'s field.
struct PackedItem {
  std::string name;
  Type type;
  bool row_major = false;
  Loc loc;
  std::optional<uint32_t> packoffset;  // bytes, when the member has : packoffset(cN.y)
  std::optional<uint32_t> vk_offset;   // bytes, when it has [[vk::offset(N)]]
};

// Lays out `members` by HLSL rules (packoffset where given; after the previous member otherwise)
// and checks that the std140 block, which lists them by offset, can hold them.
void pack_members(ConstantBuffer& buffer, const std::vector<PackedItem>& members, DiagnosticEngine& diagnostics) {
  uint32_t offset = 0;
  bool new_register = false;
  uint32_t end = 0;
  std::vector<const PackedItem*> items;
  for (const PackedItem& item : members) {
    const Type& type = item.type;
    ConstantBufferMember member;
    member.name = item.name;
    member.type = type;
    member.row_major = item.row_major;
    member.size = packed_size(type, member.row_major);
    const bool starts_register = !type.is_scalar() && !type.is_vector();
    if (item.vk_offset) {
      // Vulkan's explicit offset: no HLSL register rule, only what the std140 block can hold.
      member.offset = *item.vk_offset;
      if (starts_register && member.offset % kRegister != 0)
        diagnostics.error(item.loc, "vk::offset(" + std::to_string(member.offset) + ") of " + in_quotes(item.name) +
                                        ": an array, matrix or struct starts at a multiple of 16 bytes in the std140 "
                                        "block the targets read");
    } else if (item.packoffset) {
      member.offset = *item.packoffset;
      const std::string where =
          "c" + std::to_string(member.offset / kRegister) +
          (member.offset % kRegister ? std::string(".") + "xyzw"[member.offset % kRegister / 4] : "");
      if (starts_register && member.offset % kRegister != 0)
        diagnostics.error(item.loc, "packoffset(" + where + ") of " + in_quotes(item.name) +
                                        ": arrays, matrices and structs start a register; write packoffset(c" +
                                        std::to_string(member.offset / kRegister) + ")");
      else if (!starts_register && member.offset % kRegister + member.size > kRegister)
        diagnostics.error(item.loc, "packoffset(" + where + ") of " + in_quotes(item.name) + " puts its " +
                                        std::to_string(member.size) + " bytes across a 16-byte register");
    } else {
      if (new_register || starts_register || (offset % kRegister) + member.size > kRegister)
        offset = align_up(offset, kRegister);
      member.offset = offset;
    }
    offset = std::max(offset, member.offset + member.size);
    end = std::max(end, member.offset + member.size);
    new_register = type.kind() == TypeKind::Struct;
    if (type.is_vector()) {
      const uint32_t alignment = type.cols() == 2 ? 8 : type.cols() >= 3 ? 16 : 4;
      member.split_into_scalars = member.offset % alignment != 0;
    }
    buffer.members.push_back(std::move(member));
    items.push_back(&item);
  }
  buffer.size = align_up(end, kRegister);

  // GLSL lists a block's members in increasing offset: check them in that order.
  std::vector<size_t> order(buffer.members.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return buffer.members[a].offset < buffer.members[b].offset; });
  uint32_t previous_end_hlsl = 0, previous_end_std140 = 0;
  std::string previous_name;
  for (size_t index : order) {
    const ConstantBufferMember& member = buffer.members[index];
    const PackedItem& item = *items[index];
    const Type& type = member.type;
    if (type.kind() == TypeKind::Struct && type.struct_decl()) {
      if (auto mismatch = struct_layout_mismatch(type.struct_decl()))
        diagnostics.error(item.loc, in_quotes(item.name) + " in constant buffer " + in_quotes(buffer.name) +
                                        ": struct " + in_quotes(type.struct_decl()->name) +
                                        " cannot keep its HLSL layout in GLSL: " + *mismatch +
                                        "; reorder its fields or pad them to 16-byte registers");
    }
    if (!previous_name.empty() && member.offset < previous_end_hlsl) {
      diagnostics.error(item.loc, in_quotes(item.name) + " at offset " + std::to_string(member.offset) +
                                      " of constant buffer " + in_quotes(buffer.name) + " overlaps " +
                                      in_quotes(previous_name) + " (up to " + std::to_string(previous_end_hlsl) + ")");
    } else if (!previous_name.empty() && member.offset < previous_end_std140) {
      diagnostics.error(
          item.loc, in_quotes(item.name) + " is at offset " + std::to_string(member.offset) + " of constant buffer " +
                        in_quotes(buffer.name) + ", inside the padding GLSL gives " + in_quotes(previous_name) +
                        " (up to " + std::to_string(previous_end_std140) + "); start " + in_quotes(item.name) +
                        " on a new 16-byte register (pad before it) or declare it before " + in_quotes(previous_name));
    }
    previous_end_hlsl = member.offset + member.size;
    previous_end_std140 =
        member.offset + (member.split_into_scalars ? member.size : std140_size(type, member.row_major));
    previous_name = item.name;
  }
  std::vector<ConstantBufferMember> sorted;
  for (size_t index : order) sorted.push_back(std::move(buffer.members[index]));
  buffer.members = std::move(sorted);
}

std::vector<PackedItem> packed_items(const std::vector<const VarDecl*>& vars) {
  std::vector<PackedItem> items;
  for (const VarDecl* var : vars)
    items.push_back({var->name, var->type, var->packing == MatrixPacking::RowMajor,
                     var->packoffset ? var->packoffset_loc : var->loc, var->packoffset, var->vk.offset});
  return items;
}

bool is_uniform_global(const VarDecl& var) {
  return var.is_global && var.storage != StorageClass::Static && var.storage != StorageClass::GroupShared &&
         !var.type.is_resource() && !var.type.is_resource_array() && !var.type.is_error();
}

std::string canonical(const std::string& semantic) { return canonical_semantic(parse_semantic(semantic)); }

// Every global declaration and user function reachable from the entry points, by what reads it.
struct Usage {
  std::unordered_set<const Decl*> globals;             // the globals the entry points read
  std::map<const Decl*, const Decl*> texture_sampler;  // texture -> first SamplerState it is sampled with
  std::unordered_set<const Decl*> compared;            // textures sampled with a SamplerComparisonState
};

Usage collect_usage(const EntryPoints& entry_points, const ResourceOrigins& origins) {
  Usage usage;
  // A texture or sampler may reach a Sample call through function parameters (and locals and
  // struct fields, which resource_origins.h follows back to a global or a parameter); each
  // parameter's resource is traced back to what its call passes (the first call that passes one).
  using Key = std::pair<const Decl*, std::vector<uint32_t>>;
  std::map<Key, ResourceOrigin> passed;
  auto global_of = [&](ResourceOrigin origin) -> const Decl* {
    for (int hops = 0; origin.root && hops < 64; ++hops) {
      auto it = passed.find({origin.root, origin.fields});
      if (it == passed.end()) break;
      origin = it->second;
    }
    return origin.root && origin.root->kind == DeclKind::Var ? origin.root : nullptr;
  };
  // The global behind a resource-typed expression, if it is known.
  auto global_behind = [&](const Expr* e) -> const Decl* {
    auto it = e ? origins.find(e) : origins.end();
    if (it == origins.end() || it->second.size() != 1) return nullptr;
    return global_of(it->second[0].origin);
  };
  for (const FunctionDecl* entry : {entry_points.vertex, entry_points.fragment}) {
    std::vector<const FunctionDecl*> functions = reachable_functions(entry);
    // Callers come last in that order; tracing parameters needs callers first.
    for (auto function = functions.rbegin(); function != functions.rend(); ++function) {
      walk_expressions((*function)->body.get(), [&](const Expr& expr) {
        if (expr.kind != ExprKind::Call) return;
        const auto& call = static_cast<const CallExpr&>(expr);
        if (call.call_kind != CallKind::Function || !call.function) return;
        for (size_t i = 0; i < call.args.size() && i < call.function->params.size(); ++i) {
          if (!may_hold_resources(call.args[i]->type)) continue;
          auto it = origins.find(call.args[i].get());
          if (it == origins.end()) continue;
          for (const ResourceLeaf& leaf : it->second)
            passed.emplace(Key{call.function->params[i].get(), leaf.path}, leaf.origin);
        }
      });
    }
    for (const FunctionDecl* function : functions) {
      walk_expressions(function->body.get(), [&](const Expr& expr) {
        if (auto it = may_hold_resources(expr.type) ? origins.find(&expr) : origins.end(); it != origins.end()) {
          for (const ResourceLeaf& leaf : it->second)
            if (const Decl* global = global_of(leaf.origin)) usage.globals.insert(global);
        }
        if (expr.kind == ExprKind::Name) {
          // Only globals are asked about: locals and parameters would only fill the set.
          const Decl* decl = static_cast<const NameExpr&>(expr).decl;
          if (decl && decl->kind == DeclKind::Var && static_cast<const VarDecl*>(decl)->is_global)
            usage.globals.insert(decl);
        } else if (expr.kind == ExprKind::Call) {
          const auto& call = static_cast<const CallExpr&>(expr);
          if (call.call_kind != CallKind::Method || !call.object || call.args.empty()) return;
          if (call.args[0]->type.kind() != TypeKind::SamplerState) return;
          const Decl* texture = global_behind(call.object.get());
          const Decl* sampler = global_behind(call.args[0].get());
          if (texture && sampler) usage.texture_sampler.emplace(texture, sampler);
          if (texture && call.args[0]->type.is_comparison()) usage.compared.insert(texture);
        }
      });
    }
  }
  // A static global's initializer runs for whatever reads the global: what it reads is read too.
  std::vector<const Decl*> pending(usage.globals.begin(), usage.globals.end());
  while (!pending.empty()) {
    const Decl* decl = pending.back();
    pending.pop_back();
    if (decl->kind != DeclKind::Var) continue;
    walk_expressions(static_cast<const VarDecl*>(decl)->initializer.get(), [&](const Expr& expr) {
      if (expr.kind != ExprKind::Name) return;
      const Decl* read = static_cast<const NameExpr&>(expr).decl;
      if (read && read->kind == DeclKind::Var && static_cast<const VarDecl*>(read)->is_global &&
          usage.globals.insert(read).second)
        pending.push_back(read);
    });
  }
  return usage;
}

// Assigns bindings within one register class: explicit registers first, then the lowest free
// register to each remaining used resource in declaration order, as glslang's auto-mapping does.
class RegisterClass {
 public:
  RegisterClass(char letter, uint32_t base, DiagnosticEngine& diagnostics)
      : letter_(letter), base_(base), diagnostics_(diagnostics) {}

  // Two resources may declare one register where no entry point reaches both, as fxc and DXC
  // allow (a file of several shaders); `reached` says whether one reaches this one. A space is
  // a register set of its own (Vulkan's descriptor set of that number).
  // An array of `count` resources takes the registers from its own on.
  void claim(const RegisterBinding& binding, const std::string& name, bool reached, uint32_t count = 1) {
    for (uint32_t element = 1; element < count; ++element) {
      RegisterBinding next = binding;
      next.index += element;
      claim(next, name, reached);
    }
    if (binding.index >= kRegistersPerClass) {
      diagnostics_.error(binding.loc, std::string("register ") + binding.register_class +
                                          std::to_string(binding.index) + " of " + in_quotes(name) +
                                          " is out of range (0 to " + std::to_string(kRegistersPerClass - 1) + ")");
      return;
    }
    auto [it, inserted] = used_.emplace(std::pair{binding.space, binding.index}, Claim{name, reached});
    if (inserted) return;
    if (it->second.reached && reached) {
      diagnostics_.error(binding.loc,
                         std::string("register ") + binding.register_class + std::to_string(binding.index) +
                             (binding.space ? ", space" + std::to_string(binding.space) : std::string()) + " of " +
                             in_quotes(name) + " is already taken by " + in_quotes(it->second.name) +
                             ", and the entry points read both; give one another register");
    } else if (reached) {
      it->second = Claim{name, reached};
    }
  }
  uint32_t binding_of(const RegisterBinding& binding) const { return base_ + binding.index; }
  // The lowest free register; when none is left, an error if `required`.
  std::optional<uint32_t> next_free(const std::string& name, Loc loc, bool required = true, uint32_t count = 1) {
    for (uint32_t index = 0; index + count <= kRegistersPerClass; ++index) {
      bool free = true;
      for (uint32_t element = 0; element < count && free; ++element)
        free = !used_.count(std::pair{0u, index + element});
      if (!free) continue;
      for (uint32_t element = 0; element < count; ++element)
        used_.emplace(std::pair{0u, index + element}, Claim{name, true});
      return base_ + index;
    }
    if (required)
      diagnostics_.error(loc, std::string("no free ") + letter_ + " register for " + in_quotes(name) +
                                  ": a shader reads at most " + std::to_string(kRegistersPerClass) +
                                  " of this class here");
    return std::nullopt;
  }

 private:
  char letter_;
  uint32_t base_;
  DiagnosticEngine& diagnostics_;
  struct Claim {
    std::string name;
    bool reached;  // by an entry point
  };
  std::map<std::pair<uint32_t, uint32_t>, Claim> used_;  // by space and index
};

double literal_value(const Expr* expr) {
  if (!expr) return 0.0;
  switch (expr->kind) {
    case ExprKind::IntLiteral: return double(static_cast<const IntLiteralExpr*>(expr)->value);
    case ExprKind::FloatLiteral: return static_cast<const FloatLiteralExpr*>(expr)->value;
    case ExprKind::BoolLiteral: return static_cast<const BoolLiteralExpr*>(expr)->value ? 1.0 : 0.0;
    case ExprKind::Conversion: return literal_value(static_cast<const ConversionExpr*>(expr)->operand.get());
    case ExprKind::Unary: {
      auto* unary = static_cast<const UnaryExpr*>(expr);
      double value = literal_value(unary->operand.get());
      return unary->op == UnaryOp::Minus ? -value : value;
    }
    default: return 0.0;
  }
}

// The components of a constant initializer: literals, constructors and lists of them.
bool constant_components(const Expr* expr, std::vector<double>& out) {
  if (!expr) return false;
  switch (expr->kind) {
    case ExprKind::IntLiteral:
    case ExprKind::FloatLiteral:
    case ExprKind::BoolLiteral: out.push_back(literal_value(expr)); return true;
    case ExprKind::Unary: {
      auto* unary = static_cast<const UnaryExpr*>(expr);
      if (unary->op != UnaryOp::Minus && unary->op != UnaryOp::Plus) return false;
      const size_t first = out.size();
      if (!constant_components(unary->operand.get(), out)) return false;
      if (unary->op == UnaryOp::Minus)
        for (size_t i = first; i < out.size(); ++i) out[i] = -out[i];
      return true;
    }
    case ExprKind::Conversion: {
      auto* conversion = static_cast<const ConversionExpr*>(expr);
      std::vector<double> inner;
      if (!constant_components(conversion->operand.get(), inner)) return false;
      const uint32_t count = expr->type.component_count();
      if (inner.size() == 1 && count > 1) inner.assign(count, inner[0]);  // a splat
      if (count != 0 && inner.size() > count) inner.resize(count);        // a truncation
      out.insert(out.end(), inner.begin(), inner.end());
      return true;
    }
    case ExprKind::Call: {
      auto* call = static_cast<const CallExpr*>(expr);
      if (call->call_kind != CallKind::Constructor) return false;
      for (const ExprPtr& arg : call->args)
        if (!constant_components(arg.get(), out)) return false;
      return true;
    }
    case ExprKind::InitList:
      for (const ExprPtr& element : static_cast<const InitListExpr*>(expr)->elements)
        if (!constant_components(element.get(), out)) return false;
      return true;
    default: return false;
  }
}

// A texture's Default annotation must name one of the scene format's built-ins, which is what
// the renderer can make of it.
void check_texture_default(const VarDecl& var, DiagnosticEngine& diagnostics) {
  for (const Annotation& annotation : var.annotations) {
    if (annotation.name != "Default") continue;
    const auto& known = kTextureDefaults;
    if (std::find(std::begin(known), std::end(known), annotation.text) == std::end(known))
      diagnostics.error(
          annotation.loc,
          "Default of texture " + in_quotes(var.name) +
              " must be \"white\", \"black\", \"checker\", \"normal\", \"gray\", \"red\" or \"clear\" (a string)");
  }
}

Property property_of(const VarDecl& var) {
  Property property;
  property.name = var.name;
  property.display_name = var.name;
  property.type = var.type;
  property.is_texture = var.type.is_texture() || var.type.kind() == TypeKind::Sampler;
  for (const Annotation& annotation : var.annotations) {
    if (annotation.name == "UIName" && !annotation.text.empty()) property.display_name = annotation.text;
    if (annotation.name == "UIMin") property.min = literal_value(annotation.value.get());
    if (annotation.name == "UIMax") property.max = literal_value(annotation.value.get());
    if (annotation.name == "Default" && property.is_texture) property.default_texture = annotation.text;
  }
  std::vector<double> components;
  if (var.initializer && constant_components(var.initializer.get(), components)) property.default_value = components;
  return property;
}

// Inputs (`inputs` true) or outputs of an entry point, flattened over struct parameters and
// return values, with canonical semantics. A struct field that is itself a struct is flattened
// too, as HLSL does: its fields' semantics are the stage variables (a semantic on the struct
// field itself is not one). Sema has checked every leaf, to the same depth limit.
std::vector<StageVariable> stage_variables(const FunctionDecl& entry, bool inputs) {
  std::vector<StageVariable> variables;
  struct Pending {
    const Type* type;
    const std::string* semantic;
    Interpolation interpolation;
    std::optional<uint32_t> location;
    int depth;
  };
  auto add = [&](const Type& root_type, const std::string& root_semantic, Interpolation root_interpolation,
                 std::optional<uint32_t> root_location) {
    std::vector<Pending> pending{{&root_type, &root_semantic, root_interpolation, root_location, 0}};
    while (!pending.empty()) {
      const Pending item = pending.back();
      pending.pop_back();
      const Type& type = *item.type;
      if (type.kind() == TypeKind::Struct && type.struct_decl()) {
        if (item.depth >= sema_detail::kMaxNesting) continue;
        const auto& fields = type.struct_decl()->fields;
        for (auto field = fields.rbegin(); field != fields.rend(); ++field)  // in declaration order
          if (field->vk.builtin.empty())  // [[vk::builtin]]: GLSL's built-in, not a location
            pending.push_back(
                {&field->type, &field->semantic, field->interpolation, field->vk.location, item.depth + 1});
        continue;
      }
      if (!item.semantic->empty())
        variables.push_back(
            {canonical(*item.semantic), type, item.location.value_or(0), item.interpolation, item.location});
    }
  };
  for (const auto& param : entry.params) {
    if (!param || param->is_uniform) continue;
    const bool is_input = param->direction != ParamDirection::Out;
    const bool is_output = param->direction != ParamDirection::In;
    if ((inputs ? is_input : is_output) && param->vk.builtin.empty())
      add(param->type, param->semantic, param->interpolation, param->vk.location);
  }
  if (!inputs && !entry.return_type.is_void())
    add(entry.return_type, entry.semantic, Interpolation::Default, std::nullopt);
  return variables;
}

// System values, and the DX9 spellings sema reads as system values: POSITION out of a vertex
// shader or into a fragment shader is SV_Position where it is a float4.
bool is_system_value(const StageVariable& variable, bool vertex_input) {
  const std::string& semantic = variable.semantic;
  if (semantic.rfind("SV_", 0) == 0 || semantic == "VFACE") return true;
  return !vertex_input && is_clip_position_alias(parse_semantic(semantic), variable.type);
}

// Where the semantics the fixed tables have no place for begin (vertex_input_location,
// varying_location).
constexpr uint32_t kFirstUserVertexInput = 13;
constexpr uint32_t kFirstUserVarying = 14;

// How many locations a varying of this type takes: an array one per element, a matrix one per
// row (GLSL's matRxC, the transpose the emitter holds, has R columns).
uint32_t location_count(const Type& type) {
  if (type.kind() == TypeKind::Array) return type.array_length() * location_count(type.element());
  return type.is_matrix() ? type.rows() : 1;
}

// Varyings sit at their semantic's location (varying_location), in that order, except that one
// never overlaps the locations an array before it takes: `float3 c[2] : TEXCOORD2`
// takes 2 and 3, so a TEXCOORD3 after it moves to 4 and what follows moves on as far as needed.
// HLSL written for SPIR-V (DXC, glslang) gives every varying its own locations in this way;
// where nothing takes more than one location every varying keeps its semantic's.
// A varying the source places with [[vk::location]] stays where it is put; one that would overlap
// it is reported.
void place_varyings(std::vector<StageVariable>& varyings, Loc where, DiagnosticEngine& diagnostics) {
  std::vector<StageVariable*> order;
  for (StageVariable& varying : varyings) order.push_back(&varying);
  std::stable_sort(order.begin(), order.end(),
                   [](const StageVariable* a, const StageVariable* b) { return a->location < b->location; });
  uint32_t next_free = 0;
  const StageVariable* previous = nullptr;
  for (StageVariable* varying : order) {
    if (varying->given_location && *varying->given_location < next_free && previous)
      diagnostics.error(where, "varying " + in_quotes(varying->semantic) + " at [[vk::location(" +
                                   std::to_string(*varying->given_location) + ")]] overlaps " +
                                   in_quotes(previous->semantic) + ", which takes locations " +
                                   std::to_string(previous->location) + " to " + std::to_string(next_free - 1));
    if (!varying->given_location) varying->location = std::max(varying->location, next_free);
    next_free = std::max(next_free, varying->location + location_count(varying->type));
    previous = varying;
  }
}

// The location of a semantic the fixed table (`fixed`) has no place for: the next one from
// `first` that no variable of `variables` takes, in declaration order.
uint32_t next_free_location(const std::vector<StageVariable>& variables, uint32_t first) {
  uint32_t location = first;
  for (bool moved = true; moved;) {
    moved = false;
    for (const StageVariable& variable : variables)
      if (location >= variable.location && location < variable.location + location_count(variable.type)) {
        location = variable.location + location_count(variable.type);
        moved = true;
      }
  }
  return location;
}

}  // namespace

std::string canonical_semantic_name(const std::string& semantic) { return canonical(semantic); }

std::optional<uint32_t> vertex_input_location(const std::string& semantic) {
  static const std::map<std::string, uint32_t> locations{
      {"POSITION0", 0},  {"NORMAL0", 1},    {"TANGENT0", 2},  {"TEXCOORD0", 3}, {"TEXCOORD1", 4},
      {"COLOR0", 5},     {"TEXCOORD2", 6},  {"TEXCOORD3", 7}, {"TEXCOORD4", 8}, {"TEXCOORD5", 9},
      {"TEXCOORD6", 10}, {"TEXCOORD7", 11}, {"COLOR1", 12}};
  auto it = locations.find(semantic);
  if (it != locations.end()) return it->second;
  return std::nullopt;
}

std::optional<uint32_t> varying_location(const std::string& semantic) {
  const ParsedSemantic parsed = parse_semantic(semantic);
  switch (parsed.kind) {
    case SemanticKind::Texcoord: return parsed.index < 8 ? std::optional<uint32_t>(parsed.index) : std::nullopt;
    case SemanticKind::Color: return parsed.index < 2 ? std::optional<uint32_t>(8 + parsed.index) : std::nullopt;
    case SemanticKind::Normal: return parsed.index == 0 ? std::optional<uint32_t>(10) : std::nullopt;
    case SemanticKind::Tangent: return parsed.index == 0 ? std::optional<uint32_t>(11) : std::nullopt;
    case SemanticKind::Binormal: return parsed.index == 0 ? std::optional<uint32_t>(12) : std::nullopt;
    case SemanticKind::Position: return parsed.index == 0 ? std::optional<uint32_t>(13) : std::nullopt;
    default: return std::nullopt;
  }
}

const ConstantBuffer* Reflection::find_constant_buffer(std::string_view name) const {
  for (const ConstantBuffer& buffer : constant_buffers)
    if (buffer.name == name) return &buffer;
  return nullptr;
}

// [[vk::combinedImageSampler]] as DXC reads it: on a texture and a SamplerState that share one
// vk::binding (and set), which then are one combined image sampler there; each needs its partner.
static void check_combined_image_samplers(const Reflection& reflection, DiagnosticEngine& diagnostics) {
  const auto partner = [](const VarDecl* decl, const VarDecl* other) {
    return other && other->vk.combined_image_sampler && decl->vk.binding && other->vk.binding == decl->vk.binding &&
           other->vk.set == decl->vk.set;
  };
  const auto check = [&](const VarDecl* decl, bool texture) {
    if (!decl || !decl->vk.combined_image_sampler) return;
    const bool paired = texture ? std::any_of(reflection.samplers.begin(), reflection.samplers.end(),
                                              [&](const SamplerResource& s) { return partner(decl, s.decl); })
                                : std::any_of(reflection.textures.begin(), reflection.textures.end(),
                                              [&](const TextureResource& t) { return partner(decl, t.decl); });
    if (!paired)
      diagnostics.error(decl->vk.loc,
                        "vk::combinedImageSampler on " + in_quotes(decl->name) + " needs a " +
                            (texture ? "SamplerState" : "texture") +
                            " with it at the same vk::binding: " + "the two are one combined image sampler there");
  };
  for (const TextureResource& texture : reflection.textures) check(texture.decl, true);
  for (const SamplerResource& sampler : reflection.samplers) check(sampler.decl, false);
}

Reflection reflect(const TranslationUnit& unit, const EntryPoints& entry_points, const ResourceOrigins& origins,
                   DiagnosticEngine& diagnostics) {
  Reflection reflection;
  if (entry_points.vertex) reflection.vertex_entry = entry_points.vertex->name;
  if (entry_points.fragment) reflection.fragment_entry = entry_points.fragment->name;
  const Usage usage = collect_usage(entry_points, origins);
  // glslang maps only the resources a stage reads, so those come first; a resource nobody reads
  // then takes what is left, so that every declared one has a number.
  const bool has_entry = entry_points.vertex || entry_points.fragment;
  auto used = [&](const VarDecl* var) { return !has_entry || usage.globals.count(var) > 0; };

  // Constant buffers, textures and samplers in declaration order; $Globals takes its place at
  // its first member.
  RegisterClass buffers('b', kConstantBufferBindingBase, diagnostics);
  RegisterClass textures('t', kTextureBindingBase, diagnostics);
  RegisterClass samplers('s', kSamplerBindingBase, diagnostics);
  struct PendingBuffer {
    size_t index;
    const RegisterBinding* binding;
    Loc loc;
  };
  std::vector<PendingBuffer> pending_buffers;
  std::vector<const VarDecl*> globals;
  std::optional<size_t> globals_index;
  std::vector<std::pair<size_t, const VarDecl*>> pending_textures, pending_samplers, pending_buffers_read;

  // At most one property per global and cbuffer member: reserved, since a Property is large
  // and growing the vector moves every one made so far.
  size_t most_properties = 0;
  for (const auto& decl : unit.decls) {
    if (decl && decl->kind == DeclKind::CBuffer)
      most_properties += static_cast<const CBufferDecl&>(*decl).members.size();
    if (decl && decl->kind == DeclKind::Var) ++most_properties;
  }
  reflection.properties.reserve(most_properties);

  for (const auto& decl : unit.decls) {
    if (!decl) continue;
    if (decl->kind == DeclKind::CBuffer) {
      const auto& cbuffer = static_cast<const CBufferDecl&>(*decl);
      ConstantBuffer buffer;
      buffer.name = cbuffer.name;
      buffer.decl = &cbuffer;
      std::vector<const VarDecl*> members;
      for (const auto& member : cbuffer.members)
        if (member && !member->type.is_error()) members.push_back(member.get());
      pack_members(buffer, packed_items(members), diagnostics);
      for (const VarDecl* member : members) reflection.properties.push_back(property_of(*member));
      const bool reached = std::any_of(members.begin(), members.end(), used);
      if (cbuffer.binding.register_class == 'b' && !cbuffer.vk.binding)
        buffers.claim(cbuffer.binding, cbuffer.name, reached);
      else if (cbuffer.binding.register_class != 0)
        diagnostics.error(cbuffer.binding.loc, "constant buffer " + in_quotes(cbuffer.name) +
                                                   " needs a b register, not " + cbuffer.binding.register_class);
      pending_buffers.push_back({reflection.constant_buffers.size(), &cbuffer.binding, cbuffer.loc});
      reflection.constant_buffers.push_back(std::move(buffer));
    } else if (decl->kind == DeclKind::Var) {
      const auto& var = static_cast<const VarDecl&>(*decl);
      if (var.vk.constant_id && var.type.is_scalar())
        reflection.specialization_constants.push_back({var.name, *var.vk.constant_id, var.type.scalar_type()});
      // An array of resources is one resource of `count` elements.
      const bool array = var.type.is_resource_array();
      const Type& type = array ? var.type.element() : var.type;
      const uint32_t count = array ? var.type.array_length() : 1;
      const TypeKind kind = type.kind();
      if (kind == TypeKind::Texture || kind == TypeKind::Sampler) {
        TextureResource texture;
        texture.name = var.name;
        texture.kind = kind == TypeKind::Texture ? TextureKind::Texture : TextureKind::Sampler;
        texture.shape = type.texture_shape();
        if (kind == TypeKind::Texture)
          texture.texel = type.scalar_type() == ScalarType::Half ? ScalarType::Float : type.scalar_type();
        texture.decl = &var;
        texture.count = count;
        // glslang puts a sampler2D in the texture range whatever its register letter says.
        if (var.binding.register_class != 0 && !var.vk.binding)
          textures.claim(var.binding, var.name, used(&var), count);
        pending_textures.push_back({reflection.textures.size(), &var});
        reflection.textures.push_back(std::move(texture));
        reflection.properties.push_back(property_of(var));
        check_texture_default(var, diagnostics);
      } else if (kind == TypeKind::ConstantBuffer) {
        // ConstantBuffer<S> name: a constant buffer named `name` holding S's fields.
        ConstantBuffer buffer;
        buffer.name = var.name;
        buffer.decl = &var;
        buffer.push_constant = var.vk.push_constant;
        buffer.count = count;
        std::vector<PackedItem> members;
        if (const StructDecl* structure = type.element().struct_decl())
          for (const FieldDecl& field : structure->fields)
            members.push_back({field.name, field.type, false, field.loc, {}, field.vk.offset});
        pack_members(buffer, members, diagnostics);
        if (var.binding.register_class == 'b' && !var.vk.binding)
          buffers.claim(var.binding, var.name, used(&var), count);
        pending_buffers.push_back({reflection.constant_buffers.size(), &var.binding, var.loc});
        reflection.constant_buffers.push_back(std::move(buffer));
      } else if (kind == TypeKind::Buffer && !array && is_read_only_buffer(type.buffer_kind())) {
        StorageBufferResource buffer;
        buffer.name = var.name;
        buffer.kind = type.buffer_kind();
        const bool bytes = buffer.kind == BufferKind::ByteAddressBuffer;
        buffer.element = bytes ? Type::scalar(ScalarType::Uint) : type.element();
        buffer.stride = bytes ? 4 : structured_size(buffer.element);
        buffer.decl = &var;
        // A shader resource view: a t register, shared with the textures.
        if (var.binding.register_class != 0 && !var.vk.binding) textures.claim(var.binding, var.name, used(&var));
        pending_buffers_read.push_back({reflection.buffers.size(), &var});
        reflection.buffers.push_back(std::move(buffer));
      } else if (kind == TypeKind::SamplerState) {
        SamplerResource sampler{var.name, 0, type.is_comparison(), true, &var};
        sampler.count = count;
        if (var.binding.register_class != 0 && !var.vk.binding)
          samplers.claim(var.binding, var.name, used(&var), count);
        pending_samplers.push_back({reflection.samplers.size(), &var});
        reflection.samplers.push_back(std::move(sampler));
      } else if (is_uniform_global(var)) {
        if (var.binding.register_class != 0)
          diagnostics.warning(var.binding.loc,
                              "register of " + in_quotes(var.name) + " is ignored: it lives in $Globals");
        if (!globals_index) {
          globals_index = reflection.constant_buffers.size();
          reflection.constant_buffers.push_back({kGlobalsBufferName, 0, 0, {}, nullptr});
          pending_buffers.push_back({*globals_index, nullptr, var.loc});
        }
        globals.push_back(&var);
        reflection.properties.push_back(property_of(var));
      }
    }
  }
  if (globals_index) pack_members(reflection.constant_buffers[*globals_index], packed_items(globals), diagnostics);

  // Bindings: explicit ones were claimed above; the rest take the lowest free register.
  for (const PendingBuffer& pending : pending_buffers) {
    ConstantBuffer& buffer = reflection.constant_buffers[pending.index];
    if (given_binding(buffer.decl)) continue;
    if (pending.binding && pending.binding->register_class == 'b') {
      buffer.binding = buffers.binding_of(*pending.binding);
      buffer.set = pending.binding->space;
    } else if (auto binding = buffers.next_free(buffer.name, pending.loc, true, buffer.count)) {
      buffer.binding = *binding;
    }
  }
  std::unordered_set<std::string> read_names;  // a global's name is unique in its scope
  for (const Decl* global : usage.globals)
    if (global->kind == DeclKind::Var) read_names.insert(static_cast<const VarDecl*>(global)->name);
  for (ConstantBuffer& buffer : reflection.constant_buffers) {
    const bool whole_buffer_read = buffer.decl && usage.globals.count(buffer.decl) > 0;  // ConstantBuffer<S> name
    for (ConstantBufferMember& member : buffer.members)
      member.used = !has_entry || whole_buffer_read || read_names.count(member.name) > 0;
  }
  // An unread resource takes a register only while one is free: it is never bound, and a file
  // of many shaders may declare more than a class holds.
  for (bool used_pass : {true, false}) {
    const auto place = [&](const auto& pending, auto& resources, RegisterClass& registers) {
      for (auto [index, var] : pending) {
        if (used(var) != used_pass) continue;
        auto& resource = resources[index];
        resource.used = used_pass;
        if (var->vk.binding) continue;
        resource.set = var->binding.space;
        uint32_t count = 1;
        if constexpr (requires { resource.count; }) count = resource.count;
        if (var->binding.register_class != 0)
          resource.binding = registers.binding_of(var->binding);
        else
          resource.binding = registers.next_free(var->name, var->loc, used_pass, count).value_or(0);
      }
    };
    place(pending_textures, reflection.textures, textures);
    place(pending_buffers_read, reflection.buffers, textures);  // shader resource views share t
    place(pending_samplers, reflection.samplers, samplers);
  }

  give_vulkan_bindings(reflection, diagnostics);
  for (TextureResource& texture : reflection.textures) {
    texture.comparison = usage.compared.count(texture.decl) > 0;
    auto it = usage.texture_sampler.find(texture.decl);
    if (it == usage.texture_sampler.end()) continue;
    texture.sampler = it->second->name;
    for (const SamplerResource& sampler : reflection.samplers)
      if (sampler.decl == it->second) texture.sampler_binding = sampler.binding;
  }

  // Stage interfaces.
  if (entry_points.vertex) {
    // The vertex format's semantics first, then the others after them.
    std::vector<StageVariable> unplaced;
    for (StageVariable input : stage_variables(*entry_points.vertex, true)) {
      if (is_system_value(input, true)) continue;
      const std::optional<uint32_t> location =
          input.given_location ? input.given_location : vertex_input_location(input.semantic);
      if (!location) {
        unplaced.push_back(std::move(input));
        continue;
      }
      input.location = *location;
      reflection.vertex_inputs.push_back(std::move(input));
    }
    for (StageVariable& input : unplaced) {
      input.location = next_free_location(reflection.vertex_inputs, kFirstUserVertexInput);
      reflection.vertex_inputs.push_back(std::move(input));
    }
    unplaced.clear();
    for (StageVariable output : stage_variables(*entry_points.vertex, false)) {
      if (is_system_value(output, false)) continue;
      const std::optional<uint32_t> location =
          output.given_location ? output.given_location : varying_location(output.semantic);
      if (!location) {
        unplaced.push_back(std::move(output));
        continue;
      }
      output.location = *location;
      reflection.varyings.push_back(std::move(output));
    }
    place_varyings(reflection.varyings, entry_points.vertex->loc, diagnostics);
    for (StageVariable& output : unplaced) {
      output.location = next_free_location(reflection.varyings, kFirstUserVarying);
      reflection.varyings.push_back(std::move(output));
    }
  }
  // The distances cross from the stage that writes them (the vertex stage, or for a full-screen
  // pass the shared vertex shader, which writes what the fragment stage reads).
  if (const FunctionDecl* distances_entry = entry_points.vertex ? entry_points.vertex : entry_points.fragment) {
    for (const StageVariable& variable : stage_variables(*distances_entry, !entry_points.vertex)) {
      const SemanticKind kind = parse_semantic(variable.semantic).kind;
      if (kind == SemanticKind::SvClipDistance) reflection.clip_distances += variable.type.component_count();
      if (kind == SemanticKind::SvCullDistance) reflection.cull_distances += variable.type.component_count();
    }
  }
  if (entry_points.fragment) {
    for (const StageVariable& input : stage_variables(*entry_points.fragment, true))
      if (parse_semantic(input.semantic).kind == SemanticKind::SvShadingRate) reflection.reads_shading_rate = true;
    for (const StageVariable& input : stage_variables(*entry_points.fragment, true)) {
      if (is_system_value(input, false)) continue;
      const bool written = std::any_of(reflection.varyings.begin(), reflection.varyings.end(),
                                       [&](const StageVariable& v) { return v.semantic == input.semantic; });
      if (entry_points.vertex && !written)
        diagnostics.error(entry_points.fragment->loc, "fragment input " + in_quotes(input.semantic) +
                                                          " is not written by the vertex entry point " +
                                                          in_quotes(entry_points.vertex->name));
      if (!entry_points.vertex) {
        // A full-screen pass: the shared vertex shader feeds every scalar or vector varying
        // (glsl::fullscreen_vertex_shader: uv for floats, 0 for integers, the identity for matrices).
        std::optional<uint32_t> location =
            input.given_location ? input.given_location : varying_location(input.semantic);
        if (!location) location = next_free_location(reflection.varyings, kFirstUserVarying);
        const Type& element = input.type.kind() == TypeKind::Array ? input.type.element() : input.type;
        const ScalarType scalar = element.scalar_type();
        const bool is_float = scalar == ScalarType::Float || scalar == ScalarType::Half;
        const bool fed = ((element.is_scalar() || element.is_vector()) &&
                          (is_float || scalar == ScalarType::Int || scalar == ScalarType::Uint)) ||
                         (element.is_matrix() && is_float);
        if (!location || !fed)
          diagnostics.error(
              entry_points.fragment->loc,
              "a fragment shader without a vertex stage receives uv in its float scalar and vector inputs "
              "(TEXCOORD0 and the like, arrays of them too), 0 in its integer ones and the identity in its "
              "float matrices, not " +
                  input.type.name() + " " + in_quotes(input.semantic));
        else
          reflection.varyings.push_back(
              {input.semantic, input.type, *location, input.interpolation, input.given_location});
      }
    }
    if (!entry_points.vertex) place_varyings(reflection.varyings, entry_points.fragment->loc, diagnostics);
    for (StageVariable output : stage_variables(*entry_points.fragment, false)) {
      const ParsedSemantic parsed = parse_semantic(output.semantic);
      // DX9's COLORn out of a fragment shader is SV_Targetn.
      if (parsed.kind == SemanticKind::SvTarget || parsed.kind == SemanticKind::Color) {
        output.location = parsed.index;
        output.semantic = "SV_Target" + std::to_string(parsed.index);
      }
      reflection.fragment_outputs.push_back(std::move(output));
    }
  }
  check_combined_image_samplers(reflection, diagnostics);
  return reflection;
}

uint64_t keyword_combination_count(const std::vector<KeywordSet>& sets) {
  uint64_t count = 1;
  for (const KeywordSet& set : sets) {
    const uint64_t size = std::max<uint64_t>(set.keywords.size(), 1);
    if (count > UINT64_MAX / size) return UINT64_MAX;
    count *= size;
  }
  return count;
}

std::vector<std::string> keyword_combination(const std::vector<KeywordSet>& sets, uint64_t index) {
  std::vector<std::string> keywords(sets.size());
  for (size_t s = sets.size(); s-- > 0;) {
    const std::vector<std::string>& set = sets[s].keywords;
    if (set.empty()) continue;
    keywords[s] = set[index % set.size()];
    index /= set.size();
  }
  std::erase_if(keywords,
                [](const std::string& keyword) { return keyword.find_first_not_of('_') == std::string::npos; });
  return keywords;
}

bool is_read_only_buffer(BufferKind kind) {
  return kind == BufferKind::StructuredBuffer || kind == BufferKind::ByteAddressBuffer || kind == BufferKind::Buffer;
}

}  // namespace xshade::hlsl
