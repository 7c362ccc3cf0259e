// Line-oriented tokenizer shared by the TetGen and Gmsh readers.
//
// Splits a buffer into lines (LF or CRLF), drops `#` comments and blank lines, and hands out
// whitespace-separated tokens with the 1-based line number they came from, so that every parse
// error can say `file:line`. Numbers are parsed strictly: a token must be a whole number or a
// finite float, never garbage with a numeric prefix.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace galsculpt {

struct TextLine {
  int number = 0;                        // 1-based line number in the file
  std::vector<std::string_view> tokens;  // whitespace-separated, comments removed
};

class TextLines {
 public:
  // `commentChar` starts a comment that runs to the end of the line; 0 disables comments.
  TextLines(std::string file, std::string_view buffer, char commentChar = '#');

  bool atEnd() const { return next_ >= lines_.size(); }
  // Non-empty lines not yet handed out.
  size_t remaining() const { return lines_.size() - next_; }
  // The next non-empty line; throws InputError "unexpected end of file" past the end.
  const TextLine& next(const std::string& expecting);
  const TextLine* peek() const { return atEnd() ? nullptr : &lines_[next_]; }
  int lastLineNumber() const { return lastLine_; }
  const std::string& file() const { return file_; }

  // Strict parses; on failure throw InputError("file:line: expected <what>, got '<token>'").
  long long parseInt(const TextLine& line, size_t token, const char* what) const;
  double parseDouble(const TextLine& line, size_t token, const char* what) const;
  [[noreturn]] void fail(int line, const std::string& message) const;

 private:
  std::string file_;
  std::vector<TextLine> lines_;
  size_t next_ = 0;
  int lastLine_ = 0;
};

}  // namespace galsculpt
