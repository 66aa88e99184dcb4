// Text made safe to place in HTML or XML, and relative file paths made safe to place in a URL.
//
// Scene names, descriptions, driver strings and compiler messages are user input and may hold
// anything, including bytes that are not UTF-8 or control characters that XML 1.0 forbids; an
// escaped string is always well-formed in both languages.
#pragma once

#include <string>
#include <string_view>

namespace xshade {

// For element content: & < > " ' become references; invalid UTF-8 and characters XML cannot
// carry become U+FFFD. Line breaks and tabs stay as they are.
std::string escape_text(std::string_view text);

// For an attribute value in double or single quotes: escape_text, and line breaks and tabs as
// character references so that a parser's attribute normalisation keeps them.
std::string escape_attribute(std::string_view text);

// A relative file path as a URL path: every byte but unreserved characters and '/' is
// percent-encoded, so that a '#', '?', '%' or space in a scene name still links to its file.
std::string url_path(std::string_view relative_path);

}  // namespace xshade
