#include "shaderlab/reader.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <span>

#include "base/file_io.h"
#include "shaderlab/lexer.h"

namespace xshade::shaderlab {
namespace {

// Unity's LODs are hundreds (100 to 600 for its built-in shaders); the bound keeps one an int.
constexpr int kLargestLod = 1000000;

// The first error ends the reading; it travels up as this and leaves read_shader as a Result.
struct ReadError {
  Diagnostic diagnostic;
};

std::string describe(const Token& token) {
  switch (token.kind) {
    case TokenKind::End: return "the end of the file";
    case TokenKind::String: return "\"" + token.text + "\"";
    case TokenKind::Program: return "a program block";
    default: return "'" + token.text + "'";
  }
}

using Words = std::span<const std::string_view>;

std::string one_of(Words words) {
  std::string list;
  size_t i = 0;
  for (std::string_view word : words) {
    list += i == 0 ? "" : (i + 1 == words.size() ? " or " : ", ");
    list += word;
    ++i;
  }
  return list;
}

// The words each render state command takes, in Unity's spelling.
constexpr std::string_view kCull[] = {"Back", "Front", "Off"};
constexpr std::string_view kCompare[] = {"Less", "Greater", "LEqual", "GEqual", "Equal", "NotEqual", "Always", "Never"};
constexpr std::string_view kBlendFactors[] = {"One",
                                              "Zero",
                                              "SrcColor",
                                              "SrcAlpha",
                                              "SrcAlphaSaturate",
                                              "DstColor",
                                              "DstAlpha",
                                              "OneMinusSrcColor",
                                              "OneMinusSrcAlpha",
                                              "OneMinusDstColor",
                                              "OneMinusDstAlpha"};
constexpr std::string_view kBlendOps[] = {"Add",
                                          "Sub",
                                          "RevSub",
                                          "Min",
                                          "Max",
                                          "LogicalClear",
                                          "LogicalSet",
                                          "LogicalCopy",
                                          "LogicalCopyInverted",
                                          "LogicalNoop",
                                          "LogicalInvert",
                                          "LogicalAnd",
                                          "LogicalNand",
                                          "LogicalOr",
                                          "LogicalNor",
                                          "LogicalXor",
                                          "LogicalEquiv",
                                          "LogicalAndReverse",
                                          "LogicalAndInverted",
                                          "LogicalOrReverse",
                                          "LogicalOrInverted",
                                          "Multiply",
                                          "Screen",
                                          "Overlay",
                                          "Darken",
                                          "Lighten",
                                          "ColorDodge",
                                          "ColorBurn",
                                          "HardLight",
                                          "SoftLight",
                                          "Difference",
                                          "Exclusion",
                                          "HSLHue",
                                          "HSLSaturation",
                                          "HSLColor",
                                          "HSLLuminosity"};
constexpr std::string_view kStencilOps[] = {"Keep",    "Zero",   "Replace",  "IncrSat",
                                            "DecrSat", "Invert", "IncrWrap", "DecrWrap"};
// A switch: Unity reads On and True alike, and Off and False.
constexpr std::string_view kSwitch[] = {"On", "Off", "True", "False"};
// Commands of the fixed-function pipeline: read past, noted, never drawn.
constexpr std::string_view kFixedFunction[] = {"Lighting",  "Material",      "SetTexture",       "Fog",
                                               "AlphaTest", "ColorMaterial", "SeparateSpecular", "BindChannels"};

class Reader {
 public:
  Reader(std::string_view text, std::string file) : lex_(text), file_(std::move(file)) {}

  Shader read() {
    const Token start = lex_.peek();
    expect_word("Shader");
    shader_.name = expect(TokenKind::String, "the shader's name in quotes").text;
    expect('{', "after the shader's name");
    std::vector<ProgramBlock> includes;
    while (!lex_.peek().is('}')) {
      const Token token = lex_.next();
      if (token.is_word("Properties")) {
        properties();
      } else if (token.is_word("SubShader")) {
        shader_.subshaders.push_back(subshader(token, {}, {}, includes));
      } else if (token.is_word("Category")) {
        category(includes);
      } else if (token.is_word("Fallback")) {
        fallback();
      } else if (token.is_word("CustomEditor") || token.is_word("CustomEditorForRenderPipeline")) {
        shader_.custom_editor = expect(TokenKind::String, "the editor's class name in quotes").text;
        if (token.is_word("CustomEditorForRenderPipeline")) expect(TokenKind::String, "the render pipeline's name");
      } else if (token.is_word("Dependency")) {
        const std::string name = expect(TokenKind::String, "the dependency's name in quotes").text;
        expect('=', "after the dependency's name");
        shader_.dependencies.emplace_back(name, expect(TokenKind::String, "the shader's name in quotes").text);
      } else if (token.kind == TokenKind::Program) {
        includes.push_back(include_block(token));
      } else {
        unexpected(
            token,
            "in a Shader block: Properties, SubShader, Category, Fallback, CustomEditor, Dependency or CGINCLUDE");
      }
    }
    lex_.next();
    const Token after = lex_.next();
    if (after.kind != TokenKind::End) fail(after, describe(after) + " after the Shader block's closing '}'");
    if (shader_.subshaders.empty() && !shader_.fallback) fail(start, "the shader has no SubShader (and no Fallback)");
    return std::move(shader_);
  }

 private:
  SourceLocation where(const Token& token) const { return {file_, token.line, token.column}; }

  [[noreturn]] void fail(const Token& token, std::string message) const {
    if (token.kind == TokenKind::Bad) message = token.text;
    throw ReadError{{Severity::Error, where(token), std::move(message)}};
  }
  [[noreturn]] void unexpected(const Token& token, std::string_view expected) const {
    fail(token, "unexpected " + describe(token) + " " + std::string(expected));
  }
  void note(const Token& token, std::string message) {
    shader_.notes.push_back({Severity::Warning, where(token), std::move(message)});
  }

  Token expect(TokenKind kind, std::string_view what) {
    const Token token = lex_.next();
    if (token.kind != kind) fail(token, "expected " + std::string(what) + ", found " + describe(token));
    return token;
  }
  Token expect(char punct, std::string_view context) {
    const Token token = lex_.next();
    if (!token.is(punct))
      fail(token, "expected '" + std::string(1, punct) + "' " + std::string(context) + ", found " + describe(token));
    return token;
  }
  void expect_word(std::string_view word) {
    const Token token = lex_.next();
    if (!token.is_word(word)) fail(token, "expected '" + std::string(word) + "', found " + describe(token));
  }
  bool accept(char punct) {
    if (!lex_.peek().is(punct)) return false;
    lex_.next();
    return true;
  }

  float number(const Token& token, std::string_view what) {
    if (token.kind != TokenKind::Number) fail(token, "expected " + std::string(what) + ", found " + describe(token));
    const std::string text = token.text[0] == '+' ? token.text.substr(1) : token.text;
    float value = 0.0f;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size()) fail(token, "'" + token.text + "' is not a number");
    return value;
  }
  // A count or an index: a whole number from `lowest` to `highest`.
  int whole_number(const Token& token, std::string_view what, int lowest, int highest) {
    const float value = number(token, what);
    if (value != std::floor(value) || value < float(lowest) || value > float(highest))
      fail(token, "expected " + std::string(what) + ", a whole number from " + std::to_string(lowest) + " to " +
                      std::to_string(highest) + ", found " + token.text);
    return int(value);
  }
  float signed_number(std::string_view what) {
    // "- 1" as two tokens: ShaderLab allows a sign apart from its number.
    if (accept('-')) return -number(lex_.next(), what);
    accept('+');
    return number(lex_.next(), what);
  }

  // ---- Properties ----

  void properties() {
    expect('{', "after Properties");
    while (!accept('}')) {
      Property property;
      Token token = lex_.next();
      while (token.is('[')) {
        property.attributes.push_back(attribute(token));
        token = lex_.next();
      }
      if (token.kind != TokenKind::Word)
        unexpected(token, "where a property's name belongs (_Name (\"Label\", Type) = default)");
      property.name = token.text;
      property.where = where(token);
      expect('(', "after the property's name");
      property.display_name = expect(TokenKind::String, "the property's label in quotes").text;
      expect(',', "after the property's label");
      property_type(property);
      expect(')', "after the property's type");
      expect('=', "before the property's default");
      property_default(property);
      if (shader_.property(property.name)) fail(token, "the property '" + property.name + "' is declared twice");
      shader_.properties.push_back(std::move(property));
    }
  }

  PropertyAttribute attribute(const Token& open) {
    bool closed = false;
    const std::string raw = lex_.raw_until('[', ']', closed);
    if (!closed) fail(open, "the attribute '[" + raw + "' has no closing ']' on its line");
    PropertyAttribute attribute;
    attribute.where = where(open);
    const size_t paren = raw.find('(');
    auto trim = [](std::string_view text) {
      while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
      while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.remove_suffix(1);
      return std::string(text);
    };
    attribute.name = trim(std::string_view(raw).substr(0, paren));
    if (attribute.name.empty()) fail(open, "an attribute needs a name: [Name] or [Name(arguments)]");
    if (paren != std::string::npos) {
      const size_t close = raw.rfind(')');
      if (close == std::string::npos || close < paren) fail(open, "the attribute '[" + raw + "]' has no closing ')'");
      const std::string_view inside = std::string_view(raw).substr(paren + 1, close - paren - 1);
      // Header's text is one argument whatever it holds; the others are lists.
      if (same_word(attribute.name, "Header")) {
        attribute.arguments.push_back(trim(inside));
      } else {
        for (size_t start = 0; start <= inside.size();) {
          const size_t comma = inside.find(',', start);
          const std::string argument =
              trim(inside.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
          if (!argument.empty()) attribute.arguments.push_back(argument);
          if (comma == std::string_view::npos) break;
          start = comma + 1;
        }
      }
    }
    static constexpr std::string_view kKnown[] = {
        "HDR",       "Gamma",       "NoScaleOffset", "Normal",         "PerRendererData", "MainTexture",
        "MainColor", "Toggle",      "ToggleOff",     "MaterialToggle", "KeywordEnum",     "Enum",
        "IntRange",  "PowerSlider", "Header",        "Space",          "HideInInspector", "NoKeywordToggle",
        "ToggleUI"};
    bool known = false;
    for (std::string_view name : kKnown) known = known || same_word(name, attribute.name);
    if (!known)
      shader_.notes.push_back({Severity::Warning, attribute.where,
                               "attribute [" + attribute.name +
                                   "] is kept but means nothing to xshade (a custom drawer of the "
                                   "material inspector)"});
    return attribute;
  }

  void property_type(Property& property) {
    const Token token = lex_.next();
    struct Named {
      std::string_view name;
      PropertyType type;
    };
    static constexpr Named kTypes[] = {{"Float", PropertyType::Float},
                                       {"Int", PropertyType::Int},
                                       {"Integer", PropertyType::Integer},
                                       {"Color", PropertyType::Color},
                                       {"Vector", PropertyType::Vector},
                                       {"2D", PropertyType::Texture2D},
                                       {"2DArray", PropertyType::Texture2DArray},
                                       {"3D", PropertyType::Texture3D},
                                       {"Cube", PropertyType::Cube},
                                       {"CubeArray", PropertyType::CubeArray},
                                       {"Any", PropertyType::Any},
                                       {"Range", PropertyType::Range}};
    for (const Named& named : kTypes)
      if (token.is_word(named.name)) {
        property.type = named.type;
        if (named.type == PropertyType::Range) {
          expect('(', "after Range");
          property.range_min = signed_number("Range's minimum");
          expect(',', "between Range's minimum and maximum");
          property.range_max = signed_number("Range's maximum");
          expect(')', "after Range's maximum");
        }
        return;
      }
    fail(token, "unknown property type " + describe(token) +
                    "; a property is Float, Int, Integer, Range(min, max), Color, Vector, 2D, 2DArray, 3D, Cube, "
                    "CubeArray or Any");
  }

  void property_default(Property& property) {
    if (property.is_texture()) {
      property.texture_default =
          expect(TokenKind::String, "a texture's default in quotes (\"white\", \"black\", \"gray\", \"bump\", \"\")")
              .text;
      // { } after it: options of old Unity versions (TexGen ...), read past.
      if (accept('{')) skip_block();
      return;
    }
    if (property.type == PropertyType::Color || property.type == PropertyType::Vector) {
      expect('(',
             "before the components of a " + std::string(property.type == PropertyType::Color ? "Color" : "Vector"));
      size_t count = 0;
      do {
        if (count == 4) fail(lex_.peek(), "a default has at most four components");
        property.value[count++] = signed_number("a component of the default");
      } while (accept(','));
      expect(')', "after the default's components");
      if (count < 3) fail(lex_.peek(), "a Color or Vector default has three or four components");
      if (count == 3) property.value[3] = property.type == PropertyType::Color ? 1.0f : 0.0f;
      return;
    }
    property.value[0] = signed_number("the property's default number");
  }

  // A { ... } whose contents xshade does not read, its brackets balanced.
  void skip_block() {
    for (int depth = 1; depth > 0;) {
      const Token token = lex_.next();
      if (token.kind == TokenKind::End) fail(token, "a block '{' is not closed before the end of the file");
      depth += token.is('{') ? 1 : token.is('}') ? -1 : 0;
    }
  }

  // ---- Blocks ----

  Tags tags() {
    Tags read;
    expect('{', "after Tags");
    while (!accept('}')) {
      const std::string name = expect(TokenKind::String, "a tag's name in quotes (\"Queue\" = \"Geometry\")").text;
      expect('=', "after the tag's name");
      read.emplace_back(name, expect(TokenKind::String, "the tag's value in quotes").text);
    }
    return read;
  }

  static void add_tags(Tags& into, const Tags& outer) {
    for (const auto& [name, value] : outer)
      if (tag(into, name).empty()) into.emplace_back(name, value);
  }

  ProgramBlock include_block(const Token& token) {
    ProgramBlock block = program_block(token);
    if (!block.include)
      fail(token, "a CGPROGRAM or HLSLPROGRAM belongs inside a Pass; only CGINCLUDE and HLSLINCLUDE blocks stand here");
    return block;
  }

  // An include block joins `includes`; a program becomes `program`, of which a block holds one.
  void take_program(const Token& token, std::vector<ProgramBlock>& includes, std::optional<ProgramBlock>& program,
                    std::string_view one) {
    ProgramBlock block = program_block(token);
    if (block.include) {
      includes.push_back(std::move(block));
    } else if (program) {
      fail(token, std::string(one) + "; this one already has the block at line " + std::to_string(program->start.line));
    } else {
      program = std::move(block);
    }
  }

  ProgramBlock program_block(const Token& token) {
    ProgramBlock block;
    block.language = token.language;
    block.include = token.include;
    block.text = token.text;
    block.start = {file_, token.text_line, token.text_column};
    return block;
  }

  void category(std::vector<ProgramBlock> includes) {
    expect('{', "after Category");
    RenderState state;
    Tags category_tags;
    int lod = 0;
    while (!accept('}')) {
      const Token token = lex_.next();
      if (token.is_word("SubShader")) {
        shader_.subshaders.push_back(subshader(token, state, category_tags, includes));
        if (shader_.subshaders.back().lod == 0) shader_.subshaders.back().lod = lod;
      } else if (token.is_word("Tags")) {
        category_tags = tags();
      } else if (token.is_word("LOD")) {
        lod = whole_number(lex_.next(), "the LOD's number", 0, kLargestLod);
      } else if (token.kind == TokenKind::Program) {
        includes.push_back(include_block(token));
      } else if (!state_command(token, state) && !fixed_function(token)) {
        unexpected(token, "in a Category block: SubShader, Tags, LOD, render state or CGINCLUDE");
      }
    }
  }

  SubShader subshader(const Token& start, const RenderState& outer_state, const Tags& outer_tags,
                      const std::vector<ProgramBlock>& includes) {
    SubShader sub;
    sub.where = where(start);
    sub.includes = includes;
    expect('{', "after SubShader");
    RenderState own;
    while (!accept('}')) {
      const Token token = lex_.next();
      if (token.is_word("Tags")) {
        sub.tags = tags();
      } else if (token.is_word("LOD")) {
        sub.lod = whole_number(lex_.next(), "the LOD's number", 0, kLargestLod);
      } else if (token.is_word("Pass")) {
        sub.passes.push_back(pass(token));
      } else if (token.is_word("UsePass")) {
        Pass used;
        used.kind = PassKind::Use;
        used.where = where(token);
        used.used = expect(TokenKind::String, "\"Shader/PASSNAME\" after UsePass").text;
        if (used.used.find('/') == std::string::npos)
          fail(token, "UsePass names a pass as \"Shader name/PASS NAME\", not \"" + used.used + "\"");
        sub.passes.push_back(std::move(used));
      } else if (token.is_word("GrabPass")) {
        sub.passes.push_back(grab_pass(token));
      } else if (token.kind == TokenKind::Program) {
        // Outside a Pass, a program is a surface shader's: its passes are generated from it.
        take_program(token, sub.includes, sub.surface, "a SubShader holds one surface program");
      } else if (!state_command(token, own) && !fixed_function(token)) {
        unexpected(token, "in a SubShader block: Tags, LOD, Pass, UsePass, GrabPass, render state or CGINCLUDE");
      }
    }
    sub.state = own.over(outer_state);
    add_tags(sub.tags, outer_tags);
    if (sub.passes.empty() && !sub.surface) fail(start, "the SubShader has no Pass and no surface program");
    return sub;
  }

  Pass grab_pass(const Token& start) {
    Pass grab;
    grab.kind = PassKind::Grab;
    grab.where = where(start);
    expect('{', "after GrabPass");
    while (!accept('}')) {
      const Token token = lex_.next();
      if (token.kind == TokenKind::String)
        grab.grab_texture = token.text;
      else if (token.is_word("Name"))
        grab.name = expect(TokenKind::String, "the pass's name in quotes").text;
      else if (token.is_word("Tags"))
        grab.tags = tags();
      else
        unexpected(token, "in a GrabPass block: the texture's name in quotes, Name or Tags");
    }
    return grab;
  }

  Pass pass(const Token& start) {
    Pass pass;
    pass.where = where(start);
    expect('{', "after Pass");
    while (!accept('}')) {
      const Token token = lex_.next();
      if (token.is_word("Name")) {
        pass.name = expect(TokenKind::String, "the pass's name in quotes").text;
      } else if (token.is_word("Tags")) {
        pass.tags = tags();
      } else if (token.kind == TokenKind::Program) {
        take_program(token, pass.includes, pass.program, "a Pass holds one program");
      } else if (fixed_function(token)) {
        pass.fixed_function.push_back(token.text);
      } else if (!state_command(token, pass.state)) {
        unexpected(token, "in a Pass block: Name, Tags, render state, or a CGPROGRAM or HLSLPROGRAM");
      }
    }
    pass.kind = pass.program ? PassKind::Program : PassKind::FixedFunction;
    if (!pass.program && pass.fixed_function.empty())
      note(start, "the Pass has no program and no fixed-function command: it draws nothing");
    return pass;
  }

  void fallback() {
    const Token token = lex_.next();
    if (token.is_word("Off")) {
      shader_.fallback = "";
    } else if (token.kind == TokenKind::String) {
      shader_.fallback = token.text;
    } else {
      fail(token, "Fallback takes a shader's name in quotes or Off, not " + describe(token));
    }
  }

  // ---- Render state ----

  // A word of `words` (ignoring case; kept in Unity's spelling), or a property in brackets.
  StateValue state_value(std::string_view command, Words words, bool numbers = false) {
    const Token token = lex_.next();
    StateValue value;
    value.where = where(token);
    if (token.is('[')) {
      value.text = expect(TokenKind::Word, "a property's name in brackets").text;
      value.is_property = true;
      expect(']', "after the property's name");
      return value;
    }
    if (numbers && token.kind == TokenKind::Number) {
      number(token, "a number");
      value.text = token.text;
      return value;
    }
    if (token.kind == TokenKind::Word)
      for (std::string_view word : words)
        if (token.is_word(word)) {
          value.text = std::string(word);
          return value;
        }
    const std::string choices = words.empty() ? "a number" : (numbers ? "a number, " : "") + one_of(words) + ",";
    fail(token,
         std::string(command) + " takes " + choices + " or a property in brackets ([_Name]), not " + describe(token));
  }

  StateValue number_value(std::string_view command) {
    if (lex_.peek().is('-') || lex_.peek().is('+')) {
      const Token sign = lex_.next();
      StateValue value = number_value(command);
      if (sign.is('-')) value.text = "-" + value.text;
      value.where = where(sign);
      return value;
    }
    return state_value(command, Words{}, true);
  }

  // Whether `token` begins a render state command, which is then read into `state`.
  bool state_command(const Token& token, RenderState& state) {
    if (token.is_word("Cull")) {
      state.cull = state_value("Cull", kCull);
    } else if (token.is_word("ZWrite")) {
      state.zwrite = state_value("ZWrite", kSwitch);
    } else if (token.is_word("ZTest")) {
      state.ztest = state_value("ZTest", kCompare);
    } else if (token.is_word("AlphaToMask")) {
      state.alpha_to_mask = state_value("AlphaToMask", kSwitch);
    } else if (token.is_word("ZClip")) {
      state.zclip = state_value("ZClip", kSwitch);
    } else if (token.is_word("Conservative")) {
      state.conservative = state_value("Conservative", kSwitch);
    } else if (token.is_word("Offset")) {
      StateValue factor = number_value("Offset's factor");
      expect(',', "between Offset's factor and units");
      state.offset = {factor, number_value("Offset's units")};
    } else if (token.is_word("ColorMask")) {
      state.color_mask = color_mask();
    } else if (token.is_word("Blend")) {
      state.blend.push_back(blend());
    } else if (token.is_word("BlendOp")) {
      StateValue colour = state_value("BlendOp", kBlendOps);
      std::optional<StateValue> alpha;
      if (accept(',')) alpha = state_value("BlendOp", kBlendOps);
      state.blend_op = {colour, alpha};
    } else if (token.is_word("Stencil")) {
      state.stencil = stencil();
    } else {
      return false;
    }
    return true;
  }

  StateValue color_mask() {
    const Token token = lex_.next();
    StateValue value;
    value.where = where(token);
    if (token.is('[')) {
      value.text = expect(TokenKind::Word, "a property's name in brackets").text;
      value.is_property = true;
      expect(']', "after the property's name");
    } else if (token.kind == TokenKind::Number && token.text == "0") {
      value.text = "0";
    } else {
      std::string channels;
      for (char c : token.kind == TokenKind::Word ? token.text : std::string("?")) {
        const char upper = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        if (std::string_view("RGBA").find(upper) == std::string_view::npos || channels.find(upper) != std::string::npos)
          fail(token,
               "ColorMask takes 0 or channels of RGBA (each once), or a property in brackets, not " + describe(token));
        channels += upper;
      }
      value.text = channels;
    }
    // ColorMask RGB 1: one render target's mask.
    if (lex_.peek().kind == TokenKind::Number && lex_.peek().line == token.line) value.text += " " + lex_.next().text;
    return value;
  }

  BlendState blend() {
    BlendState blend;
    // Blend N ...: render target N.
    if (lex_.peek().kind == TokenKind::Number)
      blend.target = whole_number(lex_.next(), "a render target's number", 0, 7);
    if (lex_.peek().is_word("Off")) {
      lex_.next();
      blend.off = true;
      return blend;
    }
    blend.source = state_value("Blend", kBlendFactors);
    blend.destination = state_value("Blend", kBlendFactors);
    if (accept(',')) {
      blend.source_alpha = state_value("Blend", kBlendFactors);
      blend.destination_alpha = state_value("Blend", kBlendFactors);
    }
    return blend;
  }

  StencilState stencil() {
    StencilState stencil;
    expect('{', "after Stencil");
    while (!accept('}')) {
      const Token token = lex_.next();
      static constexpr std::string_view kMasks[] = {"Ref", "ReadMask", "WriteMask"};
      static constexpr std::string_view kCompares[] = {"Comp", "CompFront", "CompBack"};
      static constexpr std::string_view kOperations[] = {"Pass",       "Fail",     "ZFail",    "PassFront", "FailFront",
                                                         "ZFailFront", "PassBack", "FailBack", "ZFailBack"};
      auto add = [&](std::string_view name, StateValue value) {
        stencil.fields.emplace_back(std::string(name), std::move(value));
      };
      bool known = false;
      for (std::string_view name : kMasks)
        if (!known && token.is_word(name)) {
          add(name, number_value(name));
          known = true;
        }
      for (std::string_view name : kCompares)
        if (!known && token.is_word(name)) {
          add(name, state_value(name, kCompare));
          known = true;
        }
      for (std::string_view name : kOperations)
        if (!known && token.is_word(name)) {
          add(name, state_value(name, kStencilOps));
          known = true;
        }
      if (!known)
        unexpected(
            token,
            "in a Stencil block: Ref, ReadMask, WriteMask, Comp, Pass, Fail, ZFail (and their Front and Back forms)");
    }
    return stencil;
  }

  // Whether `token` begins a fixed-function command, which is then read past: what follows it on
  // its line up to the next command, and a { } block after it.
  bool fixed_function(const Token& token) {
    bool known = false;
    for (std::string_view word : kFixedFunction) known = known || token.is_word(word);
    if (!known) return false;
    for (Token next = lex_.peek();
         next.line == token.line &&
         (next.kind == TokenKind::Word
              ? !command_word(next)
              : next.kind != TokenKind::End && next.kind != TokenKind::Program && !next.is('{') && !next.is('}'));
         next = lex_.peek())
      lex_.next();
    if (accept('{')) skip_block();
    note(token, "'" + token.text + "' is a fixed-function command; xshade draws programs only, and reads past it");
    return true;
  }

  // A word that begins a command of a block, which ends the arguments of the one before it.
  static bool command_word(const Token& token) {
    static constexpr std::string_view kCommands[] = {
        "Cull",         "ZWrite",  "ZTest", "Blend", "BlendOp", "ColorMask", "Offset",   "AlphaToMask", "ZClip",
        "Conservative", "Stencil", "Name",  "Tags",  "Pass",    "UsePass",   "GrabPass", "LOD"};
    for (std::string_view word : kCommands)
      if (token.is_word(word)) return true;
    for (std::string_view word : kFixedFunction)
      if (token.is_word(word)) return true;
    return false;
  }

  Lexer lex_;
  std::string file_;
  Shader shader_;
};

}  // namespace

Result<Shader> read_shader(std::string_view text, const std::string& file) {
  try {
    return Reader(text, file).read();
  } catch (const ReadError& error) {
    return fail(ErrorKind::UserInput, error.diagnostic.message, error.diagnostic.where);
  }
}

Result<Shader> read_shader_file(const std::filesystem::path& path) {
  std::error_code error;
  if (const uintmax_t size = std::filesystem::file_size(path, error); !error && size > kMaxSourceFileBytes)
    return fail(ErrorKind::UserInput, path.string() + " is " + std::to_string(size) +
                                          " bytes; a shader source may have at most " +
                                          std::to_string(kMaxSourceFileBytes >> 20) + " MiB");
  ReadFailure why{};
  const std::optional<std::string> text = read_file(path, &why);
  if (!text)
    return fail(ErrorKind::UserInput,
                path.string() + (why == ReadFailure::IsDirectory ? " is a folder, not a .shader file"
                                 : why == ReadFailure::NotAFile  ? " is " + not_a_file(path) + ", not a .shader file"
                                                                 : ": cannot be read"));
  return read_shader(*text, path.string());
}

}  // namespace xshade::shaderlab
