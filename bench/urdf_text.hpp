// URDF text edits for the comparators: drop geometry (meshes that MuJoCo and DART would try to
// open; geometry does not enter the dynamics), and hang the root link from a "world" link by a
// floating joint (how MuJoCo's URDF reader makes a free joint).
#pragma once

#include <string>

namespace bench {

std::string read_file(const std::string& path);
void write_file(const std::string& path, const std::string& text);

/// The text without its <visual> and <collision> elements.
std::string without_geometry(const std::string& urdf);

/// The text with a link "world" and a floating joint `joint_name` from it to `root_link`.
std::string with_floating_root(const std::string& urdf, const std::string& root_link, const std::string& joint_name);

}  // namespace bench
