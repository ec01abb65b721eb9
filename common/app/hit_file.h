// Reading and writing --dump-hits files: the 8-byte magic of hit_record.h, then HitRecord structs.
#pragma once

#include <string>
#include <vector>

#include "common/trace/hit_record.h"

namespace rt {

// Writes the records into `file` (the driver hands it a fresh temporary and renames it: output_files.h).
// Throws std::runtime_error naming `file` on failure.
void write_hit_file(const std::string& file, const std::vector<HitRecord>& hits);

// Throws std::runtime_error naming `path` when it cannot be read, lacks the magic, or ends inside a record.
std::vector<HitRecord> read_hit_file(const std::string& path);

}  // namespace rt
