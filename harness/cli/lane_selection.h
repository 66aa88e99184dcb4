// Resolving the --lane options of a verb into lanes.
#pragma once

#include <vector>

#include "harness/lanes.h"
#include "harness/cli/commands.h"

namespace xshade::cli {

// The lanes named in the selection, all lanes when it names none; an unknown name is an error.
Result<std::vector<harness::Lane>> resolve_lanes(const LaneSelection& selection);

}  // namespace xshade::cli
