#include "io/read_file.hpp"

#include <fstream>
#include <sstream>
#include <system_error>

#include "core/errors.hpp"

namespace retrace::io {

std::string ReadFileBytes(const std::filesystem::path& path) {
  std::error_code ec;
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path, ec)) {
    throw core::IoError(path.string() + ": cannot open file");
  }
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) throw core::IoError(path.string() + ": cannot read file");
  return std::move(bytes).str();
}

}  // namespace retrace::io
