#pragma once
// Typed exceptions for bad user input. They are caught at the command boundary, printed as
// one line and turned into exit code 2. Expected per-tick outcomes are return values instead.

#include <stdexcept>
#include <string>

namespace retrace::core {

/// Base of every user-facing error.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A configuration value is unknown, malformed or out of range.
/// `key_path()` is the dotted path of the offending key ("lidar.beams", "walls[2].width");
/// `located()` says whether the message already names the file and line.
class ConfigError : public Error {
 public:
  ConfigError(std::string key_path, const std::string& message, bool located = false)
      : Error(located || key_path.empty() ? message : key_path + ": " + message),
        key_path_(std::move(key_path)),
        detail_(message),
        located_(located) {}
  const std::string& key_path() const { return key_path_; }
  /// The message without the key path prefix.
  const std::string& detail() const { return detail_; }
  bool located() const { return located_; }

 private:
  std::string key_path_;
  std::string detail_;
  bool located_;
};

/// A file is missing, unreadable, malformed or cannot be written.
class IoError : public Error {
 public:
  using Error::Error;
};

/// The world is inconsistent: empty, a robot inside a wall, a route through a building.
class WorldError : public Error {
 public:
  using Error::Error;
};

/// The caller asked long work to stop (Ctrl-C in the Python module: ProgressSink::Cancelled in
/// bench/engine/progress.hpp). Not a core::Error: it is no bad input, and what names, wraps or
/// turns errors into warnings (an episode's job name, FinishOrWarn) must let it pass unchanged.
class Interrupted : public std::runtime_error {
 public:
  Interrupted() : std::runtime_error("interrupted") {}
};

}  // namespace retrace::core
