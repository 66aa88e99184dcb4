#include "stability/suite.h"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>

#include "stability/cases.h"
#include "stability/probe.h"

namespace xshade::stability {

std::string_view precision_name(Precision precision) {
  return precision == Precision::Float ? "fp32" : "fp16 emulation";
}

std::vector<Case> all_cases() {
  std::vector<Case> cases;
  for (auto part : {brdf_cases, toon_cases, furnace_cases, dof_cases})
    for (Case& c : part()) cases.push_back(std::move(c));
  std::stable_sort(cases.begin(), cases.end(), [](const Case& a, const Case& b) {
    auto number = [](const std::string& section) { return std::stoi(section.substr(section.find('.') + 1)); };
    return number(a.section) < number(b.section);
  });
  return cases;
}

std::set<std::string> Outcome::failing_inputs() const {
  std::set<std::string> inputs;
  for (const Measurement& m : measurements)
    if (!m.ok) inputs.insert(m.input);
  return inputs;
}

bool Outcome::as_predicted() const { return !error && failing_inputs() == prediction.failing_inputs; }

std::string Outcome::explain() const {
  const std::string where = fmt::format("stability case {} (SHADERS.md {}), form '{}', lane {}, {}", case_id, section,
                                        form, harness::lane_name(lane), precision_name(precision));
  if (error) return where + ": could not run: " + *error + "\n";
  std::string text;
  for (const Measurement& m : measurements)
    if (!m.ok && !prediction.failing_inputs.contains(m.input))
      text += fmt::format("{}: {} at {} was {}, expected {}\n", where, m.quantity, m.input, number(m.value), m.bound);
  const std::set<std::string> failing = failing_inputs();
  for (const std::string& input : prediction.failing_inputs)
    if (!failing.contains(input)) {
      text += fmt::format("{}: predicted to break at {} but held:", where, input);
      for (const Measurement& m : measurements)
        if (m.input == input) text += fmt::format(" {} = {} ({})", m.quantity, number(m.value), m.bound);
      text += "\n";
    }
  return text;
}

size_t SuiteRun::unexpected() const {
  return size_t(std::count_if(outcomes.begin(), outcomes.end(), [](const Outcome& o) { return !o.as_predicted(); }));
}

Result<SuiteRun> run_suite(const std::vector<Case>& cases, const SuiteOptions& options) {
  std::vector<const Case*> chosen;
  for (const std::string& id : options.case_ids) {
    auto found = std::find_if(cases.begin(), cases.end(), [&](const Case& c) { return c.id == id; });
    if (found == cases.end()) {
      std::string known;
      for (const Case& c : cases) known += (known.empty() ? "" : ", ") + c.id;
      return fail(ErrorKind::Usage, "no stability case '" + id + "'; the cases are: " + known);
    }
    chosen.push_back(&*found);
  }
  if (options.case_ids.empty())
    for (const Case& c : cases) chosen.push_back(&c);
  const std::vector<harness::Lane> lanes = options.lanes.empty() ? harness::all_lanes() : options.lanes;
  const std::vector<Precision> precisions =
      options.precisions.empty() ? std::vector<Precision>{Precision::Float, Precision::Half} : options.precisions;
  auto progress = [&](const std::string& line) {
    if (options.progress) options.progress(line);
  };

  SuiteRun run;
  harness::VariantCompiler compiler(options.shaders_dir, nullptr);
  for (harness::Lane lane : lanes) {
    auto backend = harness::create_backend(lane, options.backend);
    if (!backend)
      return fail(backend.error().kind, std::string(harness::lane_name(lane)) + ": " + backend.error().to_string());
    run.drivers.emplace_back(lane, (*backend)->driver_info());
    ProbePrograms probes;
    harness::ProgramCache programs;
    if (lane == harness::Lane::VkHlsl &&
        std::find(precisions.begin(), precisions.end(), Precision::Half) != precisions.end())
      run.skipped.push_back(
          "vk-hlsl in fp16 emulation: that lane compiles the source with glslang, which cannot round to fp16");

    for (const Case* c : chosen) {
      const auto start = std::chrono::steady_clock::now();
      size_t as_predicted = 0, ran = 0;
      for (const Form& form : c->forms)
        for (Precision precision : precisions) {
          if (std::find(c->precisions.begin(), c->precisions.end(), precision) == c->precisions.end()) continue;
          if (lane == harness::Lane::VkHlsl && precision == Precision::Half) continue;
          Outcome outcome{c->id, c->section, form.name, form.seed, lane, precision, {}, {}, {}};
          if (c->predict) outcome.prediction = c->predict(form, precision);
          std::map<std::string, std::string> born_at;
          const CaseContext context{
              **backend, lane,   precision, form,   options.shaders_dir, options.probes_dir, options.scenes_dir,
              compiler,  probes, programs,  born_at};
          auto measured = c->run(context);
          if (measured)
            outcome.measurements = std::move(*measured);
          else
            outcome.error = measured.error().to_string();
          // By input; "*" for every non-finite value of the run (a whole image's first site).
          for (Measurement& m : outcome.measurements) {
            auto it = born_at.find(m.input);
            if (it == born_at.end()) it = born_at.find("*");
            if (!std::isfinite(m.value) && it != born_at.end()) m.born_at = it->second;
          }
          for (const std::string& message : (*backend)->take_driver_messages())
            outcome.error = outcome.error.value_or("") + "driver message: " + message + "\n";
          ++ran;
          if (outcome.as_predicted()) ++as_predicted;
          run.outcomes.push_back(std::move(outcome));
        }
      const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
      progress(fmt::format("{} on {}: {} of {} as predicted ({:.1f} s)", c->id, harness::lane_name(lane), as_predicted,
                           ran, elapsed.count()));
    }
  }
  return run;
}

}  // namespace xshade::stability
