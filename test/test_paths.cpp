#include "test_paths.hpp"

namespace sd_test {

const char* robots_dir() { return SD_ROBOTS_DIR; }

}  // namespace sd_test
