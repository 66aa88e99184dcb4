// The tracing variant of a fragment stage (EmitOptions::trace_nonfinite): where a NaN or an
// infinity is born.
//
// Every float-typed site (an initialisation, an assignment, a compound assignment, a return
// value, a call's result) goes through xs_trace(value, site, path), which returns the value it
// was given and, when it is the invocation's first non-finite value, keeps the site's number and
// the call path in two globals. Each of the author's functions takes the path as one more
// parameter, `uint xs_path`: a call passes its caller's path shifted by ten bits with its own
// number in the low bits, so that the innermost three calls are known at any site without a
// stack. main() tests the inputs as they arrive and the colour outputs as they leave, then writes
// the record to location 1 (NonfiniteTrace says how it reads).
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

// Float and half scalars, vectors and matrices: what can hold a NaN or an infinity.
bool traceable(const Type& type) { return type.is_floating(); }

// The assigned place as the author wrote it, for the report: `color.rgb`, `weights[...]`.
std::string place_name(const Expr* e, int depth = 0) {
  if (!e || depth > 16) return "a value";
  switch (e->kind) {
    case ExprKind::Name: return static_cast<const NameExpr*>(e)->name;
    case ExprKind::Member: {
      const auto* member = static_cast<const MemberExpr*>(e);
      return place_name(member->object.get(), depth + 1) + "." + member->member;
    }
    case ExprKind::Index: return place_name(static_cast<const IndexExpr*>(e)->object.get(), depth + 1) + "[...]";
    case ExprKind::Conversion: return place_name(static_cast<const ConversionExpr*>(e)->operand.get(), depth + 1);
    default: return "a value";
  }
}

constexpr const char* kRecordGlobals =
    "// The first non-finite site of this invocation and the calls that led to it (the tracing variant).\n"
    "uint xs_trace_site = 0u;\n"
    "uint xs_trace_path = 0u;\n";

// The test of one GLSL type: scalars and vectors as they are, matrices column by column.
std::string trace_helper(const std::string& glsl_type) {
  std::string bad;
  if (glsl_type.rfind("mat", 0) == 0) {
    bad = "bool bad = false;\n  for (int c = 0; c < v.length(); ++c) bad = bad || any(isnan(v[c])) || any(isinf(v[c]));\n  if (";
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

bool StageEmitter::is_trace_site(const Expr* e) const {
  if (!trace_ || !e || !traceable(e->type)) return false;
  if (e->kind == ExprKind::Assign) {
    // `x = f(y)` fails where f(y) does; only a value computed in place is tested as assigned.
    const Expr* value = static_cast<const AssignExpr*>(e)->value.get();
    return static_cast<const AssignExpr*>(e)->op != AssignOp::Assign || !is_tested(value);
  }
  if (e->kind == ExprKind::Call) {
    // The author's functions are tested at their returns (and assignments), where the value is
    // born; their call would name the same value a second time.
    const CallKind kind = static_cast<const CallExpr*>(e)->call_kind;
    return kind == CallKind::Intrinsic || kind == CallKind::Method;
  }
  return false;
}

bool StageEmitter::is_tested(const Expr* e) const {
  return is_trace_site(e) ||
         (e && e->kind == ExprKind::Call && static_cast<const CallExpr*>(e)->call_kind == CallKind::Function);
}

Code StageEmitter::expr(const Expr* e) {
  if (!is_trace_site(e)) return expr_untraced(e);
  if (e->kind == ExprKind::Assign) {
    const auto* assign = static_cast<const AssignExpr*>(e);
    const TraceSite::Kind kind =
        assign->op == AssignOp::Assign ? TraceSite::Kind::Assignment : TraceSite::Kind::CompoundAssignment;
    return traced(expr_untraced(e), e->type, kind, e->loc, place_name(assign->target.get()));
  }
  return traced(expr_untraced(e), e->type, TraceSite::Kind::Call, e->loc, static_cast<const CallExpr*>(e)->callee);
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

Code StageEmitter::traced(Code value, const Type& type, TraceSite::Kind kind, Loc loc, std::string what) {
  if (!trace_ || !traceable(type)) return value;
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
  if (!trace_ || !traceable(type)) return;
  main.line(traced({path}, type, TraceSite::Kind::Input, loc, semantic).text + ";");
}

void StageEmitter::trace_output(Writer& main, const std::string& path, const Type& type, const std::string& semantic,
                                Loc loc) {
  if (!trace_ || !traceable(type)) return;
  main.line(traced({path}, type, TraceSite::Kind::Output, loc, semantic).text + ";");
  // A colour below zero is a hazard of its own (the finite layer counts it), though no test
  // before the output looks at signs: most negative intermediates are meant.
  const uint32_t number = add_site(site_at(TraceSite::Kind::NegativeOutput, loc, semantic), loc);
  const std::string glsl_type = type_name(type, loc);
  const std::string negative =
      type.is_scalar() ? path + " < 0.0" : "any(lessThan(" + path + ", " + glsl_type + "(0.0)))";
  main.line("if (xs_trace_site == 0u && " + negative + ") xs_trace_site = " + std::to_string(number) + "u;");
}

void StageEmitter::trace_record(Writer& main, Writer& interface) {
  if (!trace_) return;
  helpers_.add("xs_trace globals", kRecordGlobals);
  interface.line("layout(location = 1) out vec4 xs_trace_record;");
  // Whole numbers below 2^24, exact in a float target.
  main.line(
      "xs_trace_record = vec4(float(xs_trace_site), float(xs_trace_path & 1023u), float((xs_trace_path >> 10u) & "
      "1023u), float((xs_trace_path >> 20u) & 1023u));");
}

}  // namespace detail
}  // namespace xshade::glsl
