#pragma once
// Reading a whole file into memory, with the errors every reader of the project gives.

#include <filesystem>
#include <string>

namespace retrace::io {

/// The bytes of the file at `path`. Throws core::IoError "<path>: cannot open file" (missing,
/// unreadable or a folder) or "<path>: cannot read file".
std::string ReadFileBytes(const std::filesystem::path& path);

}  // namespace retrace::io
