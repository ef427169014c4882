// Tribos_Registry.hpp: choice by name, done one way everywhere (Belos'
// SolverFactory is the model). Each kind of component (QP solvers, local
// solvers, outer contact algorithms, ...) keeps one registry: makers are
// registered under a name with a one-line description, the kinds of problem
// it accepts (a compatibility query, like PERMON's QPSIsQPCompatible) and
// optional aliases; a ParameterList validator, the documentation of the
// parameter and every error message list the registered names, so adding a
// component is one registration and nothing else.
#pragma once

#include <Teuchos_StandardParameterEntryValidators.hpp>

#include <algorithm>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "Tribos_Error.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {

// "CHOLMOD, KLU2, Tacho"
inline std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

template <class Product, class... Args>
class Registry {
 public:
  using Maker = std::function<RCP<Product>(Args...)>;

  // what: the kind of component, for messages ("local solver").
  explicit Registry(std::string what) : what_(std::move(what)) {}

  Registry& add(const std::string& name, Maker make, const std::string& description,
                const std::vector<std::string>& accepts = {}, const std::vector<std::string>& aliases = {}) {
    TRIBOS_REQUIRE(!has(name), what_ << " \"" << name << "\" is registered twice");
    entries_.push_back({name, std::move(make), description, accepts});
    for (const auto& a : aliases) aliases_.emplace_back(a, name);
    return *this;
  }

  bool has(const std::string& name) const { return find(name) != nullptr; }

  // The registered name that `name` is or stands for; throws naming the choices.
  const std::string& canonical(const std::string& name) const { return entry(name).name; }

  RCP<Product> create(const std::string& name, Args... args) const {
    return entry(name).make(std::forward<Args>(args)...);
  }

  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& e : entries_) out.push_back(e.name);
    return out;
  }

  // Whether the component `name` accepts a problem of kind `what` (e.g. the
  // friction law "Coulomb"), and the components that do.
  bool accepts(const std::string& name, const std::string& what) const {
    for (const auto& a : entry(name).accepts)
      if (a == what) return true;
    return false;
  }
  std::vector<std::string> accepting(const std::string& what) const {
    std::vector<std::string> out;
    for (const auto& e : entries_)
      if (accepts(e.name, what)) out.push_back(e.name);
    return out;
  }

  // The other names that are accepted (older names kept for inputs that use them).
  std::vector<std::string> aliases() const {
    std::vector<std::string> out;
    for (const auto& a : aliases_) out.push_back(a.first);
    return out;
  }

  std::string namesText() const { return joinNames(names()); }

  // "CHOLMOD (supernodal Cholesky); KLU2 (...)", for parameter documentation:
  // every component, or those of `only` when it is given.
  std::string documentation(const std::vector<std::string>& only = {}) const {
    std::string out;
    for (const auto& e : entries_)
      if (only.empty() || std::find(only.begin(), only.end(), e.name) != only.end())
        out += (out.empty() ? "" : "; ") + e.name + " (" + e.description + ")";
    return out;
  }

  // Accepts the registered names and their aliases, after `choices` that the
  // owner of the parameter resolves itself (e.g. "Auto").
  RCP<Teuchos::StringValidator> validator(const std::vector<std::string>& choices = {}) const {
    Teuchos::Array<std::string> valid(choices.begin(), choices.end());
    for (const auto& e : entries_) valid.push_back(e.name);
    for (const auto& a : aliases_) valid.push_back(a.first);
    return rcp(new Teuchos::StringValidator(valid));
  }

 private:
  struct Entry {
    std::string name;
    Maker make;
    std::string description;
    std::vector<std::string> accepts;
  };
  const Entry* find(const std::string& name) const {
    for (const auto& a : aliases_)
      if (a.first == name) return find(a.second);
    for (const auto& e : entries_)
      if (e.name == name) return &e;
    return nullptr;
  }
  const Entry& entry(const std::string& name) const {
    const Entry* e = find(name);
    TRIBOS_REQUIRE(e != nullptr, "unknown " << what_ << " \"" << name << "\"; registered: " << namesText());
    return *e;
  }

  std::string what_;
  std::vector<Entry> entries_;
  std::vector<std::pair<std::string, std::string>> aliases_;  // alias, name
};

}  // namespace Tribos
