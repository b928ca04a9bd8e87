// Reading text files for the parsers in io: whole-file reads with errors that name the file, and a
// line tokenizer that knows where it is (so a parse error can say "line 12").
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace vesalius::io {

// The whole file; throws BadInput naming `path` if it cannot be opened or read.
std::string readTextFile(const std::string& path);
// The whole file as bytes (same errors).
std::string readBinaryFile(const std::string& path);

// Splits text into lines (LF or CRLF) and lines into whitespace-separated tokens; tracks line numbers.
class LineReader {
 public:
  LineReader(std::string_view text, std::string source);

  // Next line with its trailing "\r" removed; false at the end.
  bool next(std::string_view& line);
  int lineNumber() const { return line_; }  // 1-based number of the line last returned
  const std::string& source() const { return source_; }

  // Throws BadInput "<source>: line N: <problem>".
  [[noreturn]] void fail(const std::string& problem) const;

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  int line_ = 0;
  std::string source_;
};

std::vector<std::string_view> splitWhitespace(std::string_view line);
std::string_view trim(std::string_view s);
// Strict number parsing: the whole token must be a finite number, else BadInput via `reader.fail`.
double parseDouble(std::string_view token, const LineReader& reader, const char* what);
long long parseInteger(std::string_view token, const LineReader& reader, const char* what);

}  // namespace vesalius::io
