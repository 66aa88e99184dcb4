#include "shaderlab/surface_shader.h"

#include <algorithm>
#include <array>

#include "shaderlab/pass_program.h"

namespace xshade::shaderlab {
namespace {

// Options of `#pragma surface` in Unity's manual ("Writing Surface Shaders", "Optional
// parameters"), with whether each takes a value.
struct KnownOption {
  const char* name;
  bool takes_value;
};
constexpr KnownOption kOptions[] = {
    {"alpha", false},          {"alphatest", true},           {"keepalpha", false},       {"decal", true},
    {"vertex", true},          {"finalcolor", true},          {"finalgbuffer", true},     {"finalprepass", true},
    {"addshadow", false},      {"fullforwardshadows", false}, {"tessellate", true},       {"tessphong", true},
    {"exclude_path", true},    {"noshadow", false},           {"noambient", false},       {"novertexlights", false},
    {"nolightmap", false},     {"nodynlightmap", false},      {"nodirlightmap", false},   {"nofog", false},
    {"nometa", false},         {"noforwardadd", false},       {"nolppv", false},          {"noshadowmask", false},
    {"halfasview", false},     {"approxview", false},         {"interpolateview", false}, {"dualforward", false},
    {"softvegetation", false}, {"dithercrossfade", false},    {"noinstancing", false},    {"vertexcolor", false},
};

// The program's text with its `#pragma surface` line made a comment (at its '#'), so that its
// lines keep their numbers and the front end reads no pragma it would warn about.
std::string without_surface_pragma(const std::string& text) {
  const std::vector<std::string_view> found = pragma_arguments(text, "surface");
  if (found.empty()) return text;
  const size_t hash = text.rfind('#', size_t(found.front().data() - text.data()));
  std::string result = text;
  result.insert(hash, "//");
  return result;
}

bool has_field(const std::vector<std::string>& fields, std::string_view name) {
  return std::find(fields.begin(), fields.end(), name) != fields.end();
}

StateValue word(std::string text, const SourceLocation& where) { return {std::move(text), false, where}; }

BlendState blend(const char* source, const char* destination, const SourceLocation& where) {
  BlendState state;
  state.source = word(source, where);
  state.destination = word(destination, where);
  return state;
}

enum class GeneratedPass { ForwardBase, ForwardAdd, ShadowCaster };

// How transparent the directive makes the object: Unity's `alpha` options.
enum class AlphaMode { Opaque, Blend, Fade, Premultiplied };

AlphaMode alpha_mode(const SurfaceDirective& directive) {
  if (!directive.has("alpha")) return AlphaMode::Opaque;
  std::string value = directive.value("alpha");
  if (value == "blend") return AlphaMode::Blend;
  if (value == "fade") return AlphaMode::Fade;
  if (value == "premul") return AlphaMode::Premultiplied;
  // `alpha` and `alpha:auto`: fade for the simple lighting models, premultiplied for the
  // physically based ones (Unity's manual).
  const std::string& model = directive.lighting_model;
  return model == "Standard" || model == "StandardSpecular" ? AlphaMode::Premultiplied : AlphaMode::Fade;
}

// What an Input field is, by the names and semantics Unity's manual gives them.
struct InputUse {
  const SurfaceField* field;
  enum Kind { Uv, WorldPos, WorldNormal, WorldRefl, ViewDir, ScreenPos, Color, Face, TangentToWorld, Custom } kind;
  int uv_set = 0;          // Uv: 0 for uv_, 1 for uv2_, ...
  std::string texture;     // Uv: the texture whose _ST transforms it
  std::string packed;      // Uv: where it travels, two to an interpolator as Unity packs them: pack0.xy
  bool half_pack = false;  // Uv: in half of its interpolator (.xy or .zw), a float2; else all of it
};

std::vector<InputUse> classify_input(const std::vector<SurfaceField>& input) {
  std::vector<InputUse> uses;
  for (const SurfaceField& field : input) {
    InputUse use{&field, InputUse::Custom, 0, {}, {}, false};
    const std::string& name = field.name;
    // "uv" or "uv2" to "uv4" followed by the texture's name: uv_MainTex is _MainTex's.
    static constexpr std::array<const char*, 4> kUvPrefixes = {"uv", "uv2", "uv3", "uv4"};
    for (size_t set = 0; set < kUvPrefixes.size(); ++set) {
      std::string_view prefix = kUvPrefixes[set];
      if (name.size() > prefix.size() + 1 && name.compare(0, prefix.size(), prefix) == 0 &&
          name[prefix.size()] == '_') {
        use.kind = InputUse::Uv;
        use.uv_set = static_cast<int>(set);
        use.texture = name.substr(prefix.size());
      }
    }
    if (use.kind == InputUse::Custom) {
      if (same_word(field.semantic, "COLOR") || same_word(field.semantic, "COLOR0"))
        use.kind = InputUse::Color;
      else if (same_word(field.semantic, "VFACE") || same_word(field.semantic, "SV_IsFrontFace"))
        use.kind = InputUse::Face;
      else if (name == "worldPos")
        use.kind = InputUse::WorldPos;
      else if (name == "worldNormal")
        use.kind = InputUse::WorldNormal;
      else if (name == "worldRefl")
        use.kind = InputUse::WorldRefl;
      else if (name == "viewDir")
        use.kind = InputUse::ViewDir;
      else if (name == "screenPos")
        use.kind = InputUse::ScreenPos;
      else if (name.rfind("internalSurfaceTtoW", 0) == 0)
        use.kind = InputUse::TangentToWorld;
    }
    uses.push_back(std::move(use));
  }
  return uses;
}

// The width of a float type's spelling: float2 -> 2, fixed -> 1.
int width_of(const std::string& type) {
  if (!type.empty() && type.back() >= '1' && type.back() <= '4') return type.back() - '0';
  return 1;
}

std::string swizzle(int width) { return std::string("xyzw").substr(0, static_cast<size_t>(width)); }

class SurfaceGenerator {
 public:
  SurfaceGenerator(const ProgramBlock& surface, const std::vector<ProgramBlock>& includes,
                   const SurfaceDirective& directive, const SurfaceProgramShape& shape)
      : surface_(surface),
        includes_(includes),
        directive_(directive),
        shape_(shape),
        uses_(classify_input(shape.input)),
        alpha_(alpha_mode(directive)) {
    // Unity packs two float2 uvs into one float4 interpolator (pack0.xy, pack0.zw), so that a
    // surface shader with several textures stays inside the eight TEXCOORDs a target has.
    bool half_used = false;
    for (InputUse& use : uses_) {
      if (use.kind != InputUse::Uv) continue;
      const std::string pack = "pack" + std::to_string(packs_);
      use.half_pack = width_of(use.field->type) <= 2;
      if (use.half_pack) {
        use.packed = pack + (half_used ? ".zw" : ".xy");
        if (half_used) ++packs_;
        half_used = !half_used;
      } else {
        if (half_used) ++packs_;
        half_used = false;
        use.packed = "pack" + std::to_string(packs_++);
      }
    }
    if (half_used) ++packs_;
  }

  Pass pass(GeneratedPass which) {
    which_ = which;
    Pass pass;
    pass.kind = PassKind::Program;
    pass.generated = true;
    pass.where = directive_.where;
    const SourceLocation& at = directive_.where;
    if (which == GeneratedPass::ShadowCaster) {
      pass.name = "ShadowCaster";
      pass.tags = {{"LightMode", "ShadowCaster"}};
      pass.state.zwrite = word("On", at);
      pass.state.ztest = word("LEqual", at);
    } else {
      pass.name = "FORWARD";
      pass.tags = {{"LightMode", which == GeneratedPass::ForwardBase ? "ForwardBase" : "ForwardAdd"}};
      set_forward_state(pass.state, which);
    }
    // Messages about the generated lines name them by the pass and their line in its text.
    ProgramBlock program;
    program.language = ProgramLanguage::Cg;
    program.start = {surface_.start.file + " (generated " + pass.tags.front().second + " pass)", 1, 1};
    program.text = text(program.start.file);
    pass.program = std::move(program);
    return pass;
  }

 private:
  bool forward() const { return which_ != GeneratedPass::ShadowCaster; }
  bool base() const { return which_ == GeneratedPass::ForwardBase; }
  bool legacy() const { return shape_.lighting == LightingForm::Legacy || shape_.lighting == LightingForm::LegacyView; }
  bool ambient() const { return base() && !directive_.has("noambient"); }
  bool fog() const { return forward() && !directive_.has("nofog"); }
  bool has_input(InputUse::Kind kind) const {
    return std::any_of(uses_.begin(), uses_.end(), [&](const InputUse& use) { return use.kind == kind; });
  }
  bool vertex_field(std::string_view name) const { return has_field(shape_.vertex_input_fields, name); }
  // A field of the vertex input, or `fallback` where the author's vertex input type has none.
  std::string vertex_input(std::string_view name, std::string_view fallback) const {
    return vertex_field(name) ? "v." + std::string(name) : std::string(fallback);
  }

  void set_forward_state(RenderState& state, GeneratedPass which) const {
    const SourceLocation& at = directive_.where;
    const std::string decal = directive_.value("decal");
    if (which == GeneratedPass::ForwardAdd) {
      state.zwrite = word("Off", at);
      state.blend.push_back(alpha_ == AlphaMode::Blend || alpha_ == AlphaMode::Fade ? blend("SrcAlpha", "One", at)
                                                                                    : blend("One", "One", at));
    } else if (alpha_ == AlphaMode::Blend || alpha_ == AlphaMode::Fade || decal == "blend") {
      state.blend.push_back(blend("SrcAlpha", "OneMinusSrcAlpha", at));
    } else if (alpha_ == AlphaMode::Premultiplied) {
      state.blend.push_back(blend("One", "OneMinusSrcAlpha", at));
    } else if (decal == "add") {
      state.blend.push_back(blend("One", "One", at));
    }
    if (alpha_ != AlphaMode::Opaque || !decal.empty()) {
      state.zwrite = word("Off", at);
      state.color_mask = word("RGB", at);
    }
    if (!decal.empty()) state.offset = std::make_pair(word("-1", at), word("-1", at));
  }

  std::string text(const std::string& generated_name) {
    std::string out;
    out += "#pragma vertex vert_surf\n#pragma fragment frag_surf\n";
    if (fog()) out += "#pragma multi_compile_fog\n";
    if (base()) {
      out +=
          alpha_ == AlphaMode::Opaque ? "#pragma multi_compile_fwdbase" : "#pragma multi_compile_fwdbasealpha noshadow";
      for (const char* option : {"nolightmap", "nodynlightmap", "nodirlightmap", "noshadowmask"})
        if (directive_.has(option)) out += std::string(" ") + option;
      out += "\n#define UNITY_PASS_FORWARDBASE\n";
    } else if (which_ == GeneratedPass::ForwardAdd) {
      out += directive_.has("fullforwardshadows") ? "#pragma multi_compile_fwdadd_fullshadows\n"
                                                  : "#pragma multi_compile_fwdadd\n";
      out += "#define UNITY_PASS_FORWARDADD\n";
    } else {
      out += "#pragma multi_compile_shadowcaster\n#define UNITY_PASS_SHADOWCASTER\n";
    }
    if (alpha_ == AlphaMode::Fade) out += "#define _ALPHABLEND_ON 1\n";
    if (alpha_ == AlphaMode::Premultiplied) out += "#define _ALPHAPREMULTIPLY_ON 1\n";
    out += "#include \"UnityCG.cginc\"\n#include \"Lighting.cginc\"\n";
    if (directive_.lighting_model == "Standard" || directive_.lighting_model == "StandardSpecular")
      out += "#include \"UnityPBSLighting.cginc\"\n";
    out += "#include \"AutoLight.cginc\"\n";
    out += shape_.writes_normal ? kTangentSpaceMacros : kWorldSpaceMacros;
    for (const ProgramBlock& block : includes_) append_block(out, block);
    append_block(out, surface_, without_surface_pragma(surface_.text));
    // Back to the generated text: the line after this one is its line count + 2 in it.
    out += "#line " + std::to_string(std::count(out.begin(), out.end(), '\n') + 2) + " \"" + generated_name + "\"\n";
    declarations(out);
    vertex_function(out);
    fragment_function(out);
    return out;
  }

  // The interpolators: what the fragment program needs of the Input struct and for lighting.
  void declarations(std::string& out) {
    int next = forward() ? 0 : 1;  // a shadow caster's V2F_SHADOW_CASTER takes TEXCOORD0
    auto slot = [&] { return " : TEXCOORD" + std::to_string(next++) + ";\n"; };
    out += "struct v2f_surf {\n";
    out += forward() ? "  UNITY_POSITION(pos);\n" : "  V2F_SHADOW_CASTER;\n";
    for (int pack = 0; pack < packs_; ++pack) out += "  float4 pack" + std::to_string(pack) + slot();
    for (const InputUse& use : uses_)
      if (use.kind == InputUse::Custom) out += "  " + use.field->type + " " + custom(use) + slot();
    if (shape_.writes_normal) {
      // The tangent-to-world rows, with the world position in w (Unity's tSpace0..2).
      for (int row = 0; row < 3; ++row) out += "  float4 tSpace" + std::to_string(row) + slot();
    } else {
      out += "  float3 worldNormal" + slot();
      out += "  float3 worldPos" + slot();
    }
    if (has_input(InputUse::ScreenPos)) out += "  float4 screenPos" + slot();
    if (has_input(InputUse::Color)) out += "  fixed4 color : COLOR0;\n";
    if (ambient()) out += "  #if UNITY_SHOULD_SAMPLE_SH\n  half3 sh" + slot() + "  #endif\n";
    // As Unity's generated passes: the base pass's light is directional, whose light coordinates
    // are none, so it declares only the shadow's; an additive pass's light may be a point, a spot
    // or have a cookie.
    const auto fog_coords = [&] {
      if (fog()) out += "  UNITY_FOG_COORDS(" + std::to_string(next++) + ")\n";
    };
    if (base()) {
      fog_coords();
      out += "  UNITY_SHADOW_COORDS(" + std::to_string(next++) + ")\n";
    } else if (forward()) {
      const int light = next++, shadow = next++;
      out += "  UNITY_LIGHTING_COORDS(" + std::to_string(light) + "," + std::to_string(shadow) + ")\n";
      fog_coords();
    }
    out += "};\n";
    // The _ST of each texture a uv_ field names, unless the author's program declares it.
    std::vector<std::string> declared;
    for (const InputUse& use : uses_)
      if (use.kind == InputUse::Uv && !has_field(shape_.globals, use.texture + "_ST") &&
          !has_field(declared, use.texture + "_ST")) {
        declared.push_back(use.texture + "_ST");
        out += "float4 " + use.texture + "_ST;\n";
      }
    const std::string cutoff = directive_.value("alphatest");
    if (!cutoff.empty() && !has_field(shape_.globals, cutoff)) out += "fixed " + cutoff + ";\n";
  }

  static std::string custom(const InputUse& use) { return "custom_" + use.field->name; }

  void vertex_function(std::string& out) {
    out += "v2f_surf vert_surf (" + shape_.vertex_input_type + " v) {\n";
    out += "  UNITY_SETUP_INSTANCE_ID(v);\n  v2f_surf o;\n  UNITY_INITIALIZE_OUTPUT(v2f_surf,o);\n";
    const std::string modifier = directive_.value("vertex");
    if (!modifier.empty()) {
      if (shape_.vertex_fills_input) {
        out += "  Input customInputData;\n  " + modifier + " (v, customInputData);\n";
        for (const InputUse& use : uses_)
          if (use.kind == InputUse::Custom)
            out += "  o." + custom(use) + " = customInputData." + use.field->name + ";\n";
      } else {
        out += "  " + modifier + " (v);\n";
      }
    }
    if (forward()) out += "  o.pos = UnityObjectToClipPos(v.vertex);\n";
    const std::array<const char*, 4> texcoords = {"texcoord", "texcoord1", "texcoord2", "texcoord3"};
    for (const InputUse& use : uses_) {
      if (use.kind != InputUse::Uv) continue;
      const std::string source = vertex_input(texcoords[static_cast<size_t>(use.uv_set)], "float4(0,0,0,0)");
      const std::string transformed = "TRANSFORM_TEX(" + source + ", " + use.texture + ")";
      if (use.half_pack) {
        out += "  o." + use.packed + " = " + transformed + ";\n";
      } else {
        out += "  o." + use.packed + " = " + source + ";\n  o." + use.packed + ".xy = " + transformed + ";\n";
      }
    }
    out += "  float3 worldPos = mul(unity_ObjectToWorld, v.vertex).xyz;\n";
    out += "  float3 worldNormal = UnityObjectToWorldNormal(v.normal);\n";
    if (shape_.writes_normal) {
      out += "  fixed3 worldTangent = UnityObjectToWorldDir(" + vertex_input("tangent", "float4(1,0,0,1)") + ".xyz);\n";
      out += "  fixed tangentSign = " + vertex_input("tangent", "float4(1,0,0,1)") +
             ".w * unity_WorldTransformParams.w;\n";
      out += "  fixed3 worldBinormal = cross(worldNormal, worldTangent) * tangentSign;\n";
      out += "  o.tSpace0 = float4(worldTangent.x, worldBinormal.x, worldNormal.x, worldPos.x);\n";
      out += "  o.tSpace1 = float4(worldTangent.y, worldBinormal.y, worldNormal.y, worldPos.y);\n";
      out += "  o.tSpace2 = float4(worldTangent.z, worldBinormal.z, worldNormal.z, worldPos.z);\n";
    } else {
      out += "  o.worldNormal = worldNormal;\n  o.worldPos = worldPos;\n";
    }
    if (has_input(InputUse::ScreenPos)) out += "  o.screenPos = ComputeScreenPos(UnityObjectToClipPos(v.vertex));\n";
    if (has_input(InputUse::Color)) out += "  o.color = " + vertex_input("color", "fixed4(1,1,1,1)") + ";\n";
    if (ambient()) {
      // The simple lighting functions' ambient is ShadeSH9 per vertex, which the fragment adds
      // times the albedo; Unity's GI functions take the L2 band per vertex and add the rest per
      // pixel (ShadeSHPerVertex, ShadeSHPerPixel).
      out += "  #if UNITY_SHOULD_SAMPLE_SH && !UNITY_SAMPLE_FULL_SH_PER_PIXEL\n";
      out += legacy() ? "  o.sh = ShadeSH9(float4(worldNormal, 1.0));\n" : "  o.sh = 0;\n";
      if (!directive_.has("novertexlights"))
        out +=
            "  #ifdef VERTEXLIGHT_ON\n"
            "  o.sh += Shade4PointLights(unity_4LightPosX0, unity_4LightPosY0, unity_4LightPosZ0,\n"
            "    unity_LightColor[0].rgb, unity_LightColor[1].rgb, unity_LightColor[2].rgb, unity_LightColor[3].rgb,\n"
            "    unity_4LightAtten0, worldPos, worldNormal);\n"
            "  #endif\n";
      if (!legacy()) out += "  o.sh = ShadeSHPerVertex(worldNormal, o.sh);\n";
      out += "  #endif\n";
    }
    if (forward()) {
      out += "  UNITY_TRANSFER_LIGHTING(o, " + vertex_input("texcoord1", "float4(0,0,0,0)") + ".xy);\n";
      if (fog()) out += "  UNITY_TRANSFER_FOG(o,o.pos);\n";
    } else {
      out += "  TRANSFER_SHADOW_CASTER_NORMALOFFSET(o)\n";
    }
    out += "  return o;\n}\n";
  }

  void fragment_function(std::string& out) {
    const bool face = has_input(InputUse::Face);
    out += std::string(forward() ? "fixed4" : "float4") + " frag_surf (v2f_surf IN" +
           (face ? ", fixed facing : VFACE" : "") + ") : SV_Target {\n";
    out += "  UNITY_SETUP_INSTANCE_ID(IN);\n  Input surfIN;\n  UNITY_INITIALIZE_OUTPUT(Input,surfIN);\n";
    out += shape_.writes_normal ? "  float3 worldPos = float3(IN.tSpace0.w, IN.tSpace1.w, IN.tSpace2.w);\n"
                                : "  float3 worldPos = IN.worldPos;\n";
    out +=
        "  #ifndef USING_DIRECTIONAL_LIGHT\n  fixed3 lightDir = normalize(UnityWorldSpaceLightDir(worldPos));\n"
        "  #else\n  fixed3 lightDir = _WorldSpaceLightPos0.xyz;\n  #endif\n";
    out += "  float3 worldViewDir = normalize(UnityWorldSpaceViewDir(worldPos));\n";
    if (shape_.writes_normal)
      out +=
          "  float3 _unity_tbn_0 = IN.tSpace0.xyz;\n  float3 _unity_tbn_1 = IN.tSpace1.xyz;\n"
          "  float3 _unity_tbn_2 = IN.tSpace2.xyz;\n";
    for (const InputUse& use : uses_) {
      const std::string field = "surfIN." + use.field->name;
      switch (use.kind) {
        case InputUse::Uv:
          out += "  " + field + " = IN." + use.packed +
                 (use.half_pack ? "" : "." + swizzle(width_of(use.field->type))) + ";\n";
          break;
        case InputUse::Custom: out += "  " + field + " = IN." + custom(use) + ";\n"; break;
        case InputUse::WorldPos: out += "  " + field + " = worldPos;\n"; break;
        case InputUse::WorldNormal:
          out += "  " + field + (shape_.writes_normal ? " = 0.0;\n" : " = IN.worldNormal;\n");
          break;
        case InputUse::WorldRefl:
          out += "  " + field +
                 (shape_.writes_normal ? " = -worldViewDir;\n" : " = reflect(-worldViewDir, IN.worldNormal);\n");
          break;
        case InputUse::ViewDir:
          // In tangent space where the surface function writes a tangent-space normal (Unity's manual).
          out += "  " + field +
                 (shape_.writes_normal ? " = _unity_tbn_0 * worldViewDir.x + _unity_tbn_1 * worldViewDir.y + "
                                         "_unity_tbn_2 * worldViewDir.z;\n"
                                       : " = worldViewDir;\n");
          break;
        case InputUse::ScreenPos: out += "  " + field + " = IN.screenPos;\n"; break;
        case InputUse::Color: out += "  " + field + " = IN.color;\n"; break;
        case InputUse::Face: out += "  " + field + " = facing;\n"; break;
        case InputUse::TangentToWorld:
          // INTERNAL_DATA declares these only where the surface function writes a normal.
          if (shape_.writes_normal)
            out += "  " + field + " = _unity_tbn_" + use.field->name.substr(use.field->name.size() - 1) + ";\n";
          break;
      }
    }
    const std::string& output = shape_.output_type;
    out += "  " + output + " o = (" + output + ")0;\n";
    for (const char* zero : {"Albedo", "Emission", "Specular", "Alpha", "Gloss"})
      if (has_field(shape_.output_fields, zero)) out += std::string("  o.") + zero + " = 0.0;\n";
    if (has_field(shape_.output_fields, "Occlusion")) out += "  o.Occlusion = 1.0;\n";
    if (has_field(shape_.output_fields, "Normal"))
      out += shape_.writes_normal ? "  o.Normal = fixed3(0,0,1);\n" : "  o.Normal = IN.worldNormal;\n";
    out += "  " + directive_.function + " (surfIN, o);\n";
    const std::string cutoff = directive_.value("alphatest");
    if (!cutoff.empty()) out += "  clip(o.Alpha - " + cutoff + ");\n";
    if (shape_.writes_normal)
      out +=
          "  float3 worldN;\n  worldN.x = dot(_unity_tbn_0, o.Normal);\n  worldN.y = dot(_unity_tbn_1, o.Normal);\n"
          "  worldN.z = dot(_unity_tbn_2, o.Normal);\n  worldN = normalize(worldN);\n  o.Normal = worldN;\n";
    if (!forward()) {
      out += "  SHADOW_CASTER_FRAGMENT(IN)\n}\n";
      return;
    }
    out += "  UNITY_LIGHT_ATTENUATION(atten, IN, worldPos)\n  fixed4 c = 0;\n";
    lighting(out);
    if (base() && has_field(shape_.output_fields, "Emission")) out += "  c.rgb += o.Emission;\n";
    if (!base()) out += "  c.a = 0.0;\n";
    const std::string final_color = directive_.value("finalcolor");
    if (!final_color.empty()) out += "  " + final_color + " (surfIN, o, c);\n";
    if (fog()) out += "  UNITY_APPLY_FOG(IN.fogCoord, c);\n";
    if (alpha_ == AlphaMode::Opaque && !directive_.has("keepalpha")) out += "  UNITY_OPAQUE_ALPHA(c.a);\n";
    out += "  return c;\n}\n";
  }

  void lighting(std::string& out) {
    const std::string function = "Lighting" + directive_.lighting_model;
    const std::string view = directive_.has("halfasview") ? "normalize(lightDir + worldViewDir)" : "worldViewDir";
    if (legacy()) {
      if (ambient()) out += "  #if UNITY_SHOULD_SAMPLE_SH\n  c.rgb += o.Albedo * IN.sh;\n  #endif\n";
      out += "  c += " + function + " (o, lightDir, " +
             (shape_.lighting == LightingForm::LegacyView ? view + ", " : "") + "atten);\n";
      return;
    }
    out +=
        "  UnityGI gi;\n  UNITY_INITIALIZE_OUTPUT(UnityGI, gi);\n  gi.indirect.diffuse = 0;\n  gi.indirect.specular = "
        "0;\n"
        "  gi.light.color = _LightColor0.rgb;\n  gi.light.dir = lightDir;\n";
    if (base()) {
      out +=
          "  UnityGIInput giInput;\n  UNITY_INITIALIZE_OUTPUT(UnityGIInput, giInput);\n  giInput.light = gi.light;\n"
          "  giInput.worldPos = worldPos;\n  giInput.worldViewDir = worldViewDir;\n  giInput.atten = atten;\n"
          "  giInput.lightmapUV = 0.0;\n";
      out += ambient() ? "  #if UNITY_SHOULD_SAMPLE_SH && !UNITY_SAMPLE_FULL_SH_PER_PIXEL\n  giInput.ambient = IN.sh;\n"
                         "  #else\n  giInput.ambient.rgb = 0.0;\n  #endif\n"
                       : "  giInput.ambient.rgb = 0.0;\n";
      out +=
          "  giInput.probeHDR[0] = unity_SpecCube0_HDR;\n  giInput.probeHDR[1] = unity_SpecCube1_HDR;\n"
          "  #if defined(UNITY_SPECCUBE_BLENDING) || defined(UNITY_SPECCUBE_BOX_PROJECTION)\n"
          "  giInput.boxMin[0] = unity_SpecCube0_BoxMin;\n  #endif\n"
          "  #ifdef UNITY_SPECCUBE_BOX_PROJECTION\n  giInput.boxMax[0] = unity_SpecCube0_BoxMax;\n"
          "  giInput.probePosition[0] = unity_SpecCube0_ProbePosition;\n  giInput.boxMax[1] = unity_SpecCube1_BoxMax;\n"
          "  giInput.boxMin[1] = unity_SpecCube1_BoxMin;\n  giInput.probePosition[1] = unity_SpecCube1_ProbePosition;\n"
          "  #endif\n";
      out += "  " + function + "_GI(o, giInput, gi);\n";
    } else {
      out += "  gi.light.color *= atten;\n";
    }
    out += "  c += " + function + " (o, " + (shape_.lighting == LightingForm::ViewGi ? view + ", " : "") + "gi);\n";
  }

  static constexpr const char* kWorldSpaceMacros =
      "#define INTERNAL_DATA\n"
      "#define WorldReflectionVector(data,normal) data.worldRefl\n"
      "#define WorldNormalVector(data,normal) normal\n";
  static constexpr const char* kTangentSpaceMacros =
      "#define INTERNAL_DATA half3 internalSurfaceTtoW0; half3 internalSurfaceTtoW1; half3 internalSurfaceTtoW2;\n"
      "#define WorldReflectionVector(data,normal) reflect (data.worldRefl, "
      "half3(dot(data.internalSurfaceTtoW0,normal), "
      "dot(data.internalSurfaceTtoW1,normal), dot(data.internalSurfaceTtoW2,normal)))\n"
      "#define WorldNormalVector(data,normal) fixed3(dot(data.internalSurfaceTtoW0,normal), "
      "dot(data.internalSurfaceTtoW1,normal), dot(data.internalSurfaceTtoW2,normal))\n";

  const ProgramBlock& surface_;
  const std::vector<ProgramBlock>& includes_;
  const SurfaceDirective& directive_;
  const SurfaceProgramShape& shape_;
  std::vector<InputUse> uses_;
  AlphaMode alpha_;
  int packs_ = 0;  // the float4 interpolators the uvs take
  GeneratedPass which_ = GeneratedPass::ForwardBase;
};

}  // namespace

bool SurfaceDirective::has(std::string_view option) const {
  return std::any_of(options.begin(), options.end(), [&](const auto& entry) { return entry.first == option; });
}

std::string SurfaceDirective::value(std::string_view option) const {
  for (const auto& [name, value] : options)
    if (name == option) return value;
  return {};
}

Result<SurfaceDirective> read_surface_directive(const ProgramBlock& program) {
  const std::vector<std::string_view> found = pragma_arguments(program.text, "surface");
  if (found.empty())
    return fail(ErrorKind::UserInput,
                "a program outside any Pass is a surface shader's, and this one has no `#pragma surface surfFunc "
                "lightModel`; put a vertex and fragment program inside a Pass { }",
                program.start);
  SurfaceDirective directive;
  std::string_view rest = found.front();
  const auto line = std::count(program.text.data(), rest.data(), '\n');
  directive.where = {program.start.file, program.start.line + static_cast<uint32_t>(line), 1};
  if (size_t comment = rest.find("//"); comment != std::string_view::npos) rest = rest.substr(0, comment);
  std::vector<std::string> words;
  size_t at = 0;
  while ((at = rest.find_first_not_of(" \t\r", at)) != std::string_view::npos) {
    size_t stop = rest.find_first_of(" \t\r", at);
    words.emplace_back(rest.substr(at, stop == std::string_view::npos ? std::string_view::npos : stop - at));
    at = stop;
  }
  if (words.size() < 2)
    return fail(ErrorKind::UserInput,
                "`#pragma surface` needs a surface function and a lighting model: `#pragma surface surf Lambert`",
                directive.where);
  directive.function = words[0];
  directive.lighting_model = words[1];
  for (size_t i = 2; i < words.size(); ++i) {
    const std::string& option = words[i];
    const size_t colon = option.find(':');
    std::string name = option.substr(0, colon), value = colon == std::string::npos ? "" : option.substr(colon + 1);
    const auto known = std::find_if(std::begin(kOptions), std::end(kOptions),
                                    [&](const KnownOption& candidate) { return name == candidate.name; });
    if (known == std::end(kOptions))
      return fail(ErrorKind::UserInput,
                  "`#pragma surface` has no option '" + name +
                      "' (Unity's manual lists alpha, alphatest:, vertex:, "
                      "finalcolor:, addshadow, fullforwardshadows, noforwardadd, nofog, ...)",
                  directive.where);
    if (known->takes_value && value.empty())
      return fail(ErrorKind::UserInput, "the surface option '" + name + "' takes a value: `" + name + ":...`",
                  directive.where);
    if (name == "tessellate" || name == "tessphong")
      return fail(
          ErrorKind::UserInput,
          "`" + name + ":` asks for a tessellation stage, and xshade compiles vertex and fragment programs only",
          directive.where);
    directive.options.emplace_back(std::move(name), std::move(value));
  }
  return directive;
}

std::vector<Pass> generate_surface_passes(const ProgramBlock& surface, const std::vector<ProgramBlock>& includes,
                                          const SurfaceDirective& directive, const SurfaceProgramShape& shape) {
  SurfaceGenerator generator(surface, includes, directive, shape);
  std::vector<Pass> passes;
  const std::string path = directive.value("exclude_path");
  if (path != "forward") {
    passes.push_back(generator.pass(GeneratedPass::ForwardBase));
    if (!directive.has("noforwardadd")) passes.push_back(generator.pass(GeneratedPass::ForwardAdd));
  }
  if (directive.has("addshadow")) passes.push_back(generator.pass(GeneratedPass::ShadowCaster));
  return passes;
}

std::string surface_program_for_analysis(const ProgramBlock& surface, const std::vector<ProgramBlock>& includes) {
  std::string out =
      "#include \"UnityCG.cginc\"\n#include \"Lighting.cginc\"\n#include \"UnityPBSLighting.cginc\"\n"
      "#include \"AutoLight.cginc\"\n";
  // INTERNAL_DATA as the tangent-space form declares it, so that an Input that holds it shows it.
  out +=
      "#define INTERNAL_DATA half3 internalSurfaceTtoW0; half3 internalSurfaceTtoW1; half3 internalSurfaceTtoW2;\n"
      "#define WorldReflectionVector(data,normal) data.worldRefl\n#define WorldNormalVector(data,normal) normal\n";
  for (const ProgramBlock& block : includes) append_block(out, block);
  append_block(out, surface, without_surface_pragma(surface.text));
  return out;
}

}  // namespace xshade::shaderlab
