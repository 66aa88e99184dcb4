// The tracing variant of a fragment stage (EmitOptions::trace_nonfinite): where a NaN or an
// infinity is born.
//
// The stage holds every function twice. The plain copy is what the untraced variant emits and
// alone makes the colour. The traced copy runs after it on the same inputs and feeds nothing but
// the record: a test of a value is one more use of it, and a driver's optimiser rewrites
// differently what has more uses (llvmpipe's NIR reassociates a sum only where its parts are
// used once), so tests inside the plain copy would move its results by an ulp. To keep the two
// copies from sharing an instruction (common subexpressions are merged, and a merged one has
// the uses of both), every value the traced copy starts from -- the entry point's inputs and
// each uniform it reads -- passes through xs_opaque, an identity the optimiser cannot see
// through (an OR with a zero read from gl_FragCoord).
//
// In the traced copy every float-typed site (an initialisation, an assignment, a compound assignment, a return
// value, a call's result; lower/trace_sites.h decides which) goes through xs_trace(value, site, path), which returns
// the value it was given and, when it is the invocation's first non-finite value, keeps the site's number and the call
// path in two globals. Each of the author's functions takes the path as one more parameter, `uint xs_path`: a call
// passes its caller's path shifted by ten bits with its own number in the low bits, so that the innermost three calls
// are known at any site without a stack. main() tests the inputs as they arrive and the colour outputs as they leave,
// then writes the record to location 1 (NonfiniteTrace says how it reads).
//
// The traced values are the untraced variant's: xs_trace only reads its argument, and the calls
// and globals it adds feed nothing but the record.
#include "glsl/stage_emitter.h"

namespace xshade::glsl {

const char* trace_site_kind_name(TraceSite::Kind kind) {
  switch (kind) {
    case TraceSite::Kind::Initialization: return "initialisation";
    case TraceSite::Kind::Assignment: return "assignment";
    case TraceSite::Kind::CompoundAssignment: return "compound assignment";
    case TraceSite::Kind::Return: return "return value";
    case TraceSite::Kind::Call: return "call result";
    case TraceSite::Kind::Input: return "input from the vertex stage";
    case TraceSite::Kind::Output: return "output";
    case TraceSite::Kind::NegativeOutput: return "negative output";
  }
  return "site";
}

std::string describe_site(const TraceSite& site) {
  switch (site.kind) {
    case TraceSite::Kind::Initialization: return "the initial value of " + site.what;
    case TraceSite::Kind::Assignment: return "the value assigned to " + site.what;
    case TraceSite::Kind::CompoundAssignment: return "the compound assignment to " + site.what;
    case TraceSite::Kind::Return: return "the value " + site.what + " returns";
    case TraceSite::Kind::Call: return "the result of " + site.what;
    case TraceSite::Kind::Input: return "input " + site.what + " as it arrived from the vertex stage";
    case TraceSite::Kind::Output: return "output " + site.what;
    case TraceSite::Kind::NegativeOutput:
      return "output " + site.what + " below zero (signs are tested at the output only)";
  }
  return site.what;
}

namespace detail {

using namespace hlsl;

namespace {

constexpr const char* kRecordGlobals =
    "// The first non-finite site of this invocation and the calls that led to it (the tracing variant).\n"
    "uint xs_trace_site = 0u;\n"
    "uint xs_trace_path = 0u;\n"
    "// Zero, from gl_FragCoord at the start of main(): the optimiser cannot know it is.\n"
    "uint xs_opaque_zero = 0u;\n";

// xs_opaque for one GLSL type: its bits ORed with xs_opaque_zero.
std::string opaque_helper(const std::string& glsl_type) {
  const bool matrix = glsl_type.rfind("mat", 0) == 0;
  std::string bits_type = "uint";
  if (glsl_type.rfind("vec", 0) == 0 || glsl_type.rfind("ivec", 0) == 0 || glsl_type.rfind("uvec", 0) == 0)
    bits_type = "uvec" + glsl_type.substr(glsl_type.size() - 1);
  auto one = [&](const std::string& value, const std::string& type, const std::string& bits) {
    const std::string zero = bits == "uint" ? "xs_opaque_zero" : bits + "(xs_opaque_zero)";
    if (type == "float" || type.rfind("vec", 0) == 0)
      return "uintBitsToFloat(floatBitsToUint(" + value + ") | " + zero + ")";
    if (type == "int" || type.rfind("ivec", 0) == 0) return type + "(" + bits + "(" + value + ") | " + zero + ")";
    return value + " | " + zero;
  };
  std::string body;
  if (matrix) {
    const std::string column = glsl_type.size() > 4 && glsl_type[4] == 'x' ? std::string("vec") + glsl_type[5]
                                                                           : std::string("vec") + glsl_type[3];
    body = "  for (int c = 0; c < v.length(); ++c) v[c] = " + one("v[c]", column, "uvec" + column.substr(3)) +
           ";\n  return v;\n";
  } else {
    body = "  return " + one("v", glsl_type, bits_type) + ";\n";
  }
  return glsl_type + " xs_opaque(" + glsl_type + " v) {\n" + body + "}\n";
}

// The test of one GLSL type: scalars and vectors as they are, matrices column by column.
std::string trace_helper(const std::string& glsl_type) {
  std::string bad;
  if (glsl_type.rfind("mat", 0) == 0) {
    bad =
        "bool bad = false;\n  for (int c = 0; c < v.length(); ++c) bad = bad || any(isnan(v[c])) || "
        "any(isinf(v[c]));\n  if (";
    bad += "xs_trace_site == 0u && bad) {\n";
  } else if (glsl_type == "float") {
    bad = "if (xs_trace_site == 0u && (isnan(v) || isinf(v))) {\n";
  } else {
    bad = "if (xs_trace_site == 0u && (any(isnan(v)) || any(isinf(v)))) {\n";
  }
  return glsl_type + " xs_trace(" + glsl_type + " v, uint site, uint path) {\n  " + bad +
         "    xs_trace_site = site;\n    xs_trace_path = path;\n  }\n  return v;\n}\n";
}

}  // namespace

Code StageEmitter::expr(const Expr* e) {
  if (!in_traced_copy_) return expr_untraced(e);
  std::optional<lower::ExpressionSite> site = lower::expression_site(e);
  if (!site) return opaque_if_uniform(e, expr_untraced(e));
  return traced(expr_untraced(e), e->type, site->kind, e->loc, std::move(site->what));
}

TraceSite StageEmitter::site_at(TraceSite::Kind kind, Loc loc, std::string what) const {
  const SourceLocation where = module_.sources.resolve(loc);
  TraceSite site;
  site.kind = kind;
  site.file = where.file;
  site.line = where.line;
  site.column = where.column;
  site.source_line = std::string(module_.sources.line_text(loc.file, loc.line));
  site.function = current_function_;
  site.what = std::move(what);
  return site;
}

uint32_t StageEmitter::add_site(TraceSite site, Loc loc) {
  if (trace_table_.sites.size() >= NonfiniteTrace::kMaxSites) {
    fail(loc, "the tracing variant numbers at most " + std::to_string(NonfiniteTrace::kMaxSites) +
                  " sites in a fragment stage; this one has more");
    return 0;
  }
  trace_table_.sites.push_back(std::move(site));
  return (trace_program_ << 16) | uint32_t(trace_table_.sites.size());
}

Code StageEmitter::opaque_if_uniform(const Expr* e, Code code) {
  if (!in_traced_copy_ || !e || !e->type.is_numeric() || e->type.is_bool() || !lower::reads_uniform(e)) return code;
  // Each read: `_Kernel[i].xy` passes through twice, as `_Kernel[i]` and again as its member.
  const std::string glsl_type = type_name(e->type, e->loc);
  helpers_.add("xs_trace globals", kRecordGlobals);
  helpers_.add("xs_opaque " + glsl_type, opaque_helper(glsl_type));
  std::string text = "xs_opaque(";
  append_operand(text, code, kAssign);
  text += ')';
  return {std::move(text), kPostfix};
}

std::string StageEmitter::function_name(const FunctionDecl* function) const {
  return in_traced_copy_ ? "xs_traced_" + names_.function(function) : names_.function(function);
}

void StageEmitter::traced_functions() {
  in_traced_copy_ = true;
  for (const FunctionDecl* f : functions_) function(*f);
  in_traced_copy_ = false;
}

Code StageEmitter::traced(Code value, const Type& type, TraceSite::Kind kind, Loc loc, std::string what) {
  if (!in_traced_copy_ || !lower::traceable(type)) return value;
  const std::string glsl_type = type_name(type, loc);
  helpers_.add("xs_trace globals", kRecordGlobals);
  helpers_.add("xs_trace " + glsl_type, trace_helper(glsl_type));
  const uint32_t number = add_site(site_at(kind, loc, std::move(what)), loc);
  std::string text = "xs_trace(";
  append_operand(text, value, kAssign);
  text += ", ";
  text += std::to_string(number);
  text += "u, xs_path)";
  return {std::move(text), kPostfix};
}

std::string StageEmitter::trace_call_path(const std::string& callee, Loc loc) {
  const SourceLocation where = module_.sources.resolve(loc);
  trace_table_.calls.push_back({callee, current_function_, where.file, where.line, where.column,
                                std::string(module_.sources.line_text(loc.file, loc.line))});
  // Past the tenth bit a call has no number: its sites name their calls from the next one out.
  const size_t number = trace_table_.calls.size() <= NonfiniteTrace::kMaxCalls ? trace_table_.calls.size() : 0;
  return "(((xs_path << 10u) | " + std::to_string(number) + "u) & 0x3FFFFFFFu)";
}

void StageEmitter::trace_input(Writer& main, const std::string& path, const Type& type, const std::string& semantic,
                               Loc loc) {
  if (!in_traced_copy_ || !lower::traceable(type)) return;
  main.line(traced({path}, type, TraceSite::Kind::Input, loc, semantic).text + ";");
}

void StageEmitter::trace_output(Writer& main, const std::string& path, const Type& type, const std::string& semantic,
                                Loc loc) {
  if (!in_traced_copy_ || !lower::traceable(type)) return;
  main.line(traced({path}, type, TraceSite::Kind::Output, loc, semantic).text + ";");
  // A colour below zero is a hazard of its own (the finite layer counts it), though no test
  // before the output looks at signs: most negative intermediates are meant.
  const uint32_t number = add_site(site_at(TraceSite::Kind::NegativeOutput, loc, semantic), loc);
  const std::string glsl_type = type_name(type, loc);
  const std::string negative =
      type.is_scalar() ? path + " < 0.0" : "any(lessThan(" + path + ", " + glsl_type + "(0.0)))";
  main.line("if (xs_trace_site == 0u && " + negative + ") xs_trace_site = " + std::to_string(number) + "u;");
}

void StageEmitter::traced_main(Writer& main, Writer& interface, const std::vector<TracedItem>& inputs,
                               const std::vector<TracedItem>& outputs) {
  in_traced_copy_ = true;
  helpers_.add("xs_trace globals", kRecordGlobals);
  auto traced_path = [](const std::string& path) {
    for (const char* prefix : {"xs_arg", "xs_result"})
      if (path.rfind(prefix, 0) == 0) return "xs_traced_" + path.substr(3);
    return path;
  };
  main.line(
      "// The traced copy (the tracing variant): the same inputs, opaque, and nothing it computes reaches the colour.");
  main.line("xs_opaque_zero = uint(gl_FragCoord.x < 0.0);");
  main.line("const uint xs_path = 0u;  // the entry point's calls are the outermost");
  const FunctionDecl& entry = *entry_;
  std::string call = function_name(&entry) + "(";
  for (size_t i = 0; i < entry.params.size(); ++i) {
    const hlsl::ParamDecl* param = entry.params[i].get();
    if (!param || param->is_uniform || param->type.is_resource()) continue;  // refused above
    const std::string index = std::to_string(i);
    main.line(declarator(param->type, "xs_traced_arg" + index, param->loc) + " = xs_arg" + index + ";");
    call += (i ? ", xs_traced_arg" : "xs_traced_arg") + index;
  }
  for (const TracedItem& input : inputs) {
    if (!input.type.is_numeric() || input.type.is_bool()) continue;
    const std::string path = traced_path(input.path);
    const std::string glsl_type = type_name(input.type, input.loc);
    helpers_.add("xs_opaque " + glsl_type, opaque_helper(glsl_type));
    main.line(path + " = xs_opaque(" + path + ");");
    if (!input.semantic.empty()) trace_input(main, path, input.type, input.semantic, input.loc);
  }
  call += entry.params.empty() ? "xs_path)" : ", xs_path)";
  if (entry.return_type.is_void())
    main.line(call + ";");
  else
    main.line(declarator(entry.return_type, "xs_traced_result", entry.loc) + " = " + call + ";");
  for (const TracedItem& output : outputs)
    trace_output(main, traced_path(output.path), output.type, output.semantic, output.loc);
  trace_record(main, interface);
  in_traced_copy_ = false;
}

void StageEmitter::trace_record(Writer& main, Writer& interface) {
  helpers_.add("xs_trace globals", kRecordGlobals);
  interface.line("layout(location = 1) out vec4 xs_trace_record;");
  // Whole numbers below 2^24, exact in a float target.
  main.line(
      "xs_trace_record = vec4(float(xs_trace_site), float(xs_trace_path & 1023u), float((xs_trace_path >> 10u) & "
      "1023u), float((xs_trace_path >> 20u) & 1023u));");
}

}  // namespace detail
}  // namespace xshade::glsl
