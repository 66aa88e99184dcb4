// The run's results as JSON, for tools: every field of the model, snake_case keys that keep their
// names from one release to the next ("format" says which layout a file has).
#pragma once

#include <string>
#include <string_view>

#include "base/result.h"
#include "harness/gate/run_results.h"

namespace xshade::harness {

// Verdicts are their verdict_name()s. A number JSON cannot hold (an infinite PSNR for identical
// images, a NaN measurement) is null. Text that is not UTF-8 is repaired with U+FFFD.
std::string results_json(const RunResults& results);

// A results.json read back (to merge the reports of several runs): the model results_json
// wrote, but for the counts, which are recomputed from it. A file that is not JSON, of another
// "format", or missing a field is a UserInput error naming `file` and the field: results.json
// comes from a folder anyone can write (a CI artifact), not from this process.
Result<RunResults> results_from_json(std::string_view text, const std::string& file);

}  // namespace xshade::harness
