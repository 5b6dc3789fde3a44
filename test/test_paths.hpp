// Where the tests find the package's robots. Compiled into one small object (test_paths.cpp) so
// that the source tree's absolute path reaches no other translation unit: the compiler cache then
// reuses every test's object from one clone of the repository to the next.
#pragma once

namespace sd_test {

/// The package's urdf/ directory (absolute).
const char* robots_dir();

}  // namespace sd_test
