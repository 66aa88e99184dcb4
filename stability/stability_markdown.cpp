// docs/stability.md: the suite's outcomes as a summary (case x form x lane x precision) and, per
// case, every measured value.
#include <fmt/core.h>

#include <map>

#include "harness/report/report_text.h"
#include "stability/probe.h"
#include "stability/suite.h"

namespace xshade::stability {
namespace {

struct Column {
  harness::Lane lane;
  Precision precision;
  std::string title() const {
    return fmt::format("{} {}", harness::lane_name(lane), precision == Precision::Float ? "fp32" : "fp16");
  }
  friend bool operator==(const Column&, const Column&) = default;
};

std::vector<Column> columns_of(const SuiteRun& run) {
  std::vector<Column> columns;
  for (Precision precision : {Precision::Float, Precision::Half})
    for (const auto& [lane, driver] : run.drivers) {
      const Column column{lane, precision};
      const bool any = std::any_of(run.outcomes.begin(), run.outcomes.end(), [&column](const Outcome& o) {
        return o.lane == column.lane && o.precision == column.precision;
      });
      if (any) columns.push_back(column);
    }
  return columns;
}

const Outcome* find(const SuiteRun& run, const std::string& case_id, const std::string& form, const Column& column) {
  for (const Outcome& o : run.outcomes)
    if (o.case_id == case_id && o.form == form && o.lane == column.lane && o.precision == column.precision) return &o;
  return nullptr;
}

std::string verdict(const Outcome& o) {
  if (o.error) return "**could not run**";
  const size_t failing = o.failing_inputs().size();
  const size_t inputs = std::set<std::string>([&] {
                          std::set<std::string> all;
                          for (const Measurement& m : o.measurements) all.insert(m.input);
                          return all;
                        }())
                            .size();
  if (!o.as_predicted()) return fmt::format("**UNEXPECTED** ({} of {} inputs break)", failing, inputs);
  if (failing == 0) return "holds";
  return fmt::format("breaks as predicted ({} of {})", failing, inputs);
}

// Table cells may not hold '|' or line breaks.
std::string cell(std::string text) {
  for (char& ch : text)
    if (ch == '|')
      ch = '/';
    else if (ch == '\n')
      ch = ' ';
  return text;
}

}  // namespace

std::string stability_markdown(const std::vector<Case>& cases, const SuiteRun& run, const std::string& command_line) {
  const std::vector<Column> columns = columns_of(run);
  std::string md = harness::generated_markdown_head("Numerical stability", command_line, run.drivers);
  md +=
      "\nEach case of SHADERS.md section 5 runs the library's own shader code on the lanes: a probe shader "
      "(stability/probes) that calls the functions of include/brdf.hlsl and include/toon.hlsl with the case's "
      "inputs, or the library's scene and post effect themselves. C++ computes only the expected values. "
      "*fp16* is half emulation: every half-typed result rounded to fp16, and the library's `real` terms in "
      "half (docs/hlsl_like.md).\n\n"
      "A form is the keyword set a material or effect is compiled with. *holds*: every input kept its bound. "
      "*breaks as predicted*: the form broke at exactly the inputs SHADERS.md (or the note under the case) "
      "predicts. *UNEXPECTED*: it broke elsewhere, or held where a break was predicted; `xshade stability` "
      "then exits 1 and names the case, the input and the value.\n\n";
  if (!run.skipped.empty()) {
    md += "Not run:\n";
    for (const std::string& s : run.skipped) md += "- " + s + "\n";
    md += "\n";
  }
  md += fmt::format("{} outcomes, {} not as predicted.\n\n## Summary\n\n| case | SHADERS.md | form |",
                    run.outcomes.size(), run.unexpected());
  for (const Column& c : columns) md += " " + c.title() + " |";
  md += "\n|---|---|---|";
  for (size_t i = 0; i < columns.size(); ++i) md += "---|";
  md += "\n";
  for (const Case& c : cases)
    for (const Form& form : c.forms) {
      std::string row = fmt::format("| [{}](#{}) | {} | {} |", c.id, c.id, c.section, form.name);
      bool any = false;
      for (const Column& column : columns) {
        const Outcome* o = find(run, c.id, form.name, column);
        row += " " + (o ? verdict(*o) : std::string("-")) + " |";
        any = any || o;
      }
      if (any) md += row + "\n";
    }

  for (const Case& c : cases) {
    const bool ran =
        std::any_of(run.outcomes.begin(), run.outcomes.end(), [&](const Outcome& o) { return o.case_id == c.id; });
    if (!ran) continue;
    md += fmt::format("\n## {}\n\nSHADERS.md {}: {}\n\n", c.id, c.section, c.title);
    // The notes of the predictions, once per form and precision.
    for (const Form& form : c.forms)
      for (Precision precision : {Precision::Float, Precision::Half}) {
        const Column any_lane{run.drivers.front().first, precision};
        const Outcome* o = find(run, c.id, form.name, any_lane);
        if (o && !o->prediction.note.empty())
          md += fmt::format("- *{}, {}*: {}\n", form.name, precision == Precision::Float ? "fp32" : "fp16",
                            o->prediction.note);
      }
    // Where each non-finite value was born, once for the lanes that agree (the tracing variant).
    std::map<std::string, std::string> born;
    for (const Outcome& o : run.outcomes)
      if (o.case_id == c.id)
        for (const Measurement& m : o.measurements)
          if (!m.born_at.empty())
            born.emplace(fmt::format("*{}, {}, {} ({})*", o.form, o.precision == Precision::Float ? "fp32" : "fp16",
                                     cell(m.input), cell(m.quantity)),
                         m.born_at);
    for (const auto& [what, where] : born) md += fmt::format("- {}: born at {}\n", what, cell(where));
    for (const Outcome& o : run.outcomes)
      if (o.case_id == c.id && o.error)
        md += fmt::format("- *{}, {}, {}*: could not run: {}\n", o.form, harness::lane_name(o.lane),
                          precision_name(o.precision), cell(*o.error));
    md += "\n| form | input | quantity | bound |";
    for (const Column& column : columns) md += " " + column.title() + " |";
    md += "\n|---|---|---|---|";
    for (size_t i = 0; i < columns.size(); ++i) md += "---|";
    md += "\n";
    for (const Form& form : c.forms) {
      // Rows in the order the first outcome measured them; a bound that differs by precision
      // gets a row of its own.
      std::vector<std::tuple<std::string, std::string, std::string>> rows;
      std::map<std::tuple<std::string, std::string, std::string>, std::map<size_t, const Measurement*>> values;
      for (size_t k = 0; k < columns.size(); ++k) {
        const Outcome* o = find(run, c.id, form.name, columns[k]);
        if (!o) continue;
        for (const Measurement& m : o->measurements) {
          auto key = std::make_tuple(m.input, m.quantity, m.bound);
          if (!values.contains(key)) rows.push_back(key);
          values[key][k] = &m;
        }
      }
      for (const auto& key : rows) {
        const auto& [input, quantity, bound] = key;
        md += fmt::format("| {} | {} | {} | {} |", form.name, cell(input), cell(quantity), cell(bound));
        for (size_t k = 0; k < columns.size(); ++k) {
          auto it = values[key].find(k);
          md += it == values[key].end() ? " - |"
                                        : fmt::format(" {}{} |", number(it->second->value), it->second->ok ? "" : " ✗");
        }
        md += "\n";
      }
    }
  }
  return md;
}

}  // namespace xshade::stability
