#include "vesalius/io/text_file.h"

#include "vesalius/core/error.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

namespace vesalius::io {

namespace {
std::string readFile(const std::string& path, std::ios::openmode mode) {
  std::ifstream in(path, mode);
  if (!in) throw BadInput(path, std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw BadInput(path, "read error");
  return buffer.str();
}
}  // namespace

std::string readTextFile(const std::string& path) { return readFile(path, std::ios::in); }
std::string readBinaryFile(const std::string& path) { return readFile(path, std::ios::in | std::ios::binary); }

LineReader::LineReader(std::string_view text, std::string source) : text_(text), source_(std::move(source)) {}

bool LineReader::next(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  std::size_t end = text_.find('\n', pos_);
  if (end == std::string_view::npos) end = text_.size();
  line = text_.substr(pos_, end - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  pos_ = end + 1;
  ++line_;
  return true;
}

void LineReader::fail(const std::string& problem) const {
  throw BadInput(source_, "line " + std::to_string(line_) + ": " + problem);
}

std::vector<std::string_view> splitWhitespace(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

double parseDouble(std::string_view token, const LineReader& reader, const char* what) {
  std::string text(token);
  char* end = nullptr;
  errno = 0;
  double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value))
    reader.fail(std::string("bad ") + what + " '" + text + "'");
  return value;
}

long long parseInteger(std::string_view token, const LineReader& reader, const char* what) {
  std::string text(token);
  char* end = nullptr;
  errno = 0;
  long long value = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE)
    reader.fail(std::string("bad ") + what + " '" + text + "'");
  return value;
}

}  // namespace vesalius::io
