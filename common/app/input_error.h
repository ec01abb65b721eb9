// Errors the user can fix (bad options, bad scene, bad output path, an image too large for the device): the driver
// (driver.cpp, run_stage) prints them as one line "<stage>: error: ..." and exits with code 2. Thrown from anywhere
// below the driver, including a renderer's render() before it draws anything.
#pragma once

#include <stdexcept>

namespace rt {

struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace rt
