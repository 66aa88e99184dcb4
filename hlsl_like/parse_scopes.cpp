// The parser's scopes of names: which struct and typedef names a variable hides, and where.
//
// The parser tells a declaration from an expression by asking whether a word names a type, so
// it must know when a word stops naming one. As in C (and DXC, which is C++), a variable,
// parameter or global named like a type hides the type from the end of its declarator to the
// end of its scope: Unity's URP writes `VertexPositionInputs Attributes = ...;` beside its
// `struct Attributes`, and reads `Attributes.positionCS` after it.
#include <string>

#include "hlsl_like/parser_internal.h"

namespace xshade::hlsl::parser_detail {

// Only a word that names a type is recorded: any other name hides nothing the parser asks about.
void Parser::hide_type_name(size_t name_index) {
  const uint32_t number = word_number(name_index);
  Word& word = words_[number];
  if (word.user_type < 0) return;
  hidden_log_.push_back({number, word.hidden_by});
  word.hidden_by = uint32_t(name_index + 1);
}

void Parser::restore_hidden(size_t mark) {
  while (hidden_log_.size() > mark) {
    const HiddenWord& entry = hidden_log_.back();
    words_[entry.word].hidden_by = entry.previous;
    hidden_log_.pop_back();
  }
}

bool Parser::report_hidden_type(size_t index) {
  const Word& word = word_at(index);
  if (word.user_type < 0 || word.hidden_by == 0) return false;
  const std::string name = in_quotes(tok(index).text);
  const Token& variable = tok(word.hidden_by - 1);
  if (error_at(index, name + " is a variable here, not a type: a variable named like a type hides it to the end of "
                             "the variable's scope; rename the variable to use the type here"))
    diagnostics_.note(variable.loc, "the variable " + name + " that hides the type is declared here");
  return true;
}

// The body of an if, else, while, do or for is a scope of its own, as in C, even unbraced.
StmtPtr Parser::parse_substatement() {
  NameScope scope(*this);
  return parse_statement();
}

}  // namespace xshade::hlsl::parser_detail
