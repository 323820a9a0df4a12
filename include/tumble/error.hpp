#pragma once
/// User-facing failures. A `tumble::Error` is a mistake in what the user gave (scene, mesh,
/// command line: exit code 2) or a failure of the environment (no GL, cannot write: exit 3).
/// It carries the place in a file when there is one, and is surfaced once, at the top, by the CLI.
/// Programming mistakes are asserts, never Errors.

#include <stdexcept>
#include <string>

namespace tumble {

enum class ErrorKind {
  BadInput = 2,     ///< scene file, mesh file, command line
  Environment = 3,  ///< no usable EGL/GL, encoder missing, cannot write output
};

/// A place in a source file; `line` and `column` are 1-based, 0 when unknown.
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;
};

class Error : public std::runtime_error {
 public:
  Error(ErrorKind kind, std::string message, SourceLocation where = {})
      : std::runtime_error(message), kind_(kind), where_(std::move(where)) {}

  ErrorKind kind() const { return kind_; }
  int exit_code() const { return static_cast<int>(kind_); }
  const SourceLocation& where() const { return where_; }
  /// `FILE:LINE:COLUMN: message` when the error points into a file, else the message alone.
  std::string describe() const;

 private:
  ErrorKind kind_;
  SourceLocation where_;
};

inline std::string Error::describe() const {
  if (where_.file.empty()) return what();
  std::string s = where_.file;
  if (where_.line > 0) {
    s += ':' + std::to_string(where_.line);
    if (where_.column > 0) s += ':' + std::to_string(where_.column);
  }
  return s + ": " + what();
}

}  // namespace tumble
