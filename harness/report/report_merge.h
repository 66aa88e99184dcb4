// Several runs' reports as one: the shards of a CI matrix, or the per-test report folders of a
// CTest run, merged into one index, one junit.xml and one results.json, as VK-GL-CTS's runners
// merge the results of many shards.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "base/result.h"
#include "harness/gate/run_results.h"

namespace xshade::harness {

// A run's report as it was found: the folder its results.json is in, and that file read back.
struct FoundReport {
  std::filesystem::path folder;
  RunResults results;
};

// A results.json holds about 2 KB a scene; 256 MiB is a run of a hundred thousand scenes, and
// keeps a link to /dev/zero or a log from being read at all.
inline constexpr size_t kMaxResultsBytes = size_t(256) << 20;

// Each of `folders` is a report (it holds a results.json) or a folder of reports (those of its
// immediate subfolders that hold one, in name order), as a CI artifact download or a CTest
// report folder lays them out. A folder that is neither, or a results.json that does not read,
// is a UserInput error naming it.
Result<std::vector<FoundReport>> find_reports(const std::vector<std::filesystem::path>& folders);

// A file a merged result names, and where it comes from.
struct MergedFile {
  std::filesystem::path from;  // in a found report's folder
  std::string to;              // relative to the merged report's folder
};

struct MergedReport {
  RunResults results;
  std::vector<MergedFile> files;
  std::vector<std::string> warnings;  // files a report names that are not there, or lead out of it
};

// One result of every report: scenes by name (in name order, as a run lists them); within a
// scene, each lane and each pair of lanes once. A lane or pair that more than one report holds
// (a CTest run checks each lane alone and then all lanes together) is taken from the report
// where its verdict is worst, else from the first; a scene's verdict is the worst any report
// gave it. The counts of the merge are then those of one run of every scene: shards add up.
// Each file a kept result names is copied from its report; a path that leads out of its report
// folder is dropped with a warning, and two different files that would land on one path keep
// apart under "run-N/".
MergedReport merge_reports(const std::vector<FoundReport>& reports);

// For each scene of `results` whose lanes came from separate runs (no pair of lanes compared,
// as when CTest checks each lane in a test of its own): its lanes held against each other from
// their float images in `folder`, with the scene's tolerances, as one run of all of them would
// (the first lane against each other), heat maps written there; the scene's verdict counts the
// pairs. Returns a warning for each float image that does not read (its lane is left out).
std::vector<std::string> compare_lanes_across_reports(RunResults& results, const std::filesystem::path& folder);

}  // namespace xshade::harness
