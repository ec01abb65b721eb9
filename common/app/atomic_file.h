// Writing files so that a failure leaves nothing half-written: write to a temporary name in the same folder (same
// file system, so the final rename is atomic), then rename over the target.
#pragma once

#include <string>

namespace rt {

// ".<stem>.tmp<pid><ext>" beside `path`; the extension is kept so writers that choose a format by name still work.
std::string temporary_sibling(const std::string& path);

// Renames `temporary` to `path`; on failure removes `temporary` and throws std::runtime_error naming `path`.
void commit_temporary(const std::string& temporary, const std::string& path);

// Removes `temporary` if it exists (after a failed write).
void discard_temporary(const std::string& temporary);

}  // namespace rt
