// Tokens to a syntax tree, with error recovery.
#pragma once

#include <vector>

#include "hlsl_like/ast.h"
#include "hlsl_like/diagnostic_engine.h"
#include "hlsl_like/token.h"

namespace xshade::hlsl {

// Parses the preprocessed token stream (ending in EndOfFile). Syntax errors go to `diagnostics`;
// the parser recovers at the next `;` or `}` and goes on, so one run reports several errors.
// The tree it returns holds every declaration it could make sense of.
TranslationUnit parse(const std::vector<Token>& tokens, DiagnosticEngine& diagnostics);

// Nesting deeper than this (parentheses, blocks, statements) is an error, not a stack overflow.
inline constexpr int kMaxParseDepth = 256;

}  // namespace xshade::hlsl
