#include "harness/render/surface_program.h"

#include <algorithm>

#include "harness/render/material_source.h"
#include "hlsl_like/ast_walk.h"
#include "shaderlab/pass_program.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

template <class T>
const T* find_decl(const hlsl::TranslationUnit& unit, hlsl::DeclKind kind, const std::string& name,
                   bool want_body = false) {
  for (const auto& decl : unit.decls) {
    if (decl->kind != kind || decl->name != name) continue;
    const auto* typed = static_cast<const T*>(decl.get());
    if constexpr (std::is_same_v<T, hlsl::FunctionDecl>)
      if (want_body && !typed->body) continue;
    return typed;
  }
  return nullptr;
}

std::vector<const hlsl::FunctionDecl*> functions_named(const hlsl::TranslationUnit& unit, const std::string& name) {
  std::vector<const hlsl::FunctionDecl*> found;
  for (const auto& decl : unit.decls)
    if (decl->kind == hlsl::DeclKind::Function && decl->name == name)
      found.push_back(static_cast<const hlsl::FunctionDecl*>(decl.get()));
  return found;
}

std::vector<std::string> field_names(const hlsl::StructDecl* decl) {
  std::vector<std::string> names;
  if (decl)
    for (const hlsl::FieldDecl& field : decl->fields) names.push_back(field.name);
  return names;
}

// The expression an assignment writes, its members and indices peeled down to the first member
// access of `param`: `o.Normal = ...`, `o.Normal.xy = ...` both write Normal.
bool writes_member(const hlsl::Expr* target, const hlsl::ParamDecl* param, const std::string& member) {
  while (target) {
    if (target->kind == hlsl::ExprKind::Member) {
      const auto* access = static_cast<const hlsl::MemberExpr*>(target);
      const hlsl::Expr* object = access->object.get();
      if (access->member == member && object && object->kind == hlsl::ExprKind::Name &&
          static_cast<const hlsl::NameExpr*>(object)->name == param->name)
        return true;
      target = object;
    } else if (target->kind == hlsl::ExprKind::Index) {
      target = static_cast<const hlsl::IndexExpr*>(target)->object.get();
    } else {
      return false;
    }
  }
  return false;
}

bool function_writes(const hlsl::FunctionDecl& function, const hlsl::ParamDecl* param, const std::string& member) {
  bool writes = false;
  hlsl::walk_expressions(function.body.get(), [&](const hlsl::Expr& expr) {
    if (expr.kind == hlsl::ExprKind::Assign &&
        writes_member(static_cast<const hlsl::AssignExpr&>(expr).target.get(), param, member))
      writes = true;
  });
  return writes;
}

// The lighting function's form by its parameters, as Unity's manual lists them; the GI forms
// first where the model has both (Unity calls those).
std::optional<shaderlab::LightingForm> lighting_form(const std::vector<const hlsl::FunctionDecl*>& overloads) {
  std::optional<shaderlab::LightingForm> legacy;
  for (const hlsl::FunctionDecl* function : overloads) {
    const auto& params = function->params;
    const bool gi_last = !params.empty() && params.back()->type.name() == "UnityGI";
    if (params.size() == 2 && gi_last) return shaderlab::LightingForm::Gi;
    if (params.size() == 3 && gi_last) return shaderlab::LightingForm::ViewGi;
    if (params.size() == 3) legacy = shaderlab::LightingForm::Legacy;
    if (params.size() == 4) legacy = shaderlab::LightingForm::LegacyView;
  }
  return legacy;
}

// A message about the program that the front end's first error explains better, where it has one.
Error program_error(const hlsl::Module& module, std::string message, const SourceLocation& where) {
  for (const Diagnostic& diagnostic : module.diagnostics.diagnostics())
    if (diagnostic.severity == Severity::Error)
      return Error{message + "; the program does not compile: " + diagnostic.message, diagnostic.where, {}};
  return Error{std::move(message), where, {}};
}

}  // namespace

Result<shaderlab::SurfaceProgramShape> read_surface_program(const fs::path& file, const shaderlab::SubShader& sub,
                                                            const shaderlab::SurfaceDirective& directive,
                                                            hlsl::CompileOptions options,
                                                            shaderlab::UnityPlatform platform) {
  const shaderlab::ProgramBlock& surface = *sub.surface;
  shaderlab::Pass reading;
  reading.kind = shaderlab::PassKind::Program;
  reading.program = surface;
  shaderlab::PassProgram program;
  program.pass = &reading;
  program.implicit_includes = true;
  for (const char* include : shaderlab::kImplicitIncludes)
    program.text += "#include \"" + std::string(include) + "\"\n";
  program.text += shaderlab::surface_program_for_analysis(surface, sub.includes);
  auto compile_options = pass_compile_options(file, program, std::move(options), platform);
  if (!compile_options) return fail(compile_options.error());
  // Read for its declarations (it has no entry point yet); an error in it is reported with what
  // the program lacks, or where the generated passes compile.
  auto module = hlsl::compile_text(file.string(), program.text, *compile_options);
  const hlsl::TranslationUnit& unit = module->unit;

  shaderlab::SurfaceProgramShape shape;
  const auto* input = find_decl<hlsl::StructDecl>(unit, hlsl::DeclKind::Struct, "Input");
  if (!input)
    return fail(program_error(*module, "a surface program declares `struct Input` with what its surface function reads",
                              directive.where));
  for (const hlsl::FieldDecl& field : input->fields)
    shape.input.push_back({field.type.name(), field.name, field.semantic});

  const auto* function = find_decl<hlsl::FunctionDecl>(unit, hlsl::DeclKind::Function, directive.function, true);
  if (!function || function->params.size() != 2 || function->params[1]->type.kind() != hlsl::TypeKind::Struct)
    return fail(program_error(*module,
                              "the surface function '" + directive.function +
                                  "' of `#pragma surface` is not defined as "
                                  "`void " +
                                  directive.function + "(Input IN, inout SurfaceOutput o)`",
                              directive.where));
  const hlsl::ParamDecl* output = function->params[1].get();
  shape.output_type = output->type.name();
  shape.output_fields = field_names(output->type.struct_decl());
  shape.writes_normal = function_writes(*function, output, "Normal");

  const std::string lighting = "Lighting" + directive.lighting_model;
  const auto form = lighting_form(functions_named(unit, lighting));
  if (!form)
    return fail(program_error(
        *module,
        "the lighting model '" + directive.lighting_model + "' has no function " + lighting +
            " of a form Unity's manual lists: (SurfaceOutput s, UnityGI gi), (s, half3 viewDir, UnityGI gi), "
            "(s, half3 lightDir, half atten) or (s, half3 lightDir, half3 viewDir, half atten); "
            "Lambert and BlinnPhong are Lighting.cginc's, Standard and StandardSpecular UnityPBSLighting.cginc's",
        directive.where));
  shape.lighting = *form;
  if ((*form == shaderlab::LightingForm::Gi || *form == shaderlab::LightingForm::ViewGi) &&
      functions_named(unit, lighting + "_GI").empty())
    return fail(ErrorKind::UserInput,
                "the lighting function " + lighting + " takes a UnityGI, and Unity then calls " + lighting +
                    "_GI(SurfaceOutput s, UnityGIInput data, inout UnityGI gi) first to fill it: define it",
                directive.where);

  const std::string modifier = directive.value("vertex");
  const hlsl::StructDecl* vertex_input = find_decl<hlsl::StructDecl>(unit, hlsl::DeclKind::Struct, "appdata_full");
  if (!modifier.empty()) {
    const auto* vertex = find_decl<hlsl::FunctionDecl>(unit, hlsl::DeclKind::Function, modifier, true);
    if (!vertex || vertex->params.empty() || vertex->params[0]->type.kind() != hlsl::TypeKind::Struct)
      return fail(program_error(*module,
                                "the vertex modifier '" + modifier + "' of `vertex:` is not defined as `void " +
                                    modifier + "(inout appdata_full v)` or `(inout appdata_full v, out Input o)`",
                                directive.where));
    vertex_input = vertex->params[0]->type.struct_decl();
    shape.vertex_input_type = vertex->params[0]->type.name();
    shape.vertex_fills_input = vertex->params.size() >= 2;
  }
  shape.vertex_input_fields = field_names(vertex_input);

  for (const auto& decl : unit.decls) {
    if (decl->kind == hlsl::DeclKind::Var) shape.globals.push_back(decl->name);
    if (decl->kind == hlsl::DeclKind::CBuffer)
      for (const auto& member : static_cast<const hlsl::CBufferDecl*>(decl.get())->members)
        shape.globals.push_back(member->name);
  }
  return shape;
}

Result<shaderlab::SubShader> with_surface_passes(const fs::path& file, const shaderlab::SubShader& sub,
                                                 const hlsl::CompileOptions& options,
                                                 shaderlab::UnityPlatform platform) {
  shaderlab::SubShader generated = sub;
  if (!sub.surface) return generated;
  auto directive = shaderlab::read_surface_directive(*sub.surface);
  if (!directive) return fail(directive.error());
  auto shape = read_surface_program(file, sub, *directive, options, platform);
  if (!shape) return fail(shape.error());
  std::vector<shaderlab::Pass> passes =
      shaderlab::generate_surface_passes(*sub.surface, sub.includes, *directive, *shape);
  // Where the program stands among the written passes: Unity puts the generated passes there.
  const auto before = [&](const shaderlab::Pass& pass) {
    return pass.where.line < sub.surface->start.line ||
           (pass.where.line == sub.surface->start.line && pass.where.column < sub.surface->start.column);
  };
  const auto at = std::find_if_not(generated.passes.begin(), generated.passes.end(), before);
  generated.passes.insert(at, std::make_move_iterator(passes.begin()), std::make_move_iterator(passes.end()));
  generated.surface.reset();
  return generated;
}

}  // namespace xshade::harness
