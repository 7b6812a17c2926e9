#pragma once
// What every fuzz target shares: the input is written to a file in a folder of this process, and
// the real loader reads it, as the command line would. A parser may refuse its input only with a
// core::Error (what `retrace` reports in one line with exit 2); anything else escapes the target
// and libFuzzer reports it as a finding, as it does crashes, sanitizer reports, leaks and hangs.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <string_view>

#include "core/errors.hpp"

namespace retrace::fuzz {

namespace fs = std::filesystem;

/// The folder of this process (created once, removed at exit).
inline const fs::path& Folder() {
  struct Holder {
    fs::path path;
    Holder() {
      path = fs::temp_directory_path() / ("retrace_fuzz_" + std::to_string(::getpid()));
      fs::create_directories(path);
    }
    ~Holder() {
      std::error_code ignored;
      fs::remove_all(path, ignored);
    }
  };
  static const Holder holder;
  return holder.path;
}

/// Writes `bytes` to `relative` inside Folder() (replacing it) and returns its path.
inline fs::path WriteFile(const fs::path& relative, std::string_view bytes) {
  const fs::path path = Folder() / relative;
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return path;
}

inline std::string_view AsText(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

/// Runs `parse`; a core::Error is a clean refusal.
template <typename F>
void Refusing(F&& parse) {
  try {
    parse();
  } catch (const core::Error&) {
  }
}

/// Copies the shipped `worlds/` (routes included) into Folder() once, so that a scenario at
/// Folder()/scenarios/ finds `../worlds/<name>.yaml` as the shipped scenarios do.
inline void CopyShippedWorlds() {
  static const bool copied = [] {
    fs::copy(fs::path(RETRACE_SOURCE_DIR) / "worlds", Folder() / "worlds",
             fs::copy_options::recursive | fs::copy_options::overwrite_existing);
    return true;
  }();
  (void)copied;
}

}  // namespace retrace::fuzz
