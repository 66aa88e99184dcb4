// The run's results as JSON, for tools: every field of the model, snake_case keys that keep their
// names from one release to the next ("format" says which layout a file has).
#pragma once

#include <string>

#include "harness/gate/run_results.h"

namespace xshade::harness {

// Verdicts are their verdict_name()s. A number JSON cannot hold (an infinite PSNR for identical
// images, a NaN measurement) is null. Text that is not UTF-8 is repaired with U+FFFD.
std::string results_json(const RunResults& results);

}  // namespace xshade::harness
