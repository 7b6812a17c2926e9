#pragma once
// Reading plain-text number files (TUM trajectories, route and path files): the file's lines
// with `#` comments, carriage returns and blank lines dropped, each split into finite numbers,
// and errors that name the file and line.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace retrace::io::internal {

/// One line of a text file that holds something besides spaces, tabs and comments.
struct TextLine {
  int line = 0;      // 1-based line number in the file
  std::string text;  // without the `#` comment and the trailing '\r'
};

/// Throws core::IoError "<path>:<line>: <what>".
[[noreturn]] void FailAt(const std::filesystem::path& path, int line, const std::string& what);

/// `token` in single quotes, for error messages.
std::string Quoted(std::string_view token);

/// Splits `text` at spaces and tabs into finite numbers; throws core::IoError naming `path` and
/// `line` on a token that is not a number or not finite. Empty for a blank `text`.
std::vector<double> ParseNumbers(std::string_view text, const std::filesystem::path& path,
                                 int line);

/// The lines of the file at `path` that are not blank once a `#` comment and a trailing '\r'
/// (CRLF files) are removed, in file order. Throws core::IoError if the file cannot be opened
/// or read.
std::vector<TextLine> ReadTextLines(const std::filesystem::path& path);

}  // namespace retrace::io::internal
