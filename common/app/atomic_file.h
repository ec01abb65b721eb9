// Writing files so that a failure or an interrupt leaves nothing half-written: write to a temporary file in the same
// folder (same file system, so the final rename is atomic), then rename it over the target.
//
// Temporaries are created exclusively (O_CREAT|O_EXCL|O_NOFOLLOW) under an unpredictable name, so a planted file or
// symbolic link is never written through, and two runs writing the same target never share a temporary. Every live
// temporary is remembered so that SIGINT, SIGTERM and SIGHUP remove it (see install_temporary_cleanup).
#pragma once

#include <string>

namespace rt {

// Creates a new, empty file ".<stem>.tmp-<random><ext>" beside `path` (the extension is kept so writers that choose
// a format by name still work) and returns its name. Throws std::runtime_error "cannot write <path>: <reason>".
std::string create_temporary(const std::string& path);

// The former name of create_temporary (stats.cpp uses it): the file now exists when this returns.
inline std::string temporary_sibling(const std::string& path) { return create_temporary(path); }

// Renames `temporary` to `path`; on failure removes `temporary` and throws std::runtime_error naming `path`.
void commit_temporary(const std::string& temporary, const std::string& path);

// Removes `temporary` if it exists (after a failed write) and forgets it.
void discard_temporary(const std::string& temporary);

// Also removes `path` on SIGINT/SIGTERM/SIGHUP until forget_on_interrupt(path): for files a library writes beside
// ours under its own name.
void remove_on_interrupt(const std::string& path);
void forget_on_interrupt(const std::string& path);

// Installs (once) the handler of SIGINT, SIGTERM and SIGHUP that unlinks every live temporary, then dies of the same
// signal. A signal the parent ignores (nohup) stays ignored.
void install_temporary_cleanup();

}  // namespace rt
