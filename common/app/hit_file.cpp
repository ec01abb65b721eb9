#include "hit_file.h"

#include <bit>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "common/scene/whole_file.h"

namespace rt {

// The file is the structs' bytes as they lie in memory: the format is little-endian, like every machine this course
// runs on.
static_assert(std::endian::native == std::endian::little, "hit files are little-endian");

void write_hit_file(const std::string& file, const std::vector<HitRecord>& hits) {
    std::string bytes(kHitFileMagic, sizeof kHitFileMagic);
    bytes.append(reinterpret_cast<const char*>(hits.data()), hits.size() * sizeof(HitRecord));
    write_whole_file(file, bytes);   // throws with the cause (e.g. "no space left on device")
}

std::vector<HitRecord> read_hit_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + path);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bytes.size() < sizeof kHitFileMagic || std::memcmp(bytes.data(), kHitFileMagic, sizeof kHitFileMagic) != 0)
        throw std::runtime_error(path + ": not a hit file (no RTHITS header)");
    const std::size_t payload = bytes.size() - sizeof kHitFileMagic;
    if (payload % sizeof(HitRecord) != 0)
        throw std::runtime_error(path + ": truncated (" + std::to_string(payload) + " bytes is not a whole number of " +
                                 std::to_string(sizeof(HitRecord)) + "-byte records)");
    std::vector<HitRecord> hits(payload / sizeof(HitRecord));
    std::memcpy(hits.data(), bytes.data() + sizeof kHitFileMagic, payload);
    return hits;
}

}  // namespace rt
