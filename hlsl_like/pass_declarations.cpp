#include "hlsl_like/pass_declarations.h"

#include <algorithm>

namespace xshade::hlsl {
namespace {

// Reads one `#pragma pass` line's arguments; false (with an error reported) if malformed.
class PassPragmaReader {
 public:
  PassPragmaReader(const Pragma& pragma, const std::vector<PassDeclaration>& earlier, DiagnosticEngine& diagnostics)
      : pragma_(pragma), earlier_(earlier), diagnostics_(diagnostics) {}

  bool read(PassDeclaration& pass) {
    const Token* name = identifier("a pass name");
    if (!name) return false;
    pass.name = std::string(name->text);
    pass.loc = name->loc;
    if (find_earlier(pass.name)) return error(*name, "pass '" + pass.name + "' is already declared");
    const Token* entry = identifier("the pass's fragment function");
    if (!entry) return false;
    pass.entry = std::string(entry->text);

    while (next_ < pragma_.args.size()) {
      const Token* key = identifier("KEY=VALUE");
      if (!key) return false;
      if (!punct("=", *key)) return false;
      const std::string value = dotted_value(*key);
      if (value.empty()) return false;
      if (key->text == "scale") {
        if (value == "full")
          pass.scale = PassDeclaration::Scale::Full;
        else if (value == "half")
          pass.scale = PassDeclaration::Scale::Half;
        else
          return error(*key, "scale is 'full' or 'half', not '" + value + "'");
      } else if (key->text == "format") {
        // Every target the backends make is RGBA32F; the key exists so that a source says so.
        if (value != "rgba32f") return error(*key, "format is 'rgba32f' (the only target format), not '" + value + "'");
      } else {
        PassInput input;
        input.texture = std::string(key->text);
        if (value == "scene.color") {
          input.kind = PassInput::Kind::SceneColor;
        } else if (value == "scene.depth") {
          input.kind = PassInput::Kind::SceneDepth;
        } else if (find_earlier(value)) {
          input.kind = PassInput::Kind::Pass;
          input.pass = value;
        } else {
          return error(*key, "'" + value + "' is not scene.color, scene.depth or an earlier pass");
        }
        const bool repeated = std::any_of(pass.inputs.begin(), pass.inputs.end(),
                                          [&](const PassInput& other) { return other.texture == input.texture; });
        if (repeated) return error(*key, "texture '" + input.texture + "' is given twice");
        pass.inputs.push_back(std::move(input));
      }
    }
    return true;
  }

 private:
  bool find_earlier(const std::string& name) const {
    return std::any_of(earlier_.begin(), earlier_.end(), [&](const PassDeclaration& p) { return p.name == name; });
  }

  bool error(const Token& at, std::string message) {
    diagnostics_.error(at.loc, "#pragma pass: " + std::move(message));
    return false;
  }

  const Token* identifier(const char* what) {
    if (next_ >= pragma_.args.size()) {
      diagnostics_.error(pragma_.loc, std::string("#pragma pass: expected ") + what + " at the end of the line");
      return nullptr;
    }
    const Token& token = pragma_.args[next_];
    if (token.kind != TokenKind::Identifier) {
      error(token, std::string("expected ") + what + ", not '" + std::string(token.text) + "'");
      return nullptr;
    }
    ++next_;
    return &token;
  }

  bool punct(std::string_view p, const Token& after) {
    if (next_ >= pragma_.args.size() || !pragma_.args[next_].is_punct(p))
      return error(next_ < pragma_.args.size() ? pragma_.args[next_] : after,
                   "expected '" + std::string(p) + "' after '" + std::string(after.text) + "'");
    ++next_;
    return true;
  }

  // IDENT or IDENT.IDENT, written without spaces.
  std::string dotted_value(const Token& key) {
    const Token* first = identifier("a value");
    if (!first) return {};
    std::string value(first->text);
    if (next_ + 1 < pragma_.args.size() && pragma_.args[next_].is_punct(".") && !pragma_.args[next_].space_before) {
      const Token& second = pragma_.args[next_ + 1];
      if (second.kind != TokenKind::Identifier || second.space_before) {
        error(key, "expected a name after '" + value + ".'");
        return {};
      }
      value += "." + std::string(second.text);
      next_ += 2;
    }
    return value;
  }

  const Pragma& pragma_;
  const std::vector<PassDeclaration>& earlier_;
  DiagnosticEngine& diagnostics_;
  size_t next_ = 0;
};

}  // namespace

std::vector<PassDeclaration> read_pass_declarations(const std::vector<Pragma>& pragmas, DiagnosticEngine& diagnostics) {
  std::vector<PassDeclaration> passes;
  for (const Pragma& pragma : pragmas) {
    if (pragma.name != "pass") continue;
    PassDeclaration pass;
    if (PassPragmaReader(pragma, passes, diagnostics).read(pass)) passes.push_back(std::move(pass));
  }
  return passes;
}

}  // namespace xshade::hlsl
