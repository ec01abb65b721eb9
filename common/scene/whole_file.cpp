#include "whole_file.h"

#include <cctype>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

namespace rt {

namespace {

[[noreturn]] void fail(int error) {
    std::string cause = std::strerror(error);
    if (!cause.empty()) cause[0] = char(std::tolower(static_cast<unsigned char>(cause[0])));
    throw std::runtime_error(cause);
}

}  // namespace

void write_whole_file(const std::string& path, std::string_view bytes) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0666);
    if (fd < 0) fail(errno);
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {   // write() returns 0 only for an empty request; a short write is retried, then fails here
            const int error = n < 0 ? errno : EIO;
            ::close(fd);
            fail(error);
        }
        done += std::size_t(n);
    }
    // Delayed allocation (ext4, NFS, overlay) reports a full disk only at fsync or close.
    if (::fsync(fd) != 0 && errno != EINVAL) {   // EINVAL: a special file without fsync
        const int error = errno;
        ::close(fd);
        fail(error);
    }
    if (::close(fd) != 0 && errno != EINTR) fail(errno);
}

}  // namespace rt
