// The driver every stage's main() calls: shared command line, scene loading, frames, image and stats output.
#pragma once

#include <string>

#include "renderer.h"

namespace rt {

// Exit codes: 0 success, 2 bad input (options, scene, output path), 1 a failure while rendering.
// Errors are one line on stderr: "<stage>: error: <message>".
int run_stage(const std::string& stage, int argc, char** argv, Renderer& renderer);

// `text` with its control characters written as escapes (\n, \r, \t, \xNN), so a message naming a file whose name
// holds a newline is still one line.
std::string one_printable_line(const std::string& text);

}  // namespace rt
