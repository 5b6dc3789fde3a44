#include "urdf_text.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace bench {

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read '" + path + "'");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw std::runtime_error("cannot write '" + path + "'");
}

namespace {

/// Removes every element <tag …>…</tag> or <tag …/> (such elements do not nest in URDF).
std::string remove_elements(const std::string& text, const std::string& tag) {
  std::string out;
  std::size_t pos = 0;
  for (;;) {
    std::size_t start = text.find("<" + tag, pos);
    while (start != std::string::npos) {  // "<visual" must not match "<visualisation"
      const char next = text[start + tag.size() + 1];
      if (next == ' ' || next == '>' || next == '/' || next == '\n' || next == '\t' || next == '\r') break;
      start = text.find("<" + tag, start + 1);
    }
    if (start == std::string::npos) break;
    out.append(text, pos, start - pos);
    const std::size_t tag_end = text.find('>', start);
    if (tag_end == std::string::npos) throw std::runtime_error("unterminated <" + tag + "> element");
    if (text[tag_end - 1] == '/') {
      pos = tag_end + 1;
    } else {
      const std::size_t close = text.find("</" + tag + ">", tag_end);
      if (close == std::string::npos) throw std::runtime_error("unterminated <" + tag + "> element");
      pos = close + tag.size() + 3;
    }
  }
  out.append(text, pos, std::string::npos);
  return out;
}

}  // namespace

std::string without_geometry(const std::string& urdf) { return remove_elements(remove_elements(urdf, "visual"), "collision"); }

std::string with_floating_root(const std::string& urdf, const std::string& root_link, const std::string& joint_name) {
  const std::size_t end = urdf.rfind("</robot>");
  if (end == std::string::npos) throw std::runtime_error("no </robot> in the URDF");
  return urdf.substr(0, end) + "  <link name=\"world\"/>\n  <joint name=\"" + joint_name +
         "\" type=\"floating\"><parent link=\"world\"/><child link=\"" + root_link + "\"/></joint>\n" + urdf.substr(end);
}

}  // namespace bench
