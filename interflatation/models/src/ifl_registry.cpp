// Model kinds of .ifl files (models/ifl_registry.h).
#include "interlin/interflatation/models/ifl_registry.h"

#include "interlin/interflatation/input_error.h"
#include "interlin/interflatation/models/normalized_model.h"
#include "interlin/interflatation/models/section_body.h"

#include <map>
#include <mutex>
#include <stdexcept>

namespace interlin {

namespace {

struct Registry {
  std::mutex lock;
  std::map<std::string, IflLoader> loaders;
};

// Converts a library's std::invalid_argument about a block's data into the block's InputError.
template <class F>
ImplicitFunction checked(const IflBlock& b, F make) {
  try {
    return make();
  } catch (const std::invalid_argument& e) {
    b.fail(e.what());
  }
}

Registry& registry() {
  static Registry r;
  static const bool builtins = [] {
    std::map<std::string, IflLoader>& x = r.loaders;
    x["section_body"] = [](const IflBlock& b, const std::string&) {
      const SectionBodyModel m = section_body_from_ifl(b);
      return checked(b, [&] { return section_body_function(m); });
    };
    x["normalized_rf"] = [](const IflBlock& b, const std::string&) {
      const NormalizedModel m = normalized_model_from_ifl(b);
      return checked(b, [&] { return normalized_model_function(m); });
    };
    return true;
  }();
  (void)builtins;
  return r;
}

} // namespace

void register_ifl_kind(const std::string& kind, IflLoader loader) {
  IflBlock probe; // the kind must be a valid block kind
  try {
    probe.set(kind, 0);
  } catch (const std::invalid_argument&) {
    throw std::invalid_argument("register_ifl_kind: '" + kind + "' is not a valid kind name");
  }
  Registry& r = registry();
  const std::lock_guard<std::mutex> g(r.lock);
  if (!r.loaders.emplace(kind, std::move(loader)).second)
    throw std::invalid_argument("register_ifl_kind: kind '" + kind + "' is registered already");
}

std::vector<std::string> ifl_kinds() {
  Registry& r = registry();
  const std::lock_guard<std::mutex> g(r.lock);
  std::vector<std::string> k;
  for (const auto& [name, loader] : r.loaders)
    k.push_back(name);
  return k;
}

ImplicitFunction load_ifl_model(const IflBlock& model, const std::string& path) {
  IflLoader loader;
  {
    Registry& r = registry();
    const std::lock_guard<std::mutex> g(r.lock);
    const auto it = r.loaders.find(model.kind);
    if (it != r.loaders.end())
      loader = it->second;
  }
  if (!loader) {
    std::string known;
    for (const std::string& k : ifl_kinds())
      known += (known.empty() ? "" : ", ") + k;
    model.fail("unknown model kind (known: " + known + ")");
  }
  return loader(model, path);
}

ImplicitFunction load_ifl(const std::string& path) {
  return load_ifl_model(read_ifl(path), path);
}

} // namespace interlin
