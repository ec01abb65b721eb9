// Writing a whole file whose every failure is reported: each write() is checked (a short write on a full disk is
// an error, not a smaller file), the data is fsync'd, and close() is checked. Every writer of the course (images,
// heatmaps, stats, hit files, glTF exports) encodes into memory first and ends here, so no library that ignores a
// write error can leave a truncated file that looks written.
#pragma once

#include <string>
#include <string_view>

namespace rt {

// Replaces the contents of `path` (normally a temporary from create_temporary, atomic_file.h) with `bytes`.
// Throws std::runtime_error with the cause in lower case, e.g. "no space left on device" or "file too large".
void write_whole_file(const std::string& path, std::string_view bytes);

}  // namespace rt
