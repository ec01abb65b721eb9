// The glTF loader + flatten fuzz target. LLVMFuzzerTestOneInput has libFuzzer's signature, so the same
// file also links with -fsanitize=fuzzer where clang is available; fuzz_gltf_driver.cpp is the standalone driver.
#pragma once

#include <cstddef>
#include <cstdint>

// Loads `data` as a glTF file (.glb when it starts with "glTF", else .gltf) and flattens its default scene at two
// times. A SceneError is the expected answer to bad input; any other exception, crash or sanitizer report is a
// finding. Returns 0, as libFuzzer requires.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

// How many inputs so far loaded and flattened without a SceneError (a fuzzer that only ever reaches the first error
// tests little).
std::size_t fuzz_gltf_accepted_inputs();
