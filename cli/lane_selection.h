// Resolving the --lane options of a verb into lanes, and its backend options.
#pragma once

#include <vector>

#include "cli/commands.h"
#include "harness/render/lanes.h"

namespace xshade::cli {

// The lanes named in the selection, all lanes when it names none; an unknown name (of a lane, or
// of the --gl-platform) is an error.
Result<std::vector<harness::Lane>> resolve_lanes(const LaneSelection& selection);

// How the selection's backends are made: the Vulkan validation layer and the gl lane's route to
// its context. Call resolve_lanes first: it rejects an unknown --gl-platform.
harness::BackendOptions backend_options(const LaneSelection& selection);

}  // namespace xshade::cli
