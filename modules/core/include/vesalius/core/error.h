// The one small error hierarchy of Vesalius (DESIGN.md, "Errors").
//
// Every failure a user can cause or meet is one of three kinds, each with its own process exit code:
//   BadInput          a file or value we were given is wrong (exit 3); the message names the file.
//   NumericalFailure  a solver did not converge or met a degenerate case (exit 4).
//   UsageError        the command line asks for something impossible (exit 2).
// Messages are one line, meant to be printed as they are.
#pragma once

#include <stdexcept>
#include <string>

namespace vesalius {

enum ExitCode : int { kExitOk = 0, kExitUsage = 2, kExitBadInput = 3, kExitNumerical = 4 };

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  virtual int exitCode() const = 0;
};

class BadInput : public Error {
 public:
  // `file` may be empty when the bad value did not come from a file.
  BadInput(const std::string& file, const std::string& problem)
      : Error(file.empty() ? problem : file + ": " + problem), file_(file), problem_(problem) {}
  int exitCode() const override { return kExitBadInput; }
  const std::string& file() const { return file_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string file_, problem_;
};

class NumericalFailure : public Error {
 public:
  using Error::Error;
  int exitCode() const override { return kExitNumerical; }
};

class UsageError : public Error {
 public:
  using Error::Error;
  int exitCode() const override { return kExitUsage; }
};

}  // namespace vesalius
