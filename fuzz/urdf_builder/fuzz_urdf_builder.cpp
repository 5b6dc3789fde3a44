// libFuzzer target: URDF text → build_model_from_urdf_string → the algorithms.
// The input is the URDF text itself (so the corpus is plain URDF files). A hash of it chooses a
// fixed or floating base and seeds three states of moderate size. The builder must either
// return a model that satisfies the Model invariants or throw ModelError with a message; on a
// model, every algorithm must return finite numbers or throw with a message (fuzz_common.hpp).
#include <sanitizer/lsan_interface.h>
#include <tinyxml.h>

#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "../fuzz_common.hpp"
#include "spatial_dynamics/urdf/model_builder.hpp"

namespace {

/// Whether the <joint> elements connect the links into a directed cycle (a link its own ancestor).
/// urdfdom (3.0, Debian 12) links each parent to its children with shared_ptrs before it finds
/// that the tree has no single root, and the cycle leaks when it rejects the document. That leak is
/// urdfdom's, not ours: for such inputs the leak checker is paused (the builder must still reject
/// them with a ModelError).
bool links_form_a_cycle(const std::string& xml) {
  // TinyXML reads past the end of text that ends in a cut-off UTF-8 character (which the builder
  // rejects before parsing); trailing NULs keep this pre-parse inside its buffer.
  const std::string padded = xml + std::string(16, '\0');
  TiXmlDocument doc;
  doc.Parse(padded.c_str());
  const TiXmlElement* robot = doc.FirstChildElement("robot");
  if (!robot) return false;
  std::map<std::string, std::vector<std::string>> children;
  for (const TiXmlElement* j = robot->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
    const TiXmlElement* parent = j->FirstChildElement("parent");
    const TiXmlElement* child = j->FirstChildElement("child");
    const char* p = parent ? parent->Attribute("link") : nullptr;
    const char* c = child ? child->Attribute("link") : nullptr;
    if (p && c) children[p].push_back(c);
  }
  std::set<std::string> done, on_path;
  std::function<bool(const std::string&)> cyclic = [&](const std::string& link) {
    if (on_path.count(link)) return true;
    if (done.count(link)) return false;
    on_path.insert(link);
    for (const std::string& c : children[link])
      if (cyclic(c)) return true;
    on_path.erase(link);
    done.insert(link);
    return false;
  };
  for (const auto& entry : children)
    if (cyclic(entry.first)) return true;
  return false;
}

std::uint64_t fnv1a(const std::uint8_t* data, std::size_t size) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::size_t k = 0; k < size; ++k) h = (h ^ data[k]) * 1099511628211ull;
  return h;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace sd = spatial_dynamics;
  const std::string urdf(reinterpret_cast<const char*>(data), size);
  std::mt19937_64 rng(fnv1a(data, size));
  sd::ModelBuildOptions options;
  options.floating_base = rng() & 1;

  const bool cyclic = links_form_a_cycle(urdf);
  sd::Model<double> model;
  try {
    if (cyclic) __lsan_disable();
    model = sd::build_model_from_urdf_string(urdf, options);
    if (cyclic) __lsan_enable();
  } catch (const sd::ModelError& e) {
    if (cyclic) __lsan_enable();
    if (e.what()[0] == '\0') sd_fuzz::finding("ModelError without a message");
    return 0;
  }  // any other exception escapes: the builder's errors are ModelErrors
  if (cyclic) sd_fuzz::finding("a URDF whose links form a cycle was accepted");
  sd_fuzz::check_model(model, "built model");

  sd::Data<double> data_ws(model);
  for (int k = 0; k < 3; ++k) {
    const sd_fuzz::State state = sd_fuzz::random_state(model, rng);
    sd_fuzz::run_algorithms(model, data_ws, state, rng);
  }
  return 0;
}
