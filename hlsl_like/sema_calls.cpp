// Semantic analysis of calls: constructors, user functions (overload resolution under HLSL's
// conversion ranks), intrinsics (generic signatures from intrinsics.cpp) and texture methods.
#include <algorithm>
#include <numeric>

#include "hlsl_like/sema_internal.h"

namespace xshade::hlsl::sema_detail {

static std::string arguments_word(size_t count) { return count == 1 ? " argument" : " arguments"; }

std::string arity_list(std::vector<size_t> arities) {
  std::sort(arities.begin(), arities.end());
  arities.erase(std::unique(arities.begin(), arities.end()), arities.end());
  std::string takes;
  for (size_t i = 0; i < arities.size(); ++i) {
    if (i > 0) takes += i + 1 == arities.size() ? " or " : ", ";
    takes += std::to_string(arities[i]);
  }
  return takes + arguments_word(arities.empty() ? 0 : arities.back());
}

bool dominates(const Ranks& a, const Ranks& b) {
  bool better = false;
  for (size_t i = 0; i < a.count && i < b.count; ++i) {
    if (a.values[i] > b.values[i]) return false;
    if (a.values[i] < b.values[i]) better = true;
  }
  return better;
}

// The candidate better than every other one, or -1.
int unique_best(std::span<const Ranks> ranks) {
  for (size_t i = 0; i < ranks.size(); ++i) {
    bool best = true;
    for (size_t j = 0; j < ranks.size() && best; ++j) {
      if (i != j && !dominates(ranks[i], ranks[j])) best = false;
    }
    if (best) return int(i);
  }
  return ranks.size() == 1 ? 0 : -1;
}

namespace {

// The element type T takes when the arguments' highest is `deduced` but the signature allows
// only `set`: integers become the other integer type or float; half becomes float.
std::optional<ScalarType> fit_element(ScalarType deduced, uint8_t set) {
  auto allowed = [&](ScalarType s) { return (set & element_bit(s)) != 0; };
  if (allowed(deduced)) return deduced;
  std::span<const ScalarType> order;
  static constexpr ScalarType kFromBool[] = {ScalarType::Int, ScalarType::Uint, ScalarType::Float};
  static constexpr ScalarType kFromInt[] = {ScalarType::Uint, ScalarType::Float};
  static constexpr ScalarType kFromUint[] = {ScalarType::Int, ScalarType::Float};
  static constexpr ScalarType kFromHalf[] = {ScalarType::Float};
  switch (deduced) {
    case ScalarType::Bool: order = kFromBool; break;
    case ScalarType::Int: order = kFromInt; break;
    case ScalarType::Uint: order = kFromUint; break;
    case ScalarType::Half: order = kFromHalf; break;
    case ScalarType::Float: break;  // never silently to an integer or half
  }
  for (ScalarType s : order) {
    if (allowed(s)) return s;
  }
  return std::nullopt;
}

ScalarType fixed_element(PatternElement element, ScalarType t) {
  switch (element) {
    case PatternElement::T: return t;
    case PatternElement::Bool: return ScalarType::Bool;
    case PatternElement::Int: return ScalarType::Int;
    case PatternElement::Uint: return ScalarType::Uint;
    case PatternElement::Float: return ScalarType::Float;
  }
  return t;
}

uint8_t shape_bit(const Type& type) {
  if (type.is_matrix()) return kShapeMatrix;
  if (type.is_vector()) return kShapeVector;
  return kShapeScalar;
}

struct Candidate {
  Type params[4];  // IntrinsicSignature's parameters
  bool out[4] = {};
  Type result;
  Ranks ranks;
};

// Deduces T, N, R and C of `signature` from the arguments and ranks every argument's conversion
// into `candidate`; false when the signature does not fit.
bool bind_signature(const Sema& sema, const IntrinsicSignature& signature, const AstVector<ExprPtr>& args,
                    Candidate& candidate) {
  if (args.size() != signature.param_count) return false;
  const size_t count = args.size();
  // T's element: the highest of the (in) arguments at T-element positions.
  const Expr* element_args_storage[4];
  size_t element_arg_count = 0;
  for (size_t i = 0; i < count; ++i) {
    const ParamPattern& param = signature.params[i];
    const bool generic = param.type.element == PatternElement::T || param.type.shape == PatternShape::T;
    if (param.out || !generic) continue;
    if (!args[i]->type.is_numeric()) return false;
    if (param.type.element == PatternElement::T) element_args_storage[element_arg_count++] = args[i].get();
  }
  const std::span<const Expr* const> element_args(element_args_storage, element_arg_count);
  ScalarType element = ScalarType::Float;
  if (!element_args.empty()) {
    const std::optional<ScalarType> fitted = fit_element(sema.common_scalar(element_args), signature.elements);
    if (!fitted) return false;
    element = *fitted;
  } else if ((signature.elements & element_bit(ScalarType::Float)) == 0) {
    for (ScalarType s : {ScalarType::Uint, ScalarType::Int, ScalarType::Half, ScalarType::Bool}) {
      if (signature.elements & element_bit(s)) {
        element = s;
        break;
      }
    }
  }
  // T's shape: scalars splat, vectors take the shortest length, matrices the smallest dimensions.
  std::optional<Type> shape;
  for (size_t i = 0; i < count; ++i) {
    const ParamPattern& param = signature.params[i];
    if (param.out || param.type.shape != PatternShape::T) continue;
    shape = shape ? combine_shapes(*shape, args[i]->type, element) : Type::with_scalar(args[i]->type, element);
    if (!shape) return false;
  }
  if (!shape) shape = Type::scalar(element);
  if ((signature.shapes & shape_bit(*shape)) == 0) return false;
  // Dimension variables: a matrix fixes one; vectors bind the shortest (longer ones truncate).
  struct Dim {
    int matrix = 0;
    int vector = 0;
  };
  Dim dims[3];
  auto dim_slot = [](uint8_t dim) { return size_t(dim - kDimN); };
  for (size_t i = 0; i < count; ++i) {
    const ParamPattern& param = signature.params[i];
    if (param.out || param.type.element != PatternElement::T) continue;
    const Type& arg = args[i]->type;
    switch (param.type.shape) {
      case PatternShape::Scalar:
        if (arg.component_count() != 1) return false;
        break;
      case PatternShape::Vector:
        if (arg.is_matrix()) return false;
        if (arg.is_vector() && arg.cols() > 1 && is_dim_variable(param.type.dims[0])) {
          Dim& dim = dims[dim_slot(param.type.dims[0])];
          dim.vector = dim.vector == 0 ? int(arg.cols()) : std::min(dim.vector, int(arg.cols()));
        }
        break;
      case PatternShape::Matrix:
        if (!arg.is_matrix()) return false;
        for (int k = 0; k < 2; ++k) {
          const uint8_t pattern_dim = param.type.dims[k];
          const int actual = int(k == 0 ? arg.rows() : arg.cols());
          if (!is_dim_variable(pattern_dim)) {
            if (actual != pattern_dim) return false;
            continue;
          }
          Dim& dim = dims[dim_slot(pattern_dim)];
          if (dim.matrix != 0 && dim.matrix != actual) return false;
          dim.matrix = actual;
        }
        break;
      default: break;
    }
  }
  int bound[3];
  for (size_t k = 0; k < 3; ++k) {
    if (dims[k].matrix != 0) {
      if (dims[k].vector != 0 && dims[k].vector < dims[k].matrix) return false;
      bound[k] = dims[k].matrix;
    } else {
      bound[k] = dims[k].vector != 0 ? dims[k].vector : 1;
    }
  }
  auto dim_value = [&](uint8_t dim) -> uint32_t {
    return is_dim_variable(dim) ? uint32_t(bound[dim_slot(dim)]) : uint32_t(dim);
  };
  auto make = [&](const TypePattern& pattern) -> Type {
    const ScalarType scalar = fixed_element(pattern.element, element);
    switch (pattern.shape) {
      case PatternShape::T: return Type::with_scalar(*shape, scalar);
      case PatternShape::Scalar: return Type::scalar(scalar);
      case PatternShape::Vector: return Type::vector(scalar, dim_value(pattern.dims[0]));
      case PatternShape::Matrix: return Type::matrix(scalar, dim_value(pattern.dims[0]), dim_value(pattern.dims[1]));
      case PatternShape::Void: return Type::void_type();
      case PatternShape::SamplerState: return Type::sampler_state();
      case PatternShape::Sampler1D: return Type::sampler(TextureShape::Tex1D);
      case PatternShape::Sampler2D: return Type::sampler2d();
      case PatternShape::Sampler3D: return Type::sampler(TextureShape::Tex3D);
      case PatternShape::SamplerCube: return Type::sampler(TextureShape::Cube);
    }
    return Type::error();
  };
  candidate.ranks.count = 0;
  candidate.result = make(signature.result);
  for (size_t i = 0; i < count; ++i) {
    const ParamPattern& param = signature.params[i];
    const Type type = make(param.type);
    const Conversion conversion =
        param.out ? classify_implicit(type, args[i]->type) : classify_implicit(args[i]->type, type);
    if (!conversion.valid) return false;
    candidate.params[i] = type;
    candidate.out[i] = param.out;
    candidate.ranks.push_back(conversion.rank);
  }
  return true;
}

// What passing `args` to `function` costs (overload_cost summed, out and inout parameters
// also for the copy back); nothing when it cannot be called with them.
std::optional<uint64_t> call_cost(const FunctionDecl& function, const AstVector<ExprPtr>& args) {
  if (args.size() > function.params.size()) return std::nullopt;
  for (size_t i = args.size(); i < function.params.size(); ++i) {
    if (!function.params[i] || !function.params[i]->default_value) return std::nullopt;
  }
  uint64_t total = 0;
  for (size_t i = 0; i < args.size(); ++i) {
    const ParamDecl* param = function.params[i].get();
    if (!param) return std::nullopt;
    const Type& arg = args[i]->type;
    const bool literal = is_literal(args[i].get());
    std::optional<uint64_t> in = 0, back = 0;
    if (param->direction != ParamDirection::Out) in = overload_cost(arg, literal, param->type);
    if (param->direction != ParamDirection::In) back = overload_cost(param->type, false, arg);
    if (!in || !back) return std::nullopt;
    total += *in + *back;
  }
  return total;
}

size_t required_params(const FunctionDecl& function) {
  size_t required = 0;
  for (size_t i = 0; i < function.params.size(); ++i) {
    if (!function.params[i] || !function.params[i]->default_value) required = i + 1;
  }
  return required;
}

}  // namespace

std::string join_types(const AstVector<ExprPtr>& args) {
  std::string text;
  for (const ExprPtr& arg : args) {
    if (!text.empty()) text += ", ";
    text += arg ? clipped(arg->type.name()) : "<error>";
  }
  return text;
}

std::string function_signature(const FunctionDecl& function) {
  std::string text = clipped(function.return_type.name()) + " " + clipped(function.name) + "(";
  for (size_t i = 0; i < function.params.size(); ++i) {
    if (i > 0) text += ", ";
    const ParamDecl* param = function.params[i].get();
    if (!param) continue;
    if (param->direction == ParamDirection::Out) text += "out ";
    if (param->direction == ParamDirection::InOut) text += "inout ";
    text += clipped(param->type.name());
  }
  return text + ")";
}

void Sema::note_fragment_only(std::string what, Loc loc) {
  if (current_info_) current_info_->fragment_only_uses.push_back({std::move(what), loc});
}

void pass_argument(Sema& sema, ExprPtr& arg, const Type& type, ParamDirection direction, size_t index,
                   std::string_view callee) {
  if (direction == ParamDirection::In) {
    sema.coerce(arg, type);
    return;
  }
  if (sema.not_assignable(arg.get())) {
    sema.diag_.error(arg->loc, "argument " + std::to_string(index + 1) + " of " + in_quotes(callee) + " is an " +
                                   (direction == ParamDirection::Out ? "out" : "inout") +
                                   " parameter and needs an assignable expression");
    return;
  }
  const Type& arg_type = arg->type;
  if (arg_type.is_error() || type.is_error() || arg_type == type) return;
  if (direction == ParamDirection::InOut) {
    const Conversion in = classify_implicit(arg_type, type);
    if (!in.valid) {
      sema.diag_.error(arg->loc, "cannot convert from " + in_quotes(arg_type.name()) + " to " + in_quotes(type.name()));
      return;
    }
    if (in.truncation) sema.diag_.warning(arg->loc, truncation_message(arg_type, type));
  }
  const Conversion back = classify_implicit(type, arg_type);
  if (!back.valid) {
    sema.diag_.error(arg->loc, "cannot convert from " + in_quotes(type.name()) + " to " + in_quotes(arg_type.name()));
    return;
  }
  if (back.truncation) sema.diag_.warning(arg->loc, truncation_message(type, arg_type));
  sema.wrap_conversion(arg, type);
}

Type Sema::analyze_call(CallExpr& expr) {
  if (expr.call_kind == CallKind::Constructor) return analyze_constructor(expr);
  if (expr.call_kind == CallKind::Printf) {
    for (ExprPtr& arg : expr.args) {
      if (!arg) continue;
      const Type type = analyze(arg.get());
      if (!type.is_error() && !type.is_scalar() && !type.is_vector())
        diag_.error(arg->loc, "printf prints scalars and vectors, not " + in_quotes(type.name()));
    }
    return Type::void_type();
  }
  Type object;
  if (expr.object) object = analyze(expr.object.get());
  bool args_ok = true;
  for (ExprPtr& arg : expr.args) {
    if (!arg) {
      args_ok = false;
      continue;
    }
    if (analyze(arg.get()).is_error()) args_ok = false;
  }
  if (expr.object) {
    if (object.is_error()) return Type::error();
    expr.call_kind = CallKind::Method;
    if (!args_ok) return Type::error();
    return analyze_method_call(expr, object);
  }
  const auto overloads = functions_.find(expr.callee);
  const std::optional<IntrinsicId> intrinsic = find_intrinsic(expr.callee);
  if (overloads == functions_.end() && !intrinsic) {
    if (all_function_names_.count(expr.callee)) {
      diag_.error(expr.loc, "function " + in_quotes(expr.callee) + " is used before its declaration");
    } else {
      std::string message = "unknown function " + in_quotes(expr.callee);
      const std::string close = suggestion(expr.callee, true);
      if (!close.empty()) message += "; did you mean " + in_quotes(close) + "?";
      diag_.error(expr.loc, message);
    }
    return Type::error();
  }
  if (!args_ok) return Type::error();
  if (overloads != functions_.end()) {
    // A user function named like an intrinsic is called when it fits; else the intrinsic is.
    bool viable = !intrinsic;
    for (const FunctionDecl* function : overloads->second) {
      if (!viable && call_cost(*function, expr.args)) viable = true;
    }
    if (viable) return analyze_function_call(expr, overloads->second);
  }
  return analyze_intrinsic_call(expr, *intrinsic);
}

Type Sema::analyze_constructor(CallExpr& expr) {
  const Type& type = expr.constructed;
  bool args_ok = true;
  for (ExprPtr& arg : expr.args) {
    if (!arg || analyze(arg.get()).is_error()) args_ok = false;
  }
  if (type.is_error()) return Type::error();
  if (!type.is_numeric()) {
    diag_.error(expr.loc, "cannot construct a value of type " + in_quotes(type.name()));
    return Type::error();
  }
  if (!args_ok) return type;
  uint64_t given = 0;
  for (ExprPtr& arg : expr.args) {
    if (!arg->type.is_numeric()) {
      diag_.error(arg->loc, "cannot use a value of type " + in_quotes(arg->type.name()) + " in a " +
                                in_quotes(type.name()) + " constructor");
      return type;
    }
    given += arg->type.component_count();
  }
  if (expr.args.size() == 1 && given == 1) {  // float3(1): a splat
    coerce(expr.args[0], type);
    return type;
  }
  if (given != type.component_count()) {
    diag_.error(expr.loc, in_quotes(type.name()) + " constructor needs " + std::to_string(type.component_count()) +
                              " components, " + std::to_string(given) + " given");
    return type;
  }
  for (ExprPtr& arg : expr.args) wrap_conversion(arg, Type::with_scalar(arg->type, type.scalar_type()));
  return type;
}

Type Sema::analyze_function_call(CallExpr& expr, const std::vector<const FunctionDecl*>& overloads) {
  const FunctionDecl* chosen = nullptr;
  if (overloads.size() == 1) {
    chosen = overloads[0];
    const size_t required = required_params(*chosen);
    const size_t total = chosen->params.size();
    if (expr.args.size() < required || expr.args.size() > total) {
      const std::string takes = required == total
                                    ? std::to_string(total) + arguments_word(total)
                                    : std::to_string(required) + " to " + std::to_string(total) + arguments_word(total);
      diag_.error(expr.loc,
                  in_quotes(expr.callee) + " takes " + takes + ", " + std::to_string(expr.args.size()) + " given");
      return Type::error();
    }
  } else {
    std::vector<const FunctionDecl*> viable;
    std::vector<uint64_t> costs;
    for (const FunctionDecl* function : overloads) {
      if (auto cost = call_cost(*function, expr.args)) {
        viable.push_back(function);
        costs.push_back(*cost);
      }
    }
    if (viable.empty()) {
      diag_.error(expr.loc, "no overload of " + in_quotes(expr.callee) + " takes (" + join_types(expr.args) + ")");
      for (const FunctionDecl* function : overloads) {
        diag_.note(function->loc, "candidate '" + function_signature(*function) + "'");
      }
      return Type::error();
    }
    // DXC's rule: the lowest cost wins; two or more at the lowest are ambiguous.
    const uint64_t lowest = *std::min_element(costs.begin(), costs.end());
    int best = -1;
    for (size_t i = 0; i < costs.size(); ++i) {
      if (costs[i] != lowest) continue;
      best = best < 0 ? int(i) : -2;
    }
    if (best < 0) {
      diag_.error(expr.loc, "ambiguous call to " + in_quotes(expr.callee) + " with (" + join_types(expr.args) + ")");
      for (size_t i = 0; i < viable.size(); ++i)
        if (costs[i] == lowest) diag_.note(viable[i]->loc, "candidate '" + function_signature(*viable[i]) + "'");
      return Type::error();
    }
    chosen = viable[size_t(best)];
  }
  for (size_t i = 0; i < expr.args.size() && i < chosen->params.size(); ++i) {
    const ParamDecl* param = chosen->params[i].get();
    if (param) pass_argument(*this, expr.args[i], param->type, param->direction, i, expr.callee);
  }
  expr.call_kind = CallKind::Function;
  expr.function = chosen;
  user_calls_.push_back(&expr);
  if (current_info_) current_info_->calls.push_back({chosen, expr.loc});
  FunctionInfo& callee = function_info_[chosen];
  if (!callee.called) {
    callee.called = true;
    callee.first_call = expr.loc;
  }
  return chosen->return_type;
}

Type Sema::analyze_intrinsic_call(CallExpr& expr, IntrinsicId id) {
  const IntrinsicInfo& info = intrinsic_info(id);
  if (!expr.object) expr.call_kind = CallKind::Intrinsic;
  expr.intrinsic = uint16_t(id);
  const std::string_view name = info.name;
  // Argument count first: the most helpful message when it is wrong.
  bool arity_matches = false;
  for (const IntrinsicSignature& signature : info.signatures)
    arity_matches |= signature.param_count == expr.args.size();
  if (!arity_matches) {
    std::vector<size_t> arities;
    for (const IntrinsicSignature& signature : info.signatures) arities.push_back(signature.param_count);
    diag_.error(expr.loc,
                in_quotes(name) + " takes " + arity_list(arities) + ", " + std::to_string(expr.args.size()) + " given");
    return Type::error();
  }
  // Only the ranks of every fitting signature are kept; the chosen one is bound again unless it
  // was the last one tried (as it is for most intrinsics, which have one signature).
  Candidate candidate;
  Ranks ranks[kMaxIntrinsicSignatures];
  size_t fitting[kMaxIntrinsicSignatures];
  size_t count = 0;
  bool last_fits = false;
  for (size_t s = 0; s < info.signatures.size() && s < kMaxIntrinsicSignatures; ++s) {
    last_fits = bind_signature(*this, info.signatures[s], expr.args, candidate);
    if (!last_fits) continue;
    ranks[count] = candidate.ranks;
    fitting[count++] = s;
  }
  if (count == 0) {
    diag_.error(expr.loc, "no overload of " + in_quotes(name) + " takes (" + join_types(expr.args) + ")");
    return Type::error();
  }
  int best = unique_best(std::span<const Ranks>(ranks, count));
  if (best < 0) {
    // No candidate beats every other: the smallest total, the table's order on a tie.
    int best_sum = 0;
    for (size_t i = 0; i < count; ++i) {
      const int sum = std::accumulate(ranks[i].values, ranks[i].values + ranks[i].count, 0);
      if (best < 0 || sum < best_sum) {
        best = int(i);
        best_sum = sum;
      }
    }
  }
  if (!(last_fits && size_t(best) + 1 == count)) {
    bind_signature(*this, info.signatures[fitting[size_t(best)]], expr.args, candidate);
  }
  const Candidate& chosen = candidate;
  for (size_t i = 0; i < expr.args.size(); ++i) {
    pass_argument(*this, expr.args[i], chosen.params[i], chosen.out[i] ? ParamDirection::Out : ParamDirection::In, i,
                  name);
  }
  if (info.fragment_only) note_fragment_only(in_quotes(name), expr.loc);
  return chosen.result;
}

}  // namespace xshade::hlsl::sema_detail
