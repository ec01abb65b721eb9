// The files one run writes (--out frames, --stats, --export, ...): checked before rendering, written through
// temporaries, and all removed again when the run fails.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace rt {

// One file a run will write, and the option that named it (for messages): {"--out", "anim_0003.png"}.
struct OutputPath {
    std::string option;
    std::string path;
};

// Refuses, with std::invalid_argument and one line naming the option, the path and the problem, an output that
//  - is in a folder that does not exist or cannot be reached (too long, a loop of links, a path under a file),
//  - exists as a symbolic link, a folder, a FIFO/socket/device or a read-only file (left alone, never replaced),
//  - is one of `inputs` (the files the scene was read from; hard links and links to them included), or
//  - is the same file as another output.
// Never throws std::filesystem::filesystem_error.
void check_outputs(const std::vector<OutputPath>& outputs, const std::vector<std::string>& inputs);

// The outputs of one run. Each is written to its own exclusive temporary and renamed over its target once complete.
// If the run does not reach keep() (an exception, a failed write), the destructor removes every temporary and every
// output this run already completed; SIGINT/SIGTERM/SIGHUP remove the temporaries (see atomic_file.h).
class RunOutputs {
public:
    RunOutputs();
    ~RunOutputs();
    RunOutputs(const RunOutputs&) = delete;
    RunOutputs& operator=(const RunOutputs&) = delete;

    // Creates the temporary of `output` now, proving before rendering that it can be written. Throws
    // std::invalid_argument "--out x.png: Permission denied" (the user's path, never the temporary's).
    void reserve(const OutputPath& output);
    // write(file) fills the (reserved or new) temporary `file`; it is then renamed over the target. Throws
    // std::runtime_error naming the user's path when either fails.
    void write(const OutputPath& output, const std::function<void(const std::string& file)>& write);
    // The run succeeded: keep the outputs.
    void keep();

private:
    struct Pending {
        OutputPath output;
        std::string temporary;
    };
    std::vector<Pending> pending_;          // reserved temporaries
    std::vector<std::string> completed_;    // targets this run has written
    bool kept_ = false;
};

}  // namespace rt
