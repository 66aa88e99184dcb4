// The passes of a post effect, declared in its source by `#pragma pass` lines:
//
//   #pragma pass NAME ENTRY [scale=full|half] [format=rgba32f] [TEXTURE=SOURCE ...]
//
// SOURCE is `scene.color` (the image the effect receives), `scene.depth` (the scene's depth
// buffer) or the NAME of an earlier pass. Passes run in the order they are declared, each a
// full-screen fragment shader into its own target; the last pass's output is the effect's.
#pragma once

#include <string>
#include <vector>

#include "hlsl_like/diagnostic_engine.h"
#include "hlsl_like/preprocessor.h"

namespace xshade::hlsl {

struct PassInput {
  enum class Kind { SceneColor, SceneDepth, Pass };
  std::string texture;  // the Texture2D the pass samples
  Kind kind = Kind::SceneColor;
  std::string pass;  // for Kind::Pass: the earlier pass's name
};

struct PassDeclaration {
  enum class Scale { Full, Half };
  std::string name;
  std::string entry;  // the fragment function
  Scale scale = Scale::Full;
  std::vector<PassInput> inputs;
  Loc loc;  // of the pass's name
};

// Reads every `#pragma pass` among `pragmas`, reporting malformed ones (an unknown key, a source
// that names no earlier pass, a name used twice) to `diagnostics`.
std::vector<PassDeclaration> read_pass_declarations(const std::vector<Pragma>& pragmas, DiagnosticEngine& diagnostics);

}  // namespace xshade::hlsl
