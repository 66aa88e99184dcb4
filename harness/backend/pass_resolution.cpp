#include "harness/backend/pass_resolution.h"

namespace xshade::harness {

std::string source_label(const TextureSource& source) {
  const std::string id = std::to_string(source.id);
  switch (source.kind) {
    case TextureSource::Kind::Texture: return "texture " + id;
    case TextureSource::Kind::TargetColor: return "the colour of target " + id;
    case TextureSource::Kind::TargetDepth: return "the depth of target " + id;
  }
  return "?";
}

}  // namespace xshade::harness
